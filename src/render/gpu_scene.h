#pragma once
// A Scene uploaded to the device: geometry buffers, textures (sRGB ones as *_SRGB formats, all
// with mip chains), the material table and the light list, in the shared_types.h layouts.
#include <vector>

#include "scene.h"
#include "shared_types.h"
#include "vk_resources.h"

namespace gbl {

struct GpuScene {
    Buffer vertices;
    Buffer indices;
    Buffer materials;  // GpuMaterial[]
    Buffer lights;     // GpuLight[] (at least one element, so the binding is never empty)
    uint32_t lightCount = 0;
    std::vector<GpuImage> textures;  // at least one (a white 1x1) so the array binding is valid
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
