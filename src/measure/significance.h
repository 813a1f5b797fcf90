#pragma once
// Is "layout A has a lower error than layout B" real, or within the noise of views and pixels?
// compare answers with a paired sign-flip permutation test (Fisher 1935, The Design of
// Experiments, section 21: the test of Darwin's paired Zea mays heights) on the differences of
// the two layouts' mean LDR-FLIP over the same units: the tiles of a 16 x 9 grid over every view
// (and every scene, across scenes). Under the null hypothesis the two layouts' errors are
// exchangeable on each unit, so each difference is as likely to have either sign; the p-value is
// the share of the 2^n sign assignments whose |sum| is at least the observed |sum| (two-sided).
// Exact for n <= kExactSignFlipUnits, else estimated from random assignments (Monte Carlo,
// p = (1 + hits) / (1 + resamples), which never understates it).
// Caveat, stated in docs/compare.md: neighbouring tiles of one view share materials and lighting,
// so they are not independent; the test then overstates significance somewhat. Coarse tiles
// (16 x 9 of the frame, 120 pixels at 1080p) keep that small.
#include <cstdint>
#include <vector>

#include "image.h"

namespace gbl {

inline constexpr int kSignificanceTileColumns = 16;
inline constexpr int kSignificanceTileRows = 9;
inline constexpr int kExactSignFlipUnits = 16;
inline constexpr int kSignFlipResamples = 4999;
inline constexpr uint64_t kSignFlipSeed = 0x5eed5eedULL;
inline constexpr double kSignificanceAlpha = 0.05;

// The mean of a 1-channel map over each tile of a columns x rows grid (tile (c, r) covers
// x in [c W / columns, (c + 1) W / columns), rows likewise), row-major. A tile with no pixel
// (an image narrower than the grid) is left out. With `included` (one byte per pixel), the mean of
// the included pixels only, 0 for a tile without any (kept, so that every run of a view has the
// same tiles: the mask is the view's, run_metrics.h RunMetricsOptions::excluded).
std::vector<float> tileMeans(const Image& map, int columns = kSignificanceTileColumns,
                             int rows = kSignificanceTileRows, const std::vector<uint8_t>* included = nullptr);

// Two-sided paired sign-flip permutation test of `differences` (A - B per unit) against 0.
// Returns 1 for no units or all-zero differences.
double pairedSignFlipPValue(const std::vector<double>& differences, int resamples = kSignFlipResamples,
                            uint64_t seed = kSignFlipSeed);

}  // namespace gbl
