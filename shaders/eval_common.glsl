// Shared by the evaluation passes (src/evaluate/, gpu_evaluator.cpp drives them): one descriptor
// set for all of them, the push constants, the histogram bin layout and the two-stage reduction's
// first stage. Twin: src/evaluate/eval_layout.h (the same numbers on the C++ side).
#extension GL_EXT_shader_explicit_arithmetic_types_float64 : require
#ifdef EVAL_SUBGROUP_HIST
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
#endif

// Images: linear HDR RGBA32F (alpha 1 where geometry covers the pixel), and the decoded surfaces as
// four RGBA32F images: normal + roughness, base colour + metallic, diffuse colour + occlusion,
// specular colour (F0) + view depth (decode_pass.comp.glsl, GBL_DECODE_TO_IMAGES).
layout(set = 0, binding = 0, rgba32f) uniform readonly image2D refHdr;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D testHdr;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D refSurface[4];
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D testSurface[4];
// Float planes of width x height (FLIP's working planes, its maps, the reference noise).
layout(set = 0, binding = 4, std430) buffer Plane { float v[]; } planes[EVAL_PLANE_COUNT];
// Stage 1 of every reduction: one record of EVAL_FIELDS doubles per invocation.
layout(set = 0, binding = 5, std430) buffer Partials { double partials[]; };
layout(set = 0, binding = 6, std430) buffer Histograms { uint hist[]; };
// 8-bit RGBA images the report shows, one uint (R | G << 8 | B << 16) per pixel.
layout(set = 0, binding = 7, std430) buffer Out8 { uint px[]; } out8[EVAL_OUT8_COUNT];
// The colour map (256 packed RGB, image/color_map.h viridisTable) and FLIP's 1D kernels.
layout(set = 0, binding = 8, std430) readonly buffer Constants { uint viridis[256]; float kernels[]; };
layout(set = 0, binding = 9, std430) buffer Result { double result[]; };
layout(set = 0, binding = 10, std430) buffer Tiles { float tiles[]; };
// The decoded material layers (issue 40), four RGBA32F images per side (eval_layers.comp.glsl);
// the HDR images are bound in their place where a run has none (no pass reads them then).
layout(set = 0, binding = 11, rgba32f) uniform readonly image2D refLayer[4];
layout(set = 0, binding = 12, rgba32f) uniform readonly image2D testLayer[4];

layout(push_constant) uniform Push {
    uint width, height;
    uint mode;        // per pass (see each shader)
    uint flags;       // per pass
    float f0, f1, f2, f3;  // per pass
    uint u0, u1, u2, u3, u4, u5, u6, u7;  // per pass: plane indices, kernel offsets, ...
    // The rows whose pixels count (statistics, histograms, 8-bit images, tiles): all of them for a
    // whole frame; in a band (gpu_evaluator.h EvalBand) the band's rows, not its halo. width x
    // height is the bound images' size (and the planes' in use), so FLIP's filters still clamp
    // at the band image's edges, which are the frame's wherever the halo is clamped.
    uint rowFirst, rowCount;
} pc;

// Grid-stride: EVAL_INVOCATIONS invocations cover every pixel.
#define EVAL_GROUP 64
layout(local_size_x = EVAL_GROUP) in;
uint invocation() { return gl_GlobalInvocationID.x; }
// Column walks, for the separable filters' vertical passes: the image split into tasks of
// EVAL_GROUP adjacent columns by EVAL_COLUMN_STRIP rows, a workgroup per task (grid-stride over the
// tasks), each invocation walking its column down the strip. A column tap's rows are then the
// previous output row's but one, still in cache; grid-stride by pixel instead moved each
// invocation 8192 pixels on (another column every step), so every tap row was fetched anew: on
// llvmpipe the vertical passes ran 2 to 5.6 times slower than the horizontal ones.
#define EVAL_COLUMN_STRIP 32u
uint columnTasks() { return ((pc.width + EVAL_GROUP - 1u) / EVAL_GROUP) * ((pc.height + EVAL_COLUMN_STRIP - 1u) / EVAL_COLUMN_STRIP); }
// Task `task`'s column (may be >= width: no pixel) and first row.
uint columnTaskX(uint task) { return (task % ((pc.width + EVAL_GROUP - 1u) / EVAL_GROUP)) * EVAL_GROUP + gl_LocalInvocationID.x; }
uint columnTaskY(uint task) { return (task / ((pc.width + EVAL_GROUP - 1u) / EVAL_GROUP)) * EVAL_COLUMN_STRIP; }
// The pixel indices (row-major in the bound images) of the rows that count: [countedBegin, countedEnd).
uint countedBegin() { return pc.rowFirst * pc.width; }
uint countedEnd() { return (pc.rowFirst + pc.rowCount) * pc.width; }

