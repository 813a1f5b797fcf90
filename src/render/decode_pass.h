#pragma once
// The decode pass: runs a layout's readGBuffer() over every pixel and reads the Surface back as
// SurfaceImages (see shaders/decode_pass.comp.glsl).
#include <array>

#include "gbuffer_wiring.h"
#include "renderer_passes.h"
#include "surface_images.h"

namespace gbl {

// Decodes the G-buffer `gbuffer` (targets in SHADER_READ_ONLY_OPTIMAL, depth in
// DEPTH_STENCIL_READ_ONLY_OPTIMAL) written with `wiring`, in bands of `bandRows` rows (a multiple
// of 8; 0: as many as fit in 64 MiB of floats). `depthValues` are the depth buffer's
// values of the render's rows (FrameConstants::band), already read back (they go into
// SurfaceImages::depth; their count / the width is the row count). `materialPass`: deferred
// lighting's material targets, bound at set 2 as in the lighting pass.
SurfaceImages decodeSurfaces(const VulkanContext& ctx, const GBufferWiring& wiring, const GBufferPass& gbuffer,
                             const Buffer& frameConstants, VkSampler nearestSampler,
                             const std::vector<float>& depthValues, const GBufferPass* materialPass,
                             uint32_t bandRows, PipelineMemo& memo);
// The decode pass's pipeline alone, from `memo` or built into it (renderer_passes.h's
// gbufferPassPipeline says why): decodeSurfaces' (bands read back), or with `toImages`
// decodeSurfacesOnDevice's.
PassPipeline decodePassPipeline(const VulkanContext& ctx, const GBufferWiring& wiring, const TargetReadScene& scene,
                                PipelineMemo& memo, bool toImages = false);

// The same decode, kept in device memory for the GPU evaluation (src/evaluate/gpu_evaluator.h):
// four RGBA32F images (STORAGE, left in GENERAL) of the render's `rows` rows (FrameConstants::band): normal + roughness, base
// colour + metallic, diffuse colour + occlusion, specular colour + view depth. Zero where no
// geometry covers the pixel (the HDR image's alpha says which). In a scene with material layers
// (GBL_LAYERS) four more, the layers' (gpu_evaluator.h DeviceRender::layers); else those four are
// empty. The caller destroys them.
std::array<GpuImage, 8> decodeSurfacesOnDevice(const VulkanContext& ctx, const GBufferWiring& wiring,
                                               const GBufferPass& gbuffer, const Buffer& frameConstants,
                                               VkSampler nearestSampler, const GBufferPass* materialPass,
                                               uint32_t rows, PipelineMemo& memo);

}  // namespace gbl
