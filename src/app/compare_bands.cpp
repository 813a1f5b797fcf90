#include "compare_bands.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <stdexcept>

#include "error.h"

#include "stage_clock.h"
#include "vk_resources.h"

namespace gbl::compare {

uint32_t BandPlan::maxImageRows() const {
    uint32_t rows = 0;
    for (const EvalBand& b : bands) rows = std::max(rows, b.imageRows);
    return rows;
}

BandPlan planBands(uint32_t height, uint32_t bandRows, uint32_t halo) {
    BandPlan plan;
    if (bandRows == 0) return plan;
    if (bandRows % 8 != 0) throw std::invalid_argument("planBands: bandRows must be a multiple of 8");
    plan.bandRows = bandRows;
    plan.halo = halo;
    for (uint32_t first = 0; first < height; first += bandRows) {
        EvalBand b;
        b.firstRow = first;
        b.rows = std::min(bandRows, height - first);
        b.imageFirstRow = first > halo ? first - halo : 0;
        b.imageRows = std::min(height, first + b.rows + halo) - b.imageFirstRow;
        plan.bands.push_back(b);
    }
    return plan;
}

uint32_t autoBandRows(bool cpuDevice, uint32_t width, uint32_t height) {
    return cpuDevice && uint64_t(width) * height > kAutoBandPixels ? kAutoBandRows : 0;
}

std::optional<uint32_t> parseBandRowsFlag(const std::string& value, bool cpuEval, bool groundTruth) {
    if (value == "auto") return std::nullopt;
    uint32_t n = 0;
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
    if ((ec != std::errc() && ec != std::errc::result_out_of_range) || end != value.data() + value.size())
        throwUserError("--band-rows " + quoteName(value) + ": give a number of rows (a multiple of 8), 0 for whole "
                       "frames, or auto");
    if (ec == std::errc::result_out_of_range || n > 65536)
        throwUserError("--band-rows " + quoteName(value) + ": at most 65536 rows (the largest --size is 16384 rows, "
                       "and a band as tall as the frame is the whole frame: give 0)");
    if (n % 8 != 0)
        throwUserError("--band-rows " + value + ": give a multiple of 8 (the worst regions' tiles are 8 rows), 0 for "
                       "whole frames, or auto");
    if (n > 0 && cpuEval)
        throwUserError("--band-rows " + value + " with --eval cpu: the CPU metrics take whole frames; give --eval gpu "
                       "(or auto), or --band-rows 0");
    if (n > 0 && groundTruth)
        throwUserError("--band-rows " + value + " with --ibl ground-truth: the ground truth converges over the whole "
                       "frame; give --band-rows 0, or leave ground-truth out");
    return n;
}

namespace {

RenderSettings bandSettings(const RenderSettings& settings, const EvalBand& band) {
    RenderSettings s = settings;
    s.bandFirstRow = band.imageFirstRow;
    s.bandRows = band.imageRows;
    s.keepOnDevice = true;
    s.decodeSurfaces = true;
    s.decodeOnCpu = false;
    s.readTargetWords = false;
    return s;
}

void addTimes(PassTimings& sum, const PassTimings& t) {
    sum.gbufferMs += t.gbufferMs;
    sum.lightingMs += t.lightingMs;
}

// The band's own rows (not its halo) of its device HDR image into the frame's, copied once
// straight out of the staging memory (downloadImageWith).
void copyBandRows(const RenderOutput& out, const EvalBand& band, Image& frame) {
    ScopedStage timed(Stage::Readback);
    const size_t rowBytes = size_t(frame.width) * 4 * sizeof(float);
    downloadImageWith(
        out.device->ctx, out.device->hdr, VK_IMAGE_LAYOUT_GENERAL,
        [&](const uint8_t* bytes, size_t size) {
            if (frame.channels != 4 || size != rowBytes * band.rows)
                throw std::logic_error("copyBandRows: the band's HDR rows do not fit the frame's RGBA image");
            std::memcpy(frame.pixels.data() + size_t(band.firstRow) * frame.width * 4, bytes, size);
        },
        0, 0, band.firstRow - band.imageFirstRow, band.rows);
}

}  // namespace

PassTimings renderReferenceInBands(Renderer& renderer, const GBufferWiring& reference, const RenderSettings& settings,
                                   const BandPlan& plan, GpuEvaluator& evaluator, float exposure, Image* hdr) {
    PassTimings times;
    if (hdr) *hdr = Image(int(settings.width), int(settings.height), 4);
    evaluator.beginReferenceBands(exposure);
    for (const EvalBand& band : plan.bands) {
        const RenderOutput out = renderer.render(reference, bandSettings(settings, band));
        addTimes(times, out.timings);
        {
            ScopedStage timed(Stage::Metrics);
            evaluator.addReferenceBand(deviceView(out), band);
        }
        if (hdr) copyBandRows(out, band, *hdr);
    }
    ScopedStage timed(Stage::Metrics);
    evaluator.endReferenceBands();
    return times;
}

BandedRun evaluateRunInBands(Renderer& renderer, const GBufferWiring& reference, const GBufferWiring& test,
                             const RenderSettings& settings, const BandPlan& plan, GpuEvaluator& evaluator,
                             const GpuEvalOptions& options, Image* hdr) {
    BandedRun run;
    if (hdr) *hdr = Image(int(settings.width), int(settings.height), 4);
    evaluator.beginRun(options);
    for (const EvalBand& band : plan.bands) {
        const RenderSettings s = bandSettings(settings, band);
        RenderSettings referenceSettings = s;
        referenceSettings.onTargetWords = nullptr;  // the compression model measures the layout's words only
        // Both renders of the band live until it is measured; the next band allocates afresh
        // (rows a render never touches are never resident on lavapipe).
        const RenderOutput ref = renderer.render(reference, referenceSettings);
        const RenderOutput out = renderer.render(test, s);
        addTimes(run.reference, ref.timings);
        addTimes(run.test, out.timings);
        {
            ScopedStage timed(Stage::Metrics);
            evaluator.addBand(deviceView(ref), deviceView(out), band);
        }
        if (hdr) copyBandRows(out, band, *hdr);
    }
    ScopedStage timed(Stage::Metrics);
    run.metrics = evaluator.finishRun();
    return run;
}

PassTimings measureRunInBands(RunReport& run, Renderer& renderer, const GBufferWiring& reference, const GBufferWiring& test,
                       const RenderSettings& settings, const BandPlan& plan, GpuEvaluator& evaluator,
                       const std::filesystem::path& outDir, const std::string& prefix, bool hdrFlip, bool writeImages,
                       const ImageOutput& output, double& gpuPassMs) {
    // The run's whole-frame images fill band by band; those of the run before must be written and
    // gone first, or two runs' images (34 B/px each, 4K: 282 MB) would be held at once.
    if (writeImages && output.writer) {
        ScopedStage timed(Stage::Report);
        output.writer->drain();
    }
    GpuErrorImages images;
    GpuEvalOptions options;
    options.hdrFlip = hdrFlip;
    options.images = writeImages ? &images : nullptr;
    options.cropSize = std::max(32, int(std::min(settings.width, settings.height)) / 12);  // as measureRun's
    // The HDR image for render.exr is the only float image that spans the frame (16 B/px), and only
    // when files are written; it goes to the writer, which owns it until written.
    auto hdr = writeImages ? std::make_shared<Image>() : nullptr;
    const BandedRun r = evaluateRunInBands(renderer, reference, test, settings, plan, evaluator, options, hdr.get());
    gpuPassMs += r.test.gbufferMs + r.test.lightingMs + r.reference.gbufferMs + r.reference.lightingMs;
    fillMetrics(run, r.metrics);
    if (!writeImages) return r.test;
    ScopedStage timed(Stage::Report);
    queueDeviceImages(run, std::move(images), r.metrics, [hdr = std::move(hdr)] { return hdr; }, outDir, prefix, output);
    return r.test;
}

}  // namespace gbl::compare
