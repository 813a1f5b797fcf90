#pragma once
// LDR-FLIP (Andersson et al., HPG 2020) and HDR-FLIP (Andersson et al., EG 2021 short) as compute
// passes over the device's HDR images: the twin of measure/flip.cpp and flip_hdr.cpp, with the
// same kernels (flip_pipeline.h makeKernels), colour constants and separable filters in the same
// order, in float. Internal to gbl_evaluate (gpu_evaluator.h drives it).
#include <vector>

#include "eval_device.h"
#include "flip.h"

namespace gbl::evaluate {

class GpuFlip {
public:
    explicit GpuFlip(EvalDevice& device, double pixelsPerDegree = flipPixelsPerDegree());
    // The working and result planes (15 floats per pixel): allocated before ldr / hdr, released
    // between runs so they do not add to the peak while the next run renders.
    void allocate();
    void release();
    // LDR-FLIP of the 8-bit tone-mapped images (toneMapToSrgb8 at `exposure`) into kFlipMap.
    void ldr(VkCommandBuffer cmd, float exposure);
    // HDR-FLIP over `range`'s exposures (per-pixel maximum) into kHdrFlipMap.
    void hdr(VkCommandBuffer cmd, const FlipExposureRange& range);
    // The reference's exposure range (flipExposureRange), from its luminance histogram refined to
    // the exact median; submits its own work. The reference image must be bound.
    FlipExposureRange exposureRange();

    // The same range from the frame's reference luminance read back band by band (the luminance
    // pass's mode 2 values, `y` reordered in place) and its maximum: the same median (the values'
    // exact lower median, or the bound exposureRange uses outside the histogram's exact bins).
    static FlipExposureRange exposureRange(std::vector<float>& y, double yMax);

private:
    // Image `which` (0 reference, 1 test) through the per-image pipeline into planes dst..dst+4.
    void prepare(VkCommandBuffer cmd, uint32_t which, bool hdrMode, float factor, uint32_t dst);
    void combine(VkCommandBuffer cmd, uint32_t out, bool maxInto);
    EvalDevice& dev_;
    uint32_t csfTaps_ = 0, featTaps_ = 0;
    uint32_t offA_ = 0, offRG_ = 0, offBY1_ = 0, offBY2_ = 0, offEdge_ = 0, offGauss_ = 0;
    float wBY1_ = 1.0f, wBY2_ = 0.0f, cMax_ = 0.0f;
};

}  // namespace gbl::evaluate
