#pragma once
// compare in bands of rows: a 4K comparison in bounded memory (issue 14, "4K fits in memory").
//
// On a CPU device (lavapipe) device memory is host memory, and a whole 3840x2160 frame of the
// reference and of a layout (G-buffer, HDR image, four decoded surfaces, FLIP's planes) needs
// about 2 GiB. In bands, each band of rows is rendered twice, the reference and the layout, with
// FLIP's halo of rows above and below (the renderer's bands are bit-exact: render_band_test),
// measured on the device (GpuEvaluator's banded calls: the same numbers as a whole frame's) and
// dropped before the next band. What spans the frame is only the run's accumulators, its 8-bit
// error images (gpu_evaluator.h) and, for the first view, its HDR image for render.exr.
//
// The price is time: the reference is rendered again for every run (once per band), and each band
// renders and measures its halo rows twice. compare picks bands on its own only where memory is
// the problem (autoBandRows); `--band-rows N` asks for them anywhere.
#include <cstdint>
#include <vector>

#include <filesystem>
#include <optional>
#include <string>

#include "compare_runs.h"
#include "gpu_evaluator.h"
#include "image.h"
#include "renderer.h"

namespace gbl::compare {

struct BandPlan {
    uint32_t bandRows = 0;  // rows per band but the last; 0: whole frames
    uint32_t halo = 0;      // rows rendered and measured above and below each band (flipHaloRows())
    std::vector<EvalBand> bands;
    bool banded() const { return bandRows != 0; }
    // The most rows a band's images have (the evaluator's planes hold this many).
    uint32_t maxImageRows() const;
};

// Bands of `bandRows` rows (a multiple of 8, so the worst regions' 8x8 tiles never straddle two
// bands; the last band takes what is left) with `halo` rows each side, clamped to the frame.
// bandRows 0: an empty plan (whole frames).
BandPlan planBands(uint32_t height, uint32_t bandRows, uint32_t halo);

// What --band-rows auto picks: bands of kAutoBandRows rows on a CPU device when the frame has more
// than kAutoBandPixels pixels, else whole frames (0). 64 rows: at 3840x2160 with three layouts
// (one view, lavapipe) the peak RSS was 844,280 KiB in 64-row bands against 973,808 KiB in
// 128-row ones, and the wall time no longer (183 s against 197 s, machine loaded by builds).
inline constexpr uint64_t kAutoBandPixels = 4194304;  // 2^22: above 2560x1600, below 3840x2160
inline constexpr uint32_t kAutoBandRows = 64;
uint32_t autoBandRows(bool cpuDevice, uint32_t width, uint32_t height);
// --band-rows VALUE: unset for auto, else N (0 or a multiple of 8). Throws UserError naming the flag
// and the fix for anything else, and for bands asked with --eval cpu or a ground truth.
std::optional<uint32_t> parseBandRowsFlag(const std::string& value, bool cpuEval, bool groundTruth);

// The reference under one IBL mode, in bands: its statistics go into `evaluator`
// (beginReferenceBands ... endReferenceBands); with `hdr`, its HDR image (RGBA float) is assembled
// there from the bands' rows. Returns the GPU pass times, summed over the bands.
PassTimings renderReferenceInBands(Renderer& renderer, const GBufferWiring& reference, const RenderSettings& settings,
                                   const BandPlan& plan, GpuEvaluator& evaluator, float exposure, Image* hdr);

// One run in bands: per band, the reference and the layout rendered and measured. `options` as
// GpuEvaluator::beginRun takes them; with `hdr`, the layout's HDR image (RGBA float) is assembled.
struct BandedRun {
    RunMetrics metrics;
    PassTimings test;       // the layout's passes, summed over its bands
    PassTimings reference;  // the reference's, rendered again for every band
};
BandedRun evaluateRunInBands(Renderer& renderer, const GBufferWiring& reference, const GBufferWiring& test,
                             const RenderSettings& settings, const BandPlan& plan, GpuEvaluator& evaluator,
                             const GpuEvalOptions& options, Image* hdr);

// compare's run in bands: evaluateRunInBands, its metrics into `run`, and with `writeImages` its
// files as measureRun's device path writes them. Returns the layout's pass times; `gpuPassMs`
// gains every pass rendered, the reference's included.
PassTimings measureRunInBands(RunReport& run, Renderer& renderer, const GBufferWiring& reference, const GBufferWiring& test,
                       const RenderSettings& settings, const BandPlan& plan, GpuEvaluator& evaluator,
                       const std::filesystem::path& outDir, const std::string& prefix, bool hdrFlip, bool writeImages,
                       const ImageOutput& output, double& gpuPassMs);

}  // namespace gbl::compare
