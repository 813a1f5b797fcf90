#include "vk_resources.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <stdexcept>

namespace gbl {

Buffer createBuffer(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible) {
    Buffer b;
    b.size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = std::max<VkDeviceSize>(size, 16);
    info.usage = usage;
    VK_CHECK(vkCreateBuffer(ctx.device, &info, nullptr, &b.buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx.device, b.buffer, &req);
    b.memoryType = hostVisible
        ? ctx.findMemoryType(req.memoryTypeBits,
                             VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                             VK_MEMORY_PROPERTY_HOST_CACHED_BIT)
        : ctx.findMemoryType(req.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    b.allocationSize = req.size;
    b.memory = ctx.recycler.take(b.memoryType, req.size, &b.mapped);
    if (!b.memory) {
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex = b.memoryType;
        VK_CHECK(vkAllocateMemory(ctx.device, &alloc, nullptr, &b.memory));
    }
    VK_CHECK(vkBindBufferMemory(ctx.device, b.buffer, b.memory, 0));
    if (hostVisible && !b.mapped) VK_CHECK(vkMapMemory(ctx.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
    return b;
}

void destroyBuffer(const VulkanContext& ctx, Buffer& b) {
    if (b.buffer) vkDestroyBuffer(ctx.device, b.buffer, nullptr);
    if (b.memory && !ctx.recycler.park(b.memory, b.memoryType, b.allocationSize, b.mapped, b.mapped != nullptr))
        vkFreeMemory(ctx.device, b.memory, nullptr);
    b = Buffer{};
}

Buffer createBufferWithData(const VulkanContext& ctx, const void* bytes, VkDeviceSize size, VkBufferUsageFlags usage) {
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (size) std::memcpy(staging.mapped, bytes, size);
    Buffer b = createBuffer(ctx, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, size};
        if (size) vkCmdCopyBuffer(cmd, staging.buffer, b.buffer, 1, &region);
    });
    destroyBuffer(ctx, staging);
    return b;
}

uint32_t formatTexelSize(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8_UNORM: case VK_FORMAT_R8_UINT: return 1;
        case VK_FORMAT_R8G8_UNORM: case VK_FORMAT_R8G8_UINT: case VK_FORMAT_R16_UNORM: case VK_FORMAT_R16_UINT:
        case VK_FORMAT_R16_SFLOAT: case VK_FORMAT_D16_UNORM: return 2;
        // every real format a layout may name (layouts export renders into them)
        case VK_FORMAT_R8G8B8A8_SNORM: case VK_FORMAT_B8G8R8A8_UNORM: case VK_FORMAT_B8G8R8A8_SRGB:
        case VK_FORMAT_A8B8G8R8_UNORM_PACK32: case VK_FORMAT_A8B8G8R8_SRGB_PACK32: case VK_FORMAT_A2R10G10B10_UNORM_PACK32:
            return 4;
        case VK_FORMAT_R16G16B16A16_UNORM: return 8;
        case VK_FORMAT_R8G8B8A8_UNORM: case VK_FORMAT_R8G8B8A8_SRGB: case VK_FORMAT_R8G8B8A8_UINT:
        case VK_FORMAT_A2B10G10R10_UNORM_PACK32: case VK_FORMAT_A2B10G10R10_UINT_PACK32: case VK_FORMAT_R32_UINT:
        case VK_FORMAT_R32_SFLOAT: case VK_FORMAT_D32_SFLOAT: case VK_FORMAT_R16G16_UNORM: case VK_FORMAT_R16G16_SFLOAT:
        case VK_FORMAT_R16G16_UINT: case VK_FORMAT_B10G11R11_UFLOAT_PACK32: case VK_FORMAT_X8_D24_UNORM_PACK32:
        case VK_FORMAT_D24_UNORM_S8_UINT:
            return 4;
        case VK_FORMAT_R16G16B16A16_SFLOAT: case VK_FORMAT_R16G16B16A16_UINT: case VK_FORMAT_R32G32_UINT:
        case VK_FORMAT_R32G32_SFLOAT: case VK_FORMAT_D32_SFLOAT_S8_UINT:
            return 8;
        case VK_FORMAT_R32G32B32A32_SFLOAT: case VK_FORMAT_R32G32B32A32_UINT: return 16;
        default: throw std::runtime_error("formatTexelSize: format " + std::to_string(int(format)) + " not handled");
    }
}

uint32_t mipCountFor(uint32_t width, uint32_t height) {
    uint32_t levels = 1;
    while ((std::max(width, height) >> levels) > 0) ++levels;
    return levels;
}

GpuImage createImage(const VulkanContext& ctx, const ImageDesc& desc) {
    static std::atomic<uint64_t> nextSerial{1};
    GpuImage img;
    img.serial = nextSerial.fetch_add(1, std::memory_order_relaxed);
    img.format = desc.format;
    img.extent = {desc.width, desc.height};
    img.mipLevels = desc.mipLevels;
    img.layers = desc.layers;
    img.aspect = desc.aspect;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.flags = desc.cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = desc.format;
    info.extent = {desc.width, desc.height, 1};
    info.mipLevels = desc.mipLevels;
    info.arrayLayers = desc.layers;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = desc.usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VK_CHECK(vkCreateImage(ctx.device, &info, nullptr, &img.image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx.device, img.image, &req);
    img.memoryType = ctx.findMemoryType(req.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    img.allocationSize = req.size;
    void* unusedMapping = nullptr;  // device-local images are never mapped
    img.memory = ctx.recycler.take(img.memoryType, req.size, &unusedMapping);
    if (!img.memory) {
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex = img.memoryType;
        VK_CHECK(vkAllocateMemory(ctx.device, &alloc, nullptr, &img.memory));
    }
    VK_CHECK(vkBindImageMemory(ctx.device, img.image, img.memory, 0));
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = img.image;
    view.viewType = desc.cube ? VK_IMAGE_VIEW_TYPE_CUBE
                              : (desc.layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D);
    view.format = desc.format;
    view.subresourceRange = {desc.viewAspect ? desc.viewAspect : desc.aspect, 0, desc.mipLevels, 0, desc.layers};
    VK_CHECK(vkCreateImageView(ctx.device, &view, nullptr, &img.view));
    return img;
}

VkImageView createMipView(const VulkanContext& ctx, const GpuImage& image, uint32_t mip, bool asArray) {
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image.image;
    view.viewType = asArray ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    view.format = image.format;
    view.subresourceRange = {image.aspect, mip, 1, 0, image.layers};
    VkImageView v;
    VK_CHECK(vkCreateImageView(ctx.device, &view, nullptr, &v));
    return v;
}

void destroyImage(const VulkanContext& ctx, GpuImage& img) {
    if (img.view) vkDestroyImageView(ctx.device, img.view, nullptr);
    if (img.image) vkDestroyImage(ctx.device, img.image, nullptr);
    if (img.memory && !ctx.recycler.park(img.memory, img.memoryType, img.allocationSize, nullptr, false))
        vkFreeMemory(ctx.device, img.memory, nullptr);
    img = GpuImage{};
}

void transitionImage(VkCommandBuffer cmd, const GpuImage& image, VkImageLayout from, VkImageLayout to,
                     VkImageAspectFlags aspect) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image.image;
    b.subresourceRange = {aspect ? aspect : image.aspect, 0, image.mipLevels, 0, image.layers};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void fullBarrier(VkCommandBuffer cmd) {
    VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

namespace {

// One mip level, just written by a transfer, becomes the source of the next transfer (blit).
void mipWrittenToReadable(VkCommandBuffer cmd, const GpuImage& image, uint32_t mip) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    b.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    b.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image.image;
    b.subresourceRange = {image.aspect, mip, 1, 0, image.layers};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace

void uploadImage(const VulkanContext& ctx, GpuImage& image, const void* pixels, VkDeviceSize bytes,
                 VkImageLayout finalLayout, bool generateMips) {
    Buffer staging = createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, pixels, bytes);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        transitionImage(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkBufferImageCopy region{};
        region.imageSubresource = {image.aspect, 0, 0, image.layers};
        region.imageExtent = {image.extent.width, image.extent.height, 1};
        vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        if (generateMips && image.mipLevels > 1) {
            int32_t w = int32_t(image.extent.width), h = int32_t(image.extent.height);
            for (uint32_t mip = 1; mip < image.mipLevels; ++mip) {
                mipWrittenToReadable(cmd, image, mip - 1);
                VkImageBlit blit{};
                blit.srcSubresource = {image.aspect, mip - 1, 0, image.layers};
                blit.srcOffsets[1] = {w, h, 1};
                w = std::max(w / 2, 1);
                h = std::max(h / 2, 1);
                blit.dstSubresource = {image.aspect, mip, 0, image.layers};
                blit.dstOffsets[1] = {w, h, 1};
                vkCmdBlitImage(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.image,
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
            }
            // Mips 0..n-2 are TRANSFER_SRC, the last is TRANSFER_DST: bring the last one in line.
            mipWrittenToReadable(cmd, image, image.mipLevels - 1);
            transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, finalLayout);
        } else {
            transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, finalLayout);
        }
    });
    destroyBuffer(ctx, staging);
}

std::vector<uint8_t> downloadImage(const VulkanContext& ctx, const GpuImage& image, VkImageLayout currentLayout,
                                   uint32_t mip, VkImageAspectFlags aspect, uint32_t firstRow, uint32_t rowCount) {
    std::vector<uint8_t> out;
    downloadImageWith(
        ctx, image, currentLayout, [&](const uint8_t* bytes, size_t size) { out.assign(bytes, bytes + size); }, mip,
        aspect, firstRow, rowCount);
    return out;
}

void downloadImageWith(const VulkanContext& ctx, const GpuImage& image, VkImageLayout currentLayout,
                       const std::function<void(const uint8_t* bytes, size_t size)>& consume, uint32_t mip,
                       VkImageAspectFlags aspect, uint32_t firstRow, uint32_t rowCount) {
    const VkImageAspectFlags a = aspect ? aspect : image.aspect;
    const uint32_t w = std::max(image.extent.width >> mip, 1u), mipRows = std::max(image.extent.height >> mip, 1u);
    if (rowCount && (firstRow >= mipRows || rowCount > mipRows - firstRow))
        throw std::logic_error("downloadImage: rows outside the image");
    const uint32_t h = rowCount ? rowCount : mipRows;
    uint32_t texel = formatTexelSize(image.format);
    // Depth-stencil copies: the depth aspect of D24S8 / D32S8 is copied as 4 bytes, stencil as 1.
    if (a == VK_IMAGE_ASPECT_DEPTH_BIT && (image.format == VK_FORMAT_D24_UNORM_S8_UINT ||
                                           image.format == VK_FORMAT_D32_SFLOAT_S8_UINT))
        texel = 4;
    if (a == VK_IMAGE_ASPECT_STENCIL_BIT) texel = 1;
    const VkDeviceSize bytes = VkDeviceSize(w) * h * texel * image.layers;
    Buffer staging = createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        transitionImage(cmd, image, currentLayout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.aspect);
        VkBufferImageCopy region{};
        region.imageSubresource = {a, mip, 0, image.layers};
        region.imageOffset = {0, int32_t(rowCount ? firstRow : 0), 0};
        region.imageExtent = {w, h, 1};
        vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &region);
        transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, currentLayout, image.aspect);
    });
    try {
        consume(static_cast<const uint8_t*>(staging.mapped), size_t(bytes));
    } catch (...) {
        destroyBuffer(ctx, staging);
        throw;
    }
    destroyBuffer(ctx, staging);
}

