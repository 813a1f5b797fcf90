#include "gpu_flip.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "color_difference.h"
#include "flip_pipeline.h"
#include "histogram.h"
#include "metrics.h"

namespace gbl::evaluate {

namespace {
// Working planes (PlaneSlot kWork + ...).
constexpr uint32_t kYy = kWork, kCx = kWork + 1, kCz = kWork + 2, kLum = kWork + 3, kTmp = kWork + 4;
constexpr uint32_t kColorConstants = 24;  // flip_common.glsl KC_*

// flip.cpp colorConsts: the same double computations rounded to float.
std::vector<float> colorConstants() {
    std::vector<float> k(kColorConstants);
    const double basis[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int j = 0; j < 3; ++j) {
        const Xyz col = linearSrgbToXyz(basis[j][0], basis[j][1], basis[j][2]);
        k[size_t(0 + j)] = float(col.X);
        k[size_t(3 + j)] = float(col.Y);
        k[size_t(6 + j)] = float(col.Z);
        double r, g, b;
        xyzToLinearSrgb(Xyz{basis[j][0], basis[j][1], basis[j][2]}, r, g, b);
        k[size_t(9 + j)] = float(r);
        k[size_t(12 + j)] = float(g);
        k[size_t(15 + j)] = float(b);
    }
    const Xyz w = d65White();
    k[18] = float(w.X), k[19] = float(w.Y), k[20] = float(w.Z);
    k[21] = float(1.0 / w.X), k[22] = float(1.0 / w.Y), k[23] = float(1.0 / w.Z);
    return k;
}

// flipExposureRange's last step, from the reference's maximum and median luminance.
FlipExposureRange rangeOf(double yMax, double yMedian) {
    // x_max [HDR]: t(x_max) = 0.85 for the tone mapper, as flip_hdr.cpp solves it.
    const double k[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
    const double t = 0.85;
    const double qa = k[0] - t * k[3], qb = k[1] - t * k[4], qc = k[2] - t * k[5];
    const double xMax = (-qb + std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
    FlipExposureRange range;
    range.start = float(std::log2(xMax / yMax));
    range.stop = float(std::log2(xMax / yMedian));
    range.count = std::max(2, int(std::ceil(double(range.stop) - double(range.start))));
    return range;
}
}  // namespace

GpuFlip::GpuFlip(EvalDevice& device, double ppd) : dev_(device) {
    const flip_pipeline::Kernels k = flip_pipeline::makeKernels(ppd);
    std::vector<float> all = colorConstants();
    auto append = [&](const std::vector<float>& taps) {
        const uint32_t at = uint32_t(all.size());
        all.insert(all.end(), taps.begin(), taps.end());
        return at;
    };
    csfTaps_ = uint32_t(k.csfA.size());
    featTaps_ = uint32_t(k.gauss.size());
    offA_ = append(k.csfA);
    offRG_ = append(k.csfRG);
    offBY1_ = append(k.csfBY1);
    offBY2_ = append(k.csfBY2);
    offEdge_ = append(k.edge);
    append(k.point);  // right after the edge taps (flip_features.comp.glsl)
    offGauss_ = append(k.gauss);
    wBY1_ = k.wBY1;
    wBY2_ = k.wBY2;
    cMax_ = float(flip_pipeline::maxColorDifference());
    dev_.setKernels(all);
}

void GpuFlip::allocate() {
    for (uint32_t s = 0; s < kNoise; ++s) dev_.ensurePlane(s);
}

void GpuFlip::release() {
    for (uint32_t s = 0; s < kNoise; ++s) dev_.releasePlane(s);
}

void GpuFlip::prepare(VkCommandBuffer cmd, uint32_t which, bool hdrMode, float factor, uint32_t dst) {
    Push p;
    p.mode = hdrMode ? 1 : 0;
    p.f0 = factor;
    p.u[0] = kYy, p.u[1] = kCx, p.u[2] = kCz, p.u[3] = kLum, p.u[6] = which;
    dev_.dispatch(cmd, Pass::FlipOpponent, p);
    auto filter = [&](uint32_t in, uint32_t out, uint32_t taps, uint32_t offset, bool cols) {
        Push f;
        f.mode = taps;
        f.flags = cols ? 1 : 0;
        f.u[0] = in, f.u[1] = out, f.u[2] = offset;
        dev_.dispatch(cmd, Pass::FlipFilter, f);
    };
    // The CSF filters (FLIP eq. (3)) per opponent channel, rows then columns, as flip.cpp prepare;
    // the filtered channels go straight into the destination planes (the second blue-yellow term
    // into dst + 3, free until the features), and the Lab pass works there in place.
    filter(kYy, kTmp, csfTaps_, offA_, false);
    filter(kTmp, dst, csfTaps_, offA_, true);
    filter(kCx, kTmp, csfTaps_, offRG_, false);
    filter(kTmp, dst + 1, csfTaps_, offRG_, true);
    filter(kCz, kTmp, csfTaps_, offBY1_, false);
    filter(kTmp, dst + 2, csfTaps_, offBY1_, true);
    const bool by2 = wBY2_ != 0.0f;
    if (by2) {
        filter(kCz, kTmp, csfTaps_, offBY2_, false);
        filter(kTmp, dst + 3, csfTaps_, offBY2_, true);
    }
    Push lab;
    lab.flags = by2 ? 1 : 0;
    lab.f0 = wBY1_, lab.f1 = wBY2_;
    lab.u[0] = dst, lab.u[1] = dst + 1, lab.u[2] = dst + 2, lab.u[3] = dst + 3, lab.u[4] = dst, lab.u[5] = dst + 1,
    lab.u[6] = dst + 2;
    dev_.dispatch(cmd, Pass::FlipLab, lab);
    // Features (eq. (9)) on the unfiltered normalised luminance.
    Push rows;
    rows.mode = featTaps_;
    rows.flags = 0;
    rows.u[0] = kLum, rows.u[1] = kYy, rows.u[2] = kCx, rows.u[3] = kCz, rows.u[6] = offEdge_, rows.u[7] = offGauss_;
    dev_.dispatch(cmd, Pass::FlipFeatures, rows);
    Push cols = rows;
    cols.flags = 1;
    cols.u[4] = dst + 3, cols.u[5] = dst + 4;
    dev_.dispatch(cmd, Pass::FlipFeatures, cols);
}

void GpuFlip::combine(VkCommandBuffer cmd, uint32_t out, bool maxInto) {
    Push p;
    p.mode = maxInto ? 1 : 0;
    p.f0 = cMax_;
    p.u[0] = kRefPrepared, p.u[1] = kTestPrepared, p.u[2] = out;
    dev_.dispatch(cmd, Pass::FlipCombine, p);
}

void GpuFlip::ldr(VkCommandBuffer cmd, float exposure) {
    prepare(cmd, 0, false, exposure, kRefPrepared);
    prepare(cmd, 1, false, exposure, kTestPrepared);
    combine(cmd, kFlipMap, false);
}

void GpuFlip::hdr(VkCommandBuffer cmd, const FlipExposureRange& range) {
    for (int e = 0; e < range.count; ++e) {
        // Exposure-compensate by 2^c, tone map, LDR-FLIP; per-pixel maximum over exposures [HDR].
        const float scale = std::exp2(range.exposure(e));
        prepare(cmd, 0, true, scale, kRefPrepared);
        prepare(cmd, 1, true, scale, kTestPrepared);
        combine(cmd, kHdrFlipMap, e > 0);
    }
}

FlipExposureRange GpuFlip::exposureRange() {
    const size_t n = size_t(dev_.width) * dev_.height;
    dev_.ctx.submitAndWait([&](VkCommandBuffer cmd) {
        dev_.clearHistograms(cmd);
        Push p;
        p.mode = 0;
        p.u[0] = kHistLuminance;
        dev_.dispatch(cmd, Pass::Luminance, p);
        dev_.reduce(cmd, 1, {1u, 0u, 0u, 0u}, 0);
    });
    const double yMax = dev_.result()[0];
    std::vector<uint32_t> bins(dev_.histogram(kHistLuminance), dev_.histogram(kHistLuminance) + kHistBins);
    if (!(yMax > 0.0)) return FlipExposureRange{};
    // The exact lower median: the bin holding its rank, then that bin's 2^14 values counted one by one.
    size_t rank = nearestRankIndex(0.5, n);
    uint32_t first = 0;  // bin 0: exact zeros; a zero median uses the positive values' median
    if (bins[0] > rank) {
        rank = size_t(bins[0]) + nearestRankIndex(0.5, n - bins[0]);
    }
    uint64_t seen = 0;
    uint32_t bin = 0;
    for (; bin < kHistBins; ++bin) {
        if (seen + bins[bin] > rank) break;
        seen += bins[bin];
    }
    double yMedian = 0.0;
    if (bin >= 2 && bin < kHistBins - 1) {
        first = kHistFirstBits + ((bin - 2) << kHistBinShift);
        dev_.ctx.submitAndWait([&](VkCommandBuffer cmd) {
            dev_.clearHistograms(cmd);
            Push p;
            p.mode = 1;
            p.u[0] = kHistRefine;
            p.u[1] = first >> kHistBinShift;
            dev_.dispatch(cmd, Pass::Luminance, p);
        });
        const uint32_t* low = dev_.histogram(kHistRefine);
        uint64_t s = seen;
        for (uint32_t b = 0; b < (1u << kHistBinShift); ++b) {
            s += low[b];
            if (s > rank) {
                yMedian = double(std::bit_cast<float>(first | b));
                break;
            }
        }
    } else {
        double lo, hi;
        histogramBinRange(std::min(bin, kHistBins - 1), lo, hi);
        yMedian = std::isinf(hi) ? lo : hi;
    }
    return rangeOf(yMax, yMedian);
}

FlipExposureRange GpuFlip::exposureRange(std::vector<float>& y, double yMax) {
    if (!(yMax > 0.0)) return FlipExposureRange{};
    // As above: the lower median over all pixels, or over the positive ones when it is 0 (the
    // luminance pass wrote 0 for NaN and infinities; -0 and 0 both sort as zeros here).
    for (float& v : y) v = v > 0.0f ? v : 0.0f;
    const size_t n = y.size();
    const size_t zeros = size_t(std::count(y.begin(), y.end(), 0.0f));
    size_t rank = nearestRankIndex(0.5, n);
    if (zeros > rank) rank = zeros + nearestRankIndex(0.5, n - zeros);
    std::nth_element(y.begin(), y.begin() + std::ptrdiff_t(rank), y.end());
    const float v = y[rank];
    // Outside the histogram's exact bins (eval_common.glsl histBin) exposureRange takes a bound.
    const uint32_t bits = std::bit_cast<uint32_t>(v);
    double yMedian = double(v);
    if (bits < kHistFirstBits) yMedian = double(std::bit_cast<float>(kHistFirstBits));  // bin 1: its top
    else if (bits >= 0x4F800000u) yMedian = double(std::bit_cast<float>(0x4F800000u));  // last bin: its bottom
    return rangeOf(yMax, yMedian);
}

}  // namespace gbl::evaluate
