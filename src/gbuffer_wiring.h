#pragma once
// What the renderer needs from a G-buffer layout: the render targets it writes (UINT formats,
// so the shader's packed words reach memory untouched), the depth format, and the GLSL that
// writes and reads them. The GLSL defines, under GBUFFER_WRITE, the fragment outputs and
// `void writeGBuffer(Surface s, ivec2 pixel)`; under GBUFFER_READ, `usampler2D`s at set 1,
// binding i (one per target) and `Surface readGBuffer(ivec2 pixel)`.
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace gbl {

struct GBufferWiring {
    std::string layoutName;
    std::vector<std::string> targetNames;
    std::vector<VkFormat> targetFormats;  // as rendered (UINT)
    VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;
    bool reversedZ = false;
    std::string glsl;
};

// The float reference: every attribute as 32-bit float bits in RGBA32_UINT targets.
GBufferWiring makeReferenceWiring();

}  // namespace gbl
