#pragma once
// The decode pass on the host (RenderSettings::decodeOnCpu): the G-buffer's raw words, read back,
// decoded by the layout's CPU codec (cpu_codec.h, the bit-exact mirror of its readGBuffer) into the
// SurfaceImages the decode pass (decode_pass.h, shaders/decode_pass.comp.glsl) fills: the same
// transform from the stored [space], the same view depth from the depth buffer, zeros where no
// geometry covers the pixel. render/cpu_decode_test holds the two to gpu_cpu_bits_test's 4 ulps.
//
// Why: on a CPU device (lavapipe) the decode pass is readGBuffer JIT-compiled by llvmpipe, scalar
// per pixel, then 80 bytes per pixel of floats copied back; the codec's loops are vectorised and
// read only the targets' words (bench/RESULTS.md, "Read-back on the CPU codec").
#include <vector>

#include <vulkan/vulkan.h>

#include "cpu_codec.h"
#include "shared_types.h"
#include "surface_images.h"

namespace gbl {

// `words`: the targets' (and material pass's) words of a width x height frame, width and height
// set; its `covered` is filled here from `depth` (the depth buffer's values, row-major) against
// the clear depth frame.shading.y, as the decode pass's gblHasGeometry. `frame`: the frame's
// constants (view, inverse view-projection, extent). `normalSpace`, `depthFormat`: the wiring's
// (a 24-bit depth's view depth is computed from the value as the device's sampler converts it).
// `storesDepth`: the wiring's; the view depth then comes from the layout's stored window depth.
// `layers`: the scene has material layers (GpuScene::layers != 0): the seven layer images are
// filled too (directions to world space, as the normal), as the decode pass does with GBL_LAYERS.
// Runs on hardwareThreads() threads, a band of rows at a time per thread.
SurfaceImages decodeSurfacesOnCpu(const CpuCodec& codec, CpuGBuffer& words, const std::vector<float>& depth,
                                  const gpu::FrameConstants& frame, int normalSpace, VkFormat depthFormat,
                                  bool storesDepth, bool layers = false);

}  // namespace gbl
