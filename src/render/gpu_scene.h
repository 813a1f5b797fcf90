#pragma once
// A Scene uploaded to the device: geometry buffers, textures (sRGB ones as *_SRGB formats, all
// with mip chains), the material table and the light list, in the shared_types.h layouts.
#include <array>
#include <cstdint>
#include <vector>

#include "scene.h"
#include "shared_types.h"
#include "vk_resources.h"

namespace gbl {

// The texture slots of a GpuMaterial, in material_eval.glsl's order (shared_types.h GBL_SLOT_*,
// scene.h TextureSlot): textures0.xyzw (base colour, metallic-roughness, normal, occlusion),
// textures1.xyzw (emissive, specular, specular colour, clear coat), textures2.xyzw (clear-coat
// roughness, clear-coat normal, sheen colour, sheen roughness), textures3.x (anisotropy). The names
// are the shaders' (material_eval.glsl's slot names, pasted into GBL_RESOLVE_SLOT_<name> and
// GBL_MATERIAL_SLOT_<name>).
inline constexpr size_t kMaterialTextureSlotCount = GBL_SLOT_COUNT;
inline constexpr std::array<const char*, kMaterialTextureSlotCount> kMaterialTextureSlotNames = {
    "BASE_COLOR", "METALLIC_ROUGHNESS", "NORMAL",         "OCCLUSION",   "EMISSIVE",
    "SPECULAR",   "SPECULAR_COLOR",     "CLEARCOAT",      "CLEARCOAT_ROUGHNESS",
    "CLEARCOAT_NORMAL", "SHEEN_COLOR",  "SHEEN_ROUGHNESS", "ANISOTROPY"};
static_assert(kMaterialTextureSlotCount == kTextureSlotCount, "scene.h TextureSlot and shared_types.h GBL_SLOT_*");
// A material's texture index per slot (GBL_SLOT_* order).
std::array<int, kMaterialTextureSlotCount> materialSlotTextures(const gpu::GpuMaterial& m);
// Per slot, the textures some material binds there: ascending, each in [0, textureCount) (an index
// outside it samples nothing in the resolve, as before these lists). Why: lavapipe runs both sides
// of a branch under a lane mask, so a slot's texture calls ran for every pixel. A visibility
// buffer's resolve (no non-uniform texture indexing there) tested every texture in every slot,
// and the G-buffer pass sampled every slot, bound or not; both now compile each slot to these
// (visibility_resolve.glsl, gbuffer_pass.cpp addMaterialSlotDefines).
using MaterialTextureSlots = std::array<std::vector<uint32_t>, kMaterialTextureSlotCount>;
MaterialTextureSlots materialTextureSlots(const std::vector<gpu::GpuMaterial>& materials, uint32_t textureCount);

struct GpuScene {
    Buffer vertices;
    Buffer indices;
    Buffer materials;  // GpuMaterial[]
    Buffer lights;     // GpuLight[] (at least one element, so the binding is never empty)
    uint32_t lightCount = 0;
    std::vector<GpuImage> textures;  // at least one (a white 1x1) so the array binding is valid
    MaterialTextureSlots texturesBySlot;  // materialTextureSlots of the uploaded materials
    VkSampler textureSampler = VK_NULL_HANDLE;
    // Per draw: model, normal matrix, material = (material index, draw index, firstIndex,
    // vertexOffset): pushed per draw by the G-buffer pass, and read whole by the visibility
    // buffer's resolve from drawTable (like vertices and indices, a storage buffer too).
    std::vector<gpu::DrawConstants> draws;
    Buffer drawTable;
    std::vector<Draw> drawRanges;
    std::vector<std::vector<std::pair<std::string, uint32_t>>> materialStencilValues;  // Material::stencilValues
    // What the passes compile in for this scene (sceneShaderFeatures): the layers some material has
    // (GBL_LAYERS, kLayer* bits), and whether some slot transforms its uv or samples TEXCOORD_1
    // (GBL_UV_TRANSFORMS). A scene with neither compiles the code it compiled before them.
    int layers = 0;
    bool uvTransforms = false;
};

struct SceneShaderFeatures {
    int layers = 0;
    bool uvTransforms = false;
};
SceneShaderFeatures sceneShaderFeatures(const Scene& scene);

GpuScene uploadScene(const VulkanContext& ctx, const Scene& scene);
void destroyGpuScene(const VulkanContext& ctx, GpuScene& gpuScene);

std::vector<gpu::GpuMaterial> packMaterials(const Scene& scene);
std::vector<gpu::GpuLight> packLights(const Scene& scene);

}  // namespace gbl
