#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : enable  // the visibility buffer's resolve indexes textures per pixel
// Decodes the layout's G-buffer with its generated readGBuffer() -- exactly what the lighting
// pass sees -- and writes every Surface attribute as floats, so attribute errors can be measured
// against the reference layout's decode.
// GBL_LAYERS as the C++ side passed it (a scene with layers: decode_pass.cpp reads their vec4s),
// taken before the includes: a visibility buffer's resolve (material_eval.glsl) defines it as 0.
#if defined(GBL_LAYERS) && GBL_LAYERS != 0
#define GBL_DECODE_LAYERS 1
#endif
#include "shared_types.h"
#include "surface.glsl"
#define GBUFFER_READ 1
#define GBL_GEOMETRY_MASK 1  // checkerboard chroma skips neighbours without geometry (as the lighting pass)
#include "gbuffer_wiring.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = 1) uniform sampler2D depthTexture;

#include "normal_space.glsl"
#ifdef GBL_VISIBILITY_BUFFER  // defined by a visibility-buffer layout's wiring: readGBuffer rebuilds the Surface
#include "visibility_resolve.glsl"
#endif

// The pixel's window depth: the depth attachment's, or where the ids hold it (a depth word:
// Nanite, Bevy's meshlets, which rasterise without a depth attachment) word 1 of the ids.
float gblSceneDepth(ivec2 p) {
#ifdef GBL_VIS_DEPTH_WORD
    return gblVisibilityDepth(p);
#else
    return texelFetch(depthTexture, p, 0).r;
#endif
}
bool gblHasGeometry(ivec2 p) { return gblSceneDepth(p) != frame.shading.y; }

struct DecodedPixel {
    vec4 normalRoughness;      // xyz normal, w roughness
    vec4 baseColorMetallic;    // rgb base colour, a metallic
    vec4 diffuseOcclusion;     // rgb diffuse colour, a occlusion
    vec4 specularColorSpecular;  // rgb F0, a UE4 scalar specular
    vec4 emissiveViewDepth;    // rgb emissive, a view depth (0 where uncovered)
#ifdef GBL_DECODE_LAYERS  // a scene with material layers: decode_pass.cpp reads 36 floats per pixel, not 20
    vec4 coatNormalCoat;       // xyz coat normal (world; 0 = the base normal), w coat
    vec4 sheenColorRoughness;  // rgb sheen colour, a sheen roughness
    vec4 tangentStrength;      // xyz anisotropy direction (world; 0 = none), w anisotropy strength
    vec4 coatRoughness;        // x coat roughness, yzw 0
#endif
};
#ifdef GBL_DECODE_TO_IMAGES
// The surfaces stay in device memory for the GPU evaluation (src/evaluate/): the first four
// vec4 of DecodedPixel as four RGBA32F images (emissive is not measured), whole frame.
// With GBL_LAYERS four more: the layers' vec4s (decode_pass.cpp, gpu_evaluator.h DeviceRender::layers).
#ifdef GBL_DECODE_LAYERS
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D decodedImages[8];
#else
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D decodedImages[4];
#endif
layout(push_constant) uniform Band { uint firstRow; } band;  // 0
void store(uint index, ivec2 pixel, DecodedPixel d) {
    imageStore(decodedImages[0], pixel, d.normalRoughness);
    imageStore(decodedImages[1], pixel, d.baseColorMetallic);
    imageStore(decodedImages[2], pixel, d.diffuseOcclusion);
    imageStore(decodedImages[3], pixel, vec4(d.specularColorSpecular.rgb, d.emissiveViewDepth.a));
#ifdef GBL_DECODE_LAYERS
    imageStore(decodedImages[4], pixel, d.coatNormalCoat);
    imageStore(decodedImages[5], pixel, d.sheenColorRoughness);
    imageStore(decodedImages[6], pixel, d.tangentStrength);
    imageStore(decodedImages[7], pixel, d.coatRoughness);
#endif
}
#else
// The frame is decoded in bands of rows (bounded read-back memory at 4K): this dispatch covers
// rows firstRow.. and writes them from decoded[0].
layout(set = 0, binding = 2, std430) writeonly buffer Decoded { DecodedPixel decoded[]; };
layout(push_constant) uniform Band { uint firstRow; } band;
void store(uint index, ivec2 pixel, DecodedPixel d) { decoded[index] = d; }
#endif

void main() {
    // `outPixel` in the outputs (the render's rows: frame.band), `pixel` in the frame and the
    // G-buffer; the same for a whole frame.
    ivec2 outPixel = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, int(band.firstRow));
    if (outPixel.x >= int(frame.extent.x) || outPixel.y >= int(frame.band.y)) return;
    uint index = uint(outPixel.y - int(band.firstRow)) * frame.extent.x + uint(outPixel.x);
    ivec2 pixel = outPixel + ivec2(0, int(frame.band.x));
    float depth = gblSceneDepth(pixel);
    DecodedPixel d;
    if (depth == frame.shading.y) {
        d.normalRoughness = vec4(0.0);
        d.baseColorMetallic = vec4(0.0);
        d.diffuseOcclusion = vec4(0.0);
        d.specularColorSpecular = vec4(0.0);
        d.emissiveViewDepth = vec4(0.0);
#ifdef GBL_DECODE_LAYERS
        d.coatNormalCoat = vec4(0.0);
        d.sheenColorRoughness = vec4(0.0);
        d.tangentStrength = vec4(0.0);
        d.coatRoughness = vec4(0.0);
#endif
        store(index, outPixel, d);
        return;
    }
    Surface stored = readGBuffer(pixel);
#ifdef GBL_STORES_DEPTH
    depth = stored.position.z;  // the depth the lighting pass reads: the layout's own (lighting_pass)
#endif
    Surface s = gblSurfaceFromStored(stored);  // back to gbufferlab's world (Y-up)
    // View depth from the depth value alone. A projection (perspective or orthographic, reversed
    // Z or not) gives clip z and w from view z without x or y, so -z_view = (d P33 - P32) /
    // (d P23 - P22). The way through world space and back (inverse view-projection, divide, view
    // matrix) cancelled large coordinates and lost digits: against the exact view depth of the
    // stored depth, up to 306 ulp off on lavapipe where this is within 1.2 (cpu_decode_test), and
    // 15 ulp apart between NVIDIA's decode and the CPU's.
    // Here the products are by 0 or +-1 for a perspective, so fused or not they round alike.
    float viewDepth = (depth * frame.proj[3][3] - frame.proj[3][2]) / (depth * frame.proj[2][3] - frame.proj[2][2]);
    d.normalRoughness = vec4(s.normal, s.roughness);
    d.baseColorMetallic = vec4(s.baseColor, s.metallic);
    d.diffuseOcclusion = vec4(s.diffuseColor, s.occlusion);
    d.specularColorSpecular = vec4(s.specularColor, s.specular);
    d.emissiveViewDepth = vec4(s.emissive, viewDepth);
#ifdef GBL_DECODE_LAYERS
    d.coatNormalCoat = vec4(s.coatNormal, s.coat);
    d.sheenColorRoughness = vec4(s.sheenColor, s.sheenRoughness);
    d.tangentStrength = vec4(s.anisotropyDirection, s.anisotropyStrength);
    d.coatRoughness = vec4(s.coatRoughness, 0.0, 0.0, 0.0);
#endif
    store(index, outPixel, d);
}
