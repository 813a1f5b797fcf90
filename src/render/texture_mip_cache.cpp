#include "texture_mip_cache.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "disk_cache.h"

namespace gbl {
namespace {

constexpr char kMagic[8] = {'G', 'B', 'L', 'M', 'I', 'P', 'S', '1'};
constexpr uint32_t kFormatVersion = 1;

VkDeviceSize levelBytes(const GpuImage& image, uint32_t mip) {
    return VkDeviceSize(std::max(image.extent.width >> mip, 1u)) * std::max(image.extent.height >> mip, 1u) *
           formatTexelSize(image.format);
}

// Mip 0 from `rgba` and mips 1.. from `rest` (their bytes one after another), one copy per level.
void uploadLevels(const VulkanContext& ctx, GpuImage& image, const uint8_t* rgba, const unsigned char* rest,
                  VkDeviceSize restBytes) {
    const VkDeviceSize base = levelBytes(image, 0);
    Buffer staging = createBuffer(ctx, base + restBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, rgba, size_t(base));
    std::memcpy(static_cast<unsigned char*>(staging.mapped) + base, rest, size_t(restBytes));
    std::vector<VkBufferImageCopy> regions;
    VkDeviceSize offset = 0;
    for (uint32_t m = 0; m < image.mipLevels; ++m) {
        VkBufferImageCopy r{};
        r.bufferOffset = offset;
        r.imageSubresource = {image.aspect, m, 0, image.layers};
        r.imageExtent = {std::max(image.extent.width >> m, 1u), std::max(image.extent.height >> m, 1u), 1};
        regions.push_back(r);
        offset += levelBytes(image, m);
    }
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        transitionImage(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(regions.size()), regions.data());
        transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
    destroyBuffer(ctx, staging);
}

}  // namespace

uint64_t textureMipCacheKey(const VulkanContext& ctx, const GpuImage& image, const uint8_t* rgba) {
    Fnv64 f;
    f.text("texture mips");
    f.value(ctx.properties.vendorID);
    f.value(ctx.properties.deviceID);
    f.value(ctx.properties.driverVersion);
    f.bytes(ctx.properties.pipelineCacheUUID, VK_UUID_SIZE);
    f.value(uint32_t(image.format));
    f.value(image.extent.width);
    f.value(image.extent.height);
    f.value(image.mipLevels);
    f.words(rgba, size_t(levelBytes(image, 0)));
    return f.h;
}

void uploadTextureWithMips(const VulkanContext& ctx, GpuImage& image, const uint8_t* rgba) {
    const VkDeviceSize base = levelBytes(image, 0);
    if (ctx.info.type != VK_PHYSICAL_DEVICE_TYPE_CPU || image.mipLevels < 2) {
        uploadImage(ctx, image, rgba, base, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, true);
        return;
    }
    VkDeviceSize restBytes = 0;
    for (uint32_t m = 1; m < image.mipLevels; ++m) restBytes += levelBytes(image, m);
    const uint64_t key = textureMipCacheKey(ctx, image, rgba);
    const std::filesystem::path file = cacheFileFor("mips", key);
    std::string why;
    if (auto rest = readCacheEnvelope(file, kMagic, kFormatVersion, key, &why); rest && rest->size() == restBytes) {
        uploadLevels(ctx, image, rgba, rest->data(), restBytes);
        return;
    }
    uploadImage(ctx, image, rgba, base, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, true);
    std::vector<unsigned char> rest;
    rest.reserve(size_t(restBytes));
    for (uint32_t m = 1; m < image.mipLevels; ++m) {
        const std::vector<uint8_t> level = downloadImage(ctx, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, m);
        rest.insert(rest.end(), level.begin(), level.end());
    }
    try {
        writeCacheEnvelope(file, kMagic, kFormatVersion, key, rest.data(), rest.size());
    } catch (const std::exception&) {
        // A cache that cannot be written (read-only home, full disk) only costs the next run the blits.
    }
}

}  // namespace gbl
