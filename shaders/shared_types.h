// Structs shared by C++ and GLSL: one definition, so the two sides cannot drift apart.
// Only vec4 / ivec4 / uvec4 / mat4 members, so std140, std430 and C++ layouts coincide.
#ifdef __cplusplus
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
namespace gbl::gpu {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
#endif

#define GBL_LIGHT_DIRECTIONAL 0
#define GBL_LIGHT_POINT 1
#define GBL_LIGHT_SPOT 2

#define GBL_NO_TEXTURE (-1)

struct FrameConstants {
    mat4 view;
    mat4 proj;
    mat4 viewProj;
    mat4 invViewProj;
    vec4 cameraPosition;  // xyz world, w unused
    uvec4 extent;         // x width, y height, z light count, w 1 when depth is reversed Z
    vec4 environment;     // x intensity, y prefiltered mip count, z specular IBL mode (IblMode), w diffuse IBL on
    vec4 shading;         // x Fresnel mode, y clear depth, z direct-light BRDF (brdf.glsl BRDF_*), w unused
    vec4 ibl;             // x ground-truth steps per batch / split-sum-shader samples per pixel, y environment cube face,
                          // z ground-truth random seed, w unused
    vec4 irradianceSh[9]; // rgb: SH9 of the irradiance, cosine convolution folded in (src/shading/ibl_precompute.h)
    // The rows of the frame a render covers (RenderSettings::bandFirstRow): x the frame row at row
    // 0 of the outputs (HDR image, decoded surfaces, light buffers), y their rows; z the frame index
    // of compare --temporal (RenderSettings::frameIndex: a dither that moves with time), w unused. The
    // G-buffer's images are the frame's (pixel = frame pixel). A whole frame: (0, height, 0, 0).
    uvec4 band;
};

struct GpuLight {
    vec4 positionType;    // xyz world position, w GBL_LIGHT_*
    vec4 directionRange;  // xyz direction the light travels, w range (0 = infinite)
    vec4 colorIntensity;  // rgb colour, a intensity (lux or candela)
    vec4 spotCone;        // spot: x lightAngleScale, y lightAngleOffset (KHR_lights_punctual), zw unused
};

// A material's texture slots (material_eval.glsl's order; src/render/gpu_scene.h names them).
#define GBL_SLOT_BASE_COLOR 0
#define GBL_SLOT_METALLIC_ROUGHNESS 1
#define GBL_SLOT_NORMAL 2
#define GBL_SLOT_OCCLUSION 3
#define GBL_SLOT_EMISSIVE 4
#define GBL_SLOT_SPECULAR 5
#define GBL_SLOT_SPECULAR_COLOR 6
#define GBL_SLOT_CLEARCOAT 7
#define GBL_SLOT_CLEARCOAT_ROUGHNESS 8
#define GBL_SLOT_CLEARCOAT_NORMAL 9
#define GBL_SLOT_SHEEN_COLOR 10
#define GBL_SLOT_SHEEN_ROUGHNESS 11
#define GBL_SLOT_ANISOTROPY 12
#define GBL_SLOT_COUNT 13

struct GpuMaterial {
    vec4 baseColorFactor;
    vec4 emissiveNormalScale;     // rgb emissive factor x KHR_materials_emissive_strength, a normal scale
    vec4 specularColorSpecular;   // rgb KHR_materials_specular colour, a specular factor
    vec4 metallicRoughnessOcclusion;  // x metallic, y roughness, z occlusion strength, w double sided
    ivec4 textures0;              // base colour, metallic-roughness, normal, occlusion
    ivec4 textures1;              // emissive, specular, specular colour, clear coat
    vec4 alphaMaskCutoff;         // x 1 = alphaMode MASK, y alpha cutoff, z dielectric F0 of the ior
                                  // (KHR_materials_ior: ((ior - 1) / (ior + 1))^2, 0.04 at 1.5), w the
                                  // material's layers (GBL_LAYER_* bits)
    vec4 clearcoat;               // KHR_materials_clearcoat: x clearcoatFactor, y clearcoatRoughnessFactor,
                                  // z clearcoatNormalTexture scale, w unused
    vec4 sheen;                   // KHR_materials_sheen: rgb sheenColorFactor, a sheenRoughnessFactor
    vec4 anisotropy;              // KHR_materials_anisotropy: x anisotropyStrength, yz cos, sin of
                                  // anisotropyRotation, w unused
    ivec4 textures2;              // clear-coat roughness, clear-coat normal, sheen colour, sheen roughness
    ivec4 textures3;              // anisotropy, unused x3
    // KHR_texture_transform per slot (GBL_SLOT_*): [2 slot] the 2x2 matrix rotation * scale as
    // columns (m00, m10, m01, m11); [2 slot + 1] (offset.x, offset.y, texCoord set, 1 where the
    // slot transforms its uv, else 0).
    vec4 uvTransforms[2 * GBL_SLOT_COUNT];
};

struct DrawConstants {
    mat4 model;
    vec4 normalMatrix[3];  // columns of the inverse transpose of model's 3x3 (128 bytes in all: the guaranteed minimum)
    ivec4 material;     // x material index, y draw index, z firstIndex, w vertexOffset (the last three: visibility buffer)
};

#ifdef __cplusplus
}  // namespace gbl::gpu
#endif

#ifdef __cplusplus
static_assert(sizeof(gbl::gpu::DrawConstants) <= 128, "push constants: 128 bytes is the guaranteed minimum");
#endif
