#pragma once
// Plain resource structs and free functions (niagara style): no ownership magic beyond a
// destroy function per type, so lifetimes stay visible at the call site.
#include <cstdint>
#include <functional>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk_context.h"

namespace gbl {

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr;  // non-null when host visible
    uint32_t memoryType = 0;  // of `memory` (its size: allocationSize), for the recycler
    VkDeviceSize allocationSize = 0;
};

struct GpuImage {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;  // all mips, all layers (cube view when cube)
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    uint32_t mipLevels = 1;
    uint32_t layers = 1;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    uint32_t memoryType = 0;  // of `memory` (its size: allocationSize), for the recycler
    VkDeviceSize allocationSize = 0;
    // Unique per createImage in this process, never 0 for a created image: the image's identity.
    // Its address is not one (the next image's struct can land where a freed one was: the
    // evaluator then kept view 0's reference statistics for view 1; compare_bands_cli_test caught
    // it under load), nor are its handles (a driver may hand a freed handle's value out again).
    uint64_t serial = 0;
};

Buffer createBuffer(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible);
void destroyBuffer(const VulkanContext& ctx, Buffer& buffer);
// Creates a device buffer holding `bytes` (through a staging copy when the memory is not mappable).
Buffer createBufferWithData(const VulkanContext& ctx, const void* bytes, VkDeviceSize size, VkBufferUsageFlags usage);

struct ImageDesc {
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    uint32_t width = 1, height = 1;
    uint32_t mipLevels = 1;
    uint32_t layers = 1;
    bool cube = false;
    VkImageUsageFlags usage = 0;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    // Only the depth aspect in the view (for sampling a depth-stencil image).
    VkImageAspectFlags viewAspect = 0;
};
GpuImage createImage(const VulkanContext& ctx, const ImageDesc& desc);
void destroyImage(const VulkanContext& ctx, GpuImage& image);
// A view of one mip level (all layers), for storage writes to a mip chain.
VkImageView createMipView(const VulkanContext& ctx, const GpuImage& image, uint32_t mip, bool asArray);

// Image layout transition of all mips and layers (synchronization2, conservative stages).
void transitionImage(VkCommandBuffer cmd, const GpuImage& image, VkImageLayout from, VkImageLayout to,
                     VkImageAspectFlags aspect = 0);
// Full memory barrier between passes: simple and correct; the passes are timed separately.
void fullBarrier(VkCommandBuffer cmd);

// Uploads tightly packed pixels into mip 0 / layer 0..layers-1 and leaves the image in `finalLayout`.
// When generateMips is set, blits the chain (the format must support linear blits).
void uploadImage(const VulkanContext& ctx, GpuImage& image, const void* pixels, VkDeviceSize bytes,
                 VkImageLayout finalLayout, bool generateMips);
// Reads back mip `mip` of every layer (tightly packed, layer after layer). Image must be in
// `currentLayout`; it is returned to it.
// rowCount > 0: only rows [firstRow, firstRow + rowCount) of the mip (a band's rows of a
// frame-sized image: the rest is neither copied nor staged).
std::vector<uint8_t> downloadImage(const VulkanContext& ctx, const GpuImage& image, VkImageLayout currentLayout,
                                   uint32_t mip = 0, VkImageAspectFlags aspect = 0, uint32_t firstRow = 0,
                                   uint32_t rowCount = 0);

// downloadImage without the returned copy: `consume` is handed the staging buffer's mapped bytes
// (tightly packed as downloadImage returns them, valid only during the call) to copy or convert
// straight into where they belong. Read-back of a 1080p frame on a CPU device: the byte vector's
// zero fill and copy were a third of the HDR image's read-back (bench/RESULTS.md).
void downloadImageWith(const VulkanContext& ctx, const GpuImage& image, VkImageLayout currentLayout,
                       const std::function<void(const uint8_t* bytes, size_t size)>& consume, uint32_t mip = 0,
                       VkImageAspectFlags aspect = 0, uint32_t firstRow = 0, uint32_t rowCount = 0);

uint32_t formatTexelSize(VkFormat format);
uint32_t mipCountFor(uint32_t width, uint32_t height);

VkSampler createSampler(const VulkanContext& ctx, VkFilter filter, VkSamplerMipmapMode mipMode,
                        VkSamplerAddressMode addressU, VkSamplerAddressMode addressV, float maxAnisotropy = 1.0f,
                        float maxLod = VK_LOD_CLAMP_NONE);  // 0: the base level only

// One submission of `segments` in order, with a timestamp before the first and after each;
// waits, and returns each segment's GPU time in ms (timestamp queries x timestampPeriod).
std::vector<double> submitTimedSegments(const VulkanContext& ctx,
                                        const std::vector<std::function<void(VkCommandBuffer)>>& segments);

}  // namespace gbl