VkSampler createSampler(const VulkanContext& ctx, VkFilter filter, VkSamplerMipmapMode mipMode,
                        VkSamplerAddressMode addressU, VkSamplerAddressMode addressV, float maxAnisotropy,
                        float maxLod) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = filter;
    info.minFilter = filter;
    info.mipmapMode = mipMode;
    info.addressModeU = addressU;
    info.addressModeV = addressV;
    info.addressModeW = addressV;
    info.maxLod = maxLod;
    info.anisotropyEnable = maxAnisotropy > 1.0f;
    info.maxAnisotropy = maxAnisotropy;
    VkSampler s;
    VK_CHECK(vkCreateSampler(ctx.device, &info, nullptr, &s));
    return s;
}

std::vector<double> submitTimedSegments(const VulkanContext& ctx,
                                        const std::vector<std::function<void(VkCommandBuffer)>>& segments) {
    const uint32_t stamps = uint32_t(segments.size()) + 1;
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = stamps;
    VkQueryPool pool;
    VK_CHECK(vkCreateQueryPool(ctx.device, &info, nullptr, &pool));
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdResetQueryPool(cmd, pool, 0, stamps);
        vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, pool, 0);
        for (uint32_t i = 0; i < segments.size(); ++i) {
            segments[i](cmd);
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool, i + 1);
        }
    });
    std::vector<uint64_t> t(stamps);
    VK_CHECK(vkGetQueryPoolResults(ctx.device, pool, 0, stamps, t.size() * sizeof(uint64_t), t.data(),
                                   sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    vkDestroyQueryPool(ctx.device, pool, nullptr);
    const double msPerTick = double(ctx.properties.limits.timestampPeriod) * 1e-6;
    std::vector<double> ms(segments.size());
    for (size_t i = 0; i < ms.size(); ++i) ms[i] = double(t[i + 1] - t[i]) * msPerTick;
    return ms;
}

}  // namespace gbl
