#pragma once
// The scene's texture mip chains, kept on disk for a CPU device.
//
// uploadScene fills a texture's mips with linear blits (vkCmdBlitImage), each level from the one
// above, as every driver defines them. On lavapipe every blit is a rasterised pass of its own:
// about 2.6 ms a level whatever its size, 125-140 ms for the built-in scene's six textures and
// about 240 ms for WaterBottle's four 2048^2 ones, the largest part of a small compare's set-up
// (bench/RESULTS.md, 2026-11-25). On a CPU device the levels the blits made are read back once
// and stored (base/disk_cache.h); a later run uploads them as they are, byte for byte what the
// same driver's blits make: the key holds the driver's identity (vendor, device, driver version,
// pipelineCacheUUID) and the texture's format, size and texels. A GPU blits every time (a few
// milliseconds there). A missing, truncated or corrupt file is a miss; one that cannot be written
// is no error (the next run blits again).
#include <cstdint>

#include "vk_context.h"
#include "vk_resources.h"

namespace gbl {

// Uploads `rgba` (mip 0 of `image`: a texel of its format each, 4 bytes of RGBA8 or 8 of RGBA16F,
// rows top to bottom) and fills the image's
// other mips, from the cache or by blits (above). Leaves every mip SHADER_READ_ONLY_OPTIMAL.
void uploadTextureWithMips(const VulkanContext& ctx, GpuImage& image, const uint8_t* rgba);

// The cache's key for `image`'s mips made from `rgba` on this device (for tests).
uint64_t textureMipCacheKey(const VulkanContext& ctx, const GpuImage& image, const uint8_t* rgba);

}  // namespace gbl