// ---- Histograms -------------------------------------------------------------------------------
// EVAL_HIST_BINS bins for non-negative values: bin 0 holds exact 0 (and NaN/negatives), bin 1
// (0, 2^-32), bins 2 .. EVAL_HIST_BINS-2 the floats in [2^-32, 2^32) by their top bits (exponent
// and the 9 leading mantissa bits: a relative bin width of 2^-9), the last bin [2^32, +inf].
// A quantile read as the bin's midpoint is off by at most 2^-10 (0.1 %) relative.
uint histBin(float v) {
    if (!(v > 0.0)) return 0u;
    uint bits = floatBitsToUint(v);
    if (bits < 0x2F800000u) return 1u;
    if (bits >= 0x4F800000u) return EVAL_HIST_BINS - 1u;
    return 2u + ((bits - 0x2F800000u) >> 14);
}
// Where the device has subgroup vote and ballot (EVAL_SUBGROUP_HIST, eval_device.cpp), a subgroup
// whose active invocations all add to one bin adds their count once. Neighbouring pixels often
// share a bin (bin 0: the exact zeros of the background, where test and reference are equal),
// and atomics on one address serialise. The counts are the same either way. (On an H200 the
// histogram passes' 10-28 ms per call at 4K turned out to be the histograms' host memory, fixed
// in eval_device.cpp; this aggregation's own effect was not measured apart.)
void histAdd(uint h, float v) {
    uint index = h * EVAL_HIST_BINS + histBin(v);
#ifdef EVAL_SUBGROUP_HIST
    if (subgroupAllEqual(index)) {
        uint n = subgroupBallotBitCount(subgroupBallot(true));
        if (subgroupElect()) atomicAdd(hist[index], n);
        return;
    }
#endif
    atomicAdd(hist[index], 1u);
}

// ---- Tone mapping (image/tone_map.h) ------------------------------------------------------------
float acesFilmNarkowicz(float x) {
    if (!(x > 0.0)) return 0.0;
    if (x >= 8.0) return 1.0;
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
float linearToSrgb(float x) {
    x = clamp(x, 0.0, 1.0);
    if (!(x > 0.0031308)) return isnan(x) ? 0.0 : 12.92 * x;
    return 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}
// The byte toneMapToSrgb8 writes: floor(255 v + 0.5).
uvec3 toneMap8(vec3 linear, float exposure) {
    uvec3 b;
    for (int c = 0; c < 3; ++c) b[c] = uint(floor(linearToSrgb(acesFilmNarkowicz(linear[c] * exposure)) * 255.0 + 0.5));
    return b;
}
uint pack8(uvec3 c) { return c.r | (c.g << 8) | (c.b << 16) | (255u << 24); }
uint colorMap(float v, float lo, float hi) {  // applyColorMap: grey for NaN
    if (isnan(v)) return pack8(uvec3(128u));
    float range = hi - lo;
    float t = range > 0.0 ? clamp((v - lo) / range, 0.0, 1.0) : (v > lo ? 1.0 : 0.0);
    return viridis[uint(floor(t * 255.0 + 0.5))] | (255u << 24);
}
float luminance(vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }
