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

// The seven texture slots of a GpuMaterial, in material_eval.glsl's order: textures0.xyzw (base
// colour, metallic-roughness, normal, occlusion), then textures1.xyz (emissive, specular,
// specular colour). The names are the shaders' (material_eval.glsl's slot names, pasted into
// GBL_RESOLVE_SLOT_<name> and GBL_MATERIAL_SLOT_<name>).
inline constexpr size_t kMaterialTextureSlotCount = 7;
inline constexpr std::array<const char*, kMaterialTextureSlotCount> kMaterialTextureSlotNames = {
    "BASE_COLOR", "METALLIC_ROUGHNESS", "NORMAL", "OCCLUSION", "EMISSIVE", "SPECULAR", "SPECULAR_COLOR"};
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
};

GpuScene uploadScene(const VulkanContext& ctx, const Scene& scene);
void destroyGpuScene(const VulkanContext& ctx, GpuScene& gpuScene);

std::vector<gpu::GpuMaterial> packMaterials(const Scene& scene);
std::vector<gpu::GpuLight> packLights(const Scene& scene);

}  // namespace gbl
