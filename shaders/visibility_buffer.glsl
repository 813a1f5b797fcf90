// The visibility buffer's id target (layout pipeline = "visibility-buffer"; Burns & Hunt, JCGT
// 2013), included by the wiring generated from the layout (src/codec/visibility_wiring.cpp), which
// first defines GBL_VIS_ID_WORDS (1: R32_UINT, 2: R32G32_UINT), GBL_VIS_TRIANGLE_BITS,
// GBL_VIS_DRAW_BITS and GBL_VIS_ALPHA_MASK_BIT (0 or 1).
// The ids fill one little-endian bit string (word 0 = bits 0..31): the triangle id from bit 0,
// the draw id above it, and the alpha-mask flag in the top bit. With 23 / 8 / 1 in R32_UINT this
// is The Forge's packVisBufData: ((drawId << 23) & 0x7F800000) | (triangleId & 0x007FFFFF), bit 31
// for alpha-tested geometry (ConfettiFX/The-Forge, Examples_3/Visibility_Buffer,
// visibilityBuffer_pass.frag). The CPU side (src/codec/visibility_wiring.h) packs the same way.
#ifndef GBL_VISIBILITY_BUFFER_GLSL
#define GBL_VISIBILITY_BUFFER_GLSL

#define GBL_VIS_BITS (32u * uint(GBL_VIS_ID_WORDS))

uint gblLowMask(uint count) { return count >= 32u ? 0xFFFFFFFFu : (1u << count) - 1u; }

// `count` (1..32) bits of `value` into the bit string at `first`, straddling the words if need be.
uvec2 gblPutBits(uvec2 words, uint value, uint first, uint count) {
    value &= gblLowMask(count);
    if (first >= 32u) return uvec2(words.x, words.y | (value << (first - 32u)));
    words.x |= value << first;
    if (first + count > 32u) words.y |= value >> (32u - first);
    return words;
}

uint gblGetBits(uvec2 words, uint first, uint count) {
    uint v = first >= 32u ? words.y >> (first - 32u) : words.x >> first;
    if (first < 32u && first + count > 32u) v |= words.y << (32u - first);
    return v & gblLowMask(count);
}

uvec2 packVisibilityIds(uint drawId, uint triangleId, bool alphaMasked) {
    uvec2 w = gblPutBits(uvec2(0u), triangleId, 0u, GBL_VIS_TRIANGLE_BITS);
    w = gblPutBits(w, drawId, GBL_VIS_TRIANGLE_BITS, GBL_VIS_DRAW_BITS);
#if GBL_VIS_ALPHA_MASK_BIT
    if (alphaMasked) w = gblPutBits(w, 1u, GBL_VIS_BITS - 1u, 1u);
#endif
    return w;
}

// x draw id, y triangle id, z alpha-mask flag.
uvec3 unpackVisibilityIds(uvec2 w) {
    uint alpha = 0u;
#if GBL_VIS_ALPHA_MASK_BIT
    alpha = gblGetBits(w, GBL_VIS_BITS - 1u, 1u);
#endif
    return uvec3(gblGetBits(w, GBL_VIS_TRIANGLE_BITS, GBL_VIS_DRAW_BITS), gblGetBits(w, 0u, GBL_VIS_TRIANGLE_BITS),
                 alpha);
}

#ifdef GBUFFER_WRITE
#if GBL_VIS_ID_WORDS == 1
layout(location = 0) out uint gblVisibilityIds;
void writeVisibilityIds(uint drawId, uint triangleId, bool alphaMasked) {
    gblVisibilityIds = packVisibilityIds(drawId, triangleId, alphaMasked).x;
}
#else
layout(location = 0) out uvec2 gblVisibilityIds;
void writeVisibilityIds(uint drawId, uint triangleId, bool alphaMasked) {
    gblVisibilityIds = packVisibilityIds(drawId, triangleId, alphaMasked);
}
#endif
#endif  // GBUFFER_WRITE

#ifdef GBUFFER_READ
// What the resolve reads besides the ids, in set 1 after the id target (renderer_passes.h,
// kVisibility*Binding): the scene's vertices (GpuScene's Vertex, 12 floats), indices, draws
// (DrawConstants: model, normal matrix, material = (material, draw, firstIndex, vertexOffset)),
// materials and textures.
layout(set = 1, binding = 0) uniform usampler2D gblIdTarget;
layout(std430, set = 1, binding = 1) readonly buffer GblVertices { float gblVertexFloats[]; };
layout(std430, set = 1, binding = 2) readonly buffer GblIndices { uint gblIndices[]; };
layout(std430, set = 1, binding = 3) readonly buffer GblDraws { DrawConstants gblDraws[]; };
layout(std430, set = 1, binding = 4) readonly buffer GblMaterials { GpuMaterial gblMaterials[]; };
layout(set = 1, binding = 5) uniform sampler2D gblTextures[TEXTURE_COUNT];

uvec3 readVisibilityIds(ivec2 pixel) { return unpackVisibilityIds(texelFetch(gblIdTarget, pixel, 0).xy); }

// Defined by visibility_resolve.glsl, which the passes include once their FrameConstants exist.
Surface readGBuffer(ivec2 pixel);
#endif  // GBUFFER_READ

#endif
