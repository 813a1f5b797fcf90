#pragma once
// The evaluation passes' histograms (shaders/eval_common.glsl histBin), read on the host.
//
// Bin layout for a non-negative float v: bin 0 holds v = 0 (and NaN / negatives), bin 1 the
// values in (0, 2^-32), bins 2 .. 32769 the floats in [2^-32, 2^32) by their exponent and 9
// leading mantissa bits (2^14 consecutive float bit patterns per bin: a relative width of 2^-9),
// bin 32770 [2^32, +inf]. A quantile is reported as its bin's midpoint, clamped to the exact
// maximum: at most 2^-10 (about 0.1 %) relative from the exact nearest-rank value for values in
// [2^-32, 2^32), at most 2^-32 absolute below that, and exactly 0 when it is 0.
#include <cstddef>
#include <cstdint>
#include <span>

namespace gbl::evaluate {

inline constexpr uint32_t kHistBins = 32771;
inline constexpr uint32_t kHistFirstBits = 0x2F800000u;  // 2^-32
inline constexpr uint32_t kHistBinShift = 14;

// The nearest-rank p-quantile (measure/metrics.h nearestRankIndex) of the samples counted in
// `bins` (kHistBins counters; several histograms of the same quantity may be summed first).
double histogramQuantile(std::span<const uint32_t> bins, double p, double exactMax);
// The bin's [lo, hi) as doubles.
void histogramBinRange(uint32_t bin, double& lo, double& hi);

}  // namespace gbl::evaluate
