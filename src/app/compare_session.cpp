// compare's set-up, bookkeeping and finish (the renders and runs of a view: compare_session_view.cpp).
#include "compare_session.h"
#include "compare_temporal.h"

#include <algorithm>
#include <cstdio>
#include <ctime>

#include "auto_exposure.h"
#include "bandwidth.h"
#include "light_coverage.h"
#include "budget_verdict.h"
#include "best_fit_normals.h"
#include "forward_mask.h"
#include "gpu_scene.h"
#include "compare_memory.h"
#include "compare_timings.h"
#include "env_flag.h"
#include "error.h"
#include "file_io.h"
#include "host_heap.h"
#include "host_profile.h"
#include "ibl_cache.h"
#include "interrupt.h"  // signalName
#include "layout_atlas.h"
#include "layout_catalog.h"
#include "memory_budget.h"
#include "parallel_for.h"
#include "rank_significance.h"
#include "report_html.h"
#include "stage_clock.h"
#include "view_content.h"

namespace gbl::compare {

namespace fs = std::filesystem;

namespace {

// In the output folder while it is incomplete (see the constructor).
constexpr const char* kIncompleteMarker = "INCOMPLETE";

int writerNiceness() { return int(std::clamp(envLong("GBL_WRITER_NICE").value_or(0), 0L, 19L)); }

std::string isoDate() {
    const std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return buf;
}

}  // namespace

CompareShared::~CompareShared() {
    if (ctx) {
        vkDeviceWaitIdle(ctx->device);
        pipelines.destroy(ctx->device);
    }
}

CompareSession::CompareSession(const CompareOptions& options, const app::RunControl& control, CompareShared* shared)
    : options_(options), control_(control), shared_(shared) {
    std::optional<ScopedStage> timedSetup(std::in_place, Stage::Setup);
    checkOutputDirectory(options_.outDir, options_.force, "--out");
    loadInputs();  // everything the user gave is read and validated before the first pixel is rendered
    openDevice();
    describeRun();
    placeViews();
    openOutput();
    timedSetup.reset();
    createRenderer();
    referenceWiring_ = generateWiring(referenceLayout_, {});
    preparePipelines();
}

// The layouts, the reference layout, the scene and its environment; a scene with materials drawn
// forward is refused where its mask cannot be applied.
void CompareSession::loadInputs() {
    const CompareOptions& o = options_;
    layouts_ = resolveLayouts(o.layoutsSpec);
    if (o.force) {
        std::vector<std::string> inputs = {o.scenePath, o.envPath};
        for (const Layout& l : layouts_) inputs.push_back(l.sourceFile);
        refuseInputsInsideDirectory(o.outDir, inputs, "--out");
    }
    // The best-fit normal table (best_fit_normals.h), if a layout writes with it, is generated
    // while the scene loads and the device starts.
    if (std::any_of(layouts_.begin(), layouts_.end(), [](const Layout& l) { return usesBestFitTable(l); }))
        enc::prefetchBestFitNormalTable();
    inputs_ = loadSceneInputs(o.scenePath, o.envPath, float(o.width) / float(o.height),
                              GltfLoadOptions{o.allowOutsideScene});
    // Only the layers some material has: a scene without layers pays for none of the reference's
    // layer targets (loadReferenceLayout).
    referenceLayout_ = loadReferenceLayout(sceneShaderFeatures(inputs_.scene).layers);
    // A scene with materials drawn forward (transmission, volume): their pixels are left out of
    // every metric, which the CPU evaluation does, on whole frames (RunMetricsOptions::excluded).
    forwardScene_ = hasForwardMaterials(inputs_.scene);
    if (forwardScene_ && o.evalWhere == "gpu")
        throwUserError("gbufferlab compare: " + inputs_.scene.source +
                       " has materials drawn forward (KHR_materials_transmission or _volume), whose pixels only the CPU "
                       "evaluation leaves out of the metrics; give --eval cpu or auto");
    if (forwardScene_ && o.bandRowsGiven.value_or(0) > 0)
        throwUserError("gbufferlab compare: " + inputs_.scene.source +
                       " has materials drawn forward (KHR_materials_transmission or _volume), whose pixels are left out "
                       "of the metrics on whole frames only; give --band-rows 0 or auto");

}

// The Vulkan context (the suite's shared one, or this comparison's own), then where and how the
// metrics run (bands, the device evaluator), and the size and memory checks that depend on it.
void CompareSession::openDevice() {
    const CompareOptions& o = options_;
    std::optional<HostScope> contextScope(std::in_place, "set-up: Vulkan context");
    std::optional<VulkanContext>& context = shared_ ? shared_->ctx : ownCtx_;
    if (!context) context.emplace(DeviceOptions{o.device, o.validation});
    ctx_ = &*context;
    contextScope.reset();
    const VulkanContext& ctx = *ctx_;
    // --eval auto: the metrics run where the render ran. On a CPU device (lavapipe) that is the
    // CPU, where the measure library's vectorised code beats the same passes JIT-compiled by
    // llvmpipe (bench/RESULTS.md: warm 1080p compare 7.09x the GPU passes with --eval gpu,
    // 3.50x with --eval cpu, back to back); on a GPU it is the evaluate library's compute passes.
    // --band-rows auto: bands where a whole frame would not fit comfortably, i.e. on a CPU device
    // (device memory is host memory) at 4K-class sizes; never against the user's --eval cpu or for
    // a ground truth (it converges over the whole frame).
    const uint32_t bandRows = o.bandRowsGiven ? *o.bandRowsGiven
                              : (o.evalWhere == "cpu" || o.groundTruthAsked || forwardScene_)
                                  ? 0u
                                  : autoBandRows(ctx.info.type == VK_PHYSICAL_DEVICE_TYPE_CPU, o.width, o.height);
    bandPlan_ = planBands(o.height, bandRows, bandRows ? flipHaloRows() : 0u);
    // Whole frames: freed images stay with the allocator for the next run (host_heap.h); in bands
    // the peak memory is the point. (The device memory recycler on lavapipe as well, on top of
    // this: 18% more minor faults and 250 MB more peak for no faster run, 6 layouts x 3 views.)
    retainHostBlocks(!bandPlan_.banded());
    gpuEval_ = !forwardScene_ && (bandPlan_.banded() || o.evalWhere == "gpu" ||
                                  (o.evalWhere == "auto" && ctx.info.type != VK_PHYSICAL_DEVICE_TYPE_CPU));
    // A refusal of whole frames advises bands only where the other flags allow them.
    const std::string wholeFrameAdvice =
        o.temporalFrames > 1 ? "give a smaller --size or fewer --layouts (--temporal resolves whole frames, so it "
                               "takes no --band-rows)"
        : o.errorExr         ? "give a smaller --size or fewer --layouts (--error-exr needs whole frames), or drop "
                               "--error-exr and compare in bands (--band-rows 64)"
        : o.groundTruthAsked ? "give a smaller --size or fewer --layouts (the ground truth converges over whole "
                               "frames, so it takes no --band-rows)"
        : o.evalWhere == "cpu" ? "give a smaller --size or fewer --layouts, or compare in bands on the device "
                                 "evaluator (--eval auto --band-rows 64)"
                               : "give a smaller --size, or compare in bands (--band-rows 64)";
    validateResolution(ctx, o.width, o.height, "--size", bandPlan_.banded() ? bandPlan_.maxImageRows() : 0u,
                       wholeFrameAdvice);
    const uint32_t bandImageRows = bandPlan_.banded() ? bandPlan_.maxImageRows() : 0u;
    requireMemory(compareMemoryBytes(o.width, o.height, bandImageRows, layouts_.size(), o.viewCount, o.temporalFrames),
                  "--size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                      (bandImageRows ? " in bands of " + std::to_string(bandPlan_.bandRows) + " rows" : "") + " with " +
                      std::to_string(layouts_.size()) + " layout" + (layouts_.size() == 1 ? "" : "s") +
                      (o.temporalFrames > 1 ? " and --temporal " + std::to_string(o.temporalFrames) : ""),
                  bandImageRows ? "give a smaller --size or fewer --layouts" : wholeFrameAdvice);
    wiringOptions_.nativeFormats = o.nativeFormats;
}

// The report's description of the run: its inputs, device, flags and the notes they imply.
void CompareSession::describeRun() {
    const CompareOptions& o = options_;
    const VulkanContext& ctx = *ctx_;
    model_.run.scene = inputs_.scene.source;
    model_.run.environment = inputs_.environment.source;
    model_.run.width = int(o.width);
    model_.run.height = int(o.height);
    model_.run.device = {ctx.info.name, ctx.info.driver, ctx.info.typeName};
    model_.run.date = isoDate();
    model_.run.commandLine = o.commandLine;
    model_.run.iblModes = o.modeNames;
    model_.run.exposure = o.exposure;
    model_.run.exposureMethod = o.autoExposure ? kAutoExposureMethod : "fixed";
    model_.run.exrPrecision = exrPixelTypeName(o.exrType);
    model_.run.temporalFrames = o.temporalFrames;
    model_.run.temporalResolve = resolveMethodName(o.resolve);
    if (o.temporalFrames > 1) {
        for (const JitterOffset& j : temporalJitter(o.temporalFrames)) model_.run.temporalJitter.push_back({j.x, j.y});
        model_.run.notes.push_back(
            "temporal: " + std::to_string(o.temporalFrames) + " frames per view with Halton(2,3) sub-pixel jitter, "
            "resolved by " + (o.resolve == ResolveMethod::Mean ? std::string("their uniform mean in linear HDR")
                                                               : std::string("an exponential history (weight 0.1)")) +
            "; every image metric is the resolved image's, the attribute errors the temporal mean's; single-frame: "
            "frame 0 against the reference's frame 0. Not modelled: motion and reprojection, history rejection, "
            "upscalers");
    }
    model_.reference.layout = kReferenceLayout;
    for (const Layout& l : layouts_) model_.atlas.push_back(atlasEntryOf(l));
    model_.run.notes.push_back("split-sum BRDF LUT: " + brdfLutVariantName(o.iblSettings) + " (--brdf-lut)");
    // --eval gpu: one evaluator for every run (its working planes are allocated once).
    if (gpuEval_) {
        HostScope scope("set-up: GPU evaluator");
        evaluator_ = std::make_unique<GpuEvaluator>(ctx, o.width, o.height, bandPlan_.maxImageRows());
        model_.run.notes.push_back("metrics computed on the device (--eval gpu): quantiles from histograms (within "
                                   "0.1 %), worst regions on 8-pixel tiles, no errors.exr");
    }
    if (bandPlan_.banded()) {
        model_.run.notes.push_back(
            "rendered and measured in " + std::to_string(bandPlan_.bands.size()) + " bands of " +
            std::to_string(bandPlan_.bandRows) + " rows with " + std::to_string(bandPlan_.halo) +
            " rows of FLIP halo each side (--band-rows" + (o.bandRowsGiven ? "" : " auto") +
            "): the same numbers as whole frames; the reference is rendered again for every run, and the pass "
            "times are the layout's own, summed over its bands");
    }

}

// The views (the scene's camera and the placed ones, or a suite's cameras), the lighting model's
// reads per pixel from view 0, and the progress over every step the comparison will take.
void CompareSession::placeViews() {
    const CompareOptions& o = options_;
    views_ = o.cameras.empty() ? compareViews(inputs_.scene, o.viewCount, float(o.width) / float(o.height)) : placedViews(inputs_.scene, o.cameras);
    for (const CompareView& v : views_) model_.run.views.push_back(v.description);
    // --lighting volumes: the mean light volumes covering a pixel of view 0 (scene/light_coverage.h).
    lighting_ = o.lighting;
    if (lighting_.kind == LightingModel::Kind::Volumes && lighting_.counted && !views_.empty())
        lighting_.readsPerPixel = meanLightVolumesPerPixel(inputs_.scene.lights, views_.front().camera, o.width, o.height);
    model_.run.lighting = lighting_.text();
    if (lighting_.kind != LightingModel::Kind::Tiled)
        model_.run.notes.push_back("--lighting " + lighting_.text() + ": every traffic figure reads the G-buffer and "
                                   "depth that many times per pixel (light volumes)");
    viewExposures_.assign(views_.size(), o.exposure);
    if (o.viewCount > 1)
        model_.run.notes.push_back("every metric is the mean over " + std::to_string(o.viewCount) +
                                   " views (--views); images and crops are the first view's (the scene camera)");
    const int modeCount = int(o.modes.size());
    steps_ = o.viewCount * (modeCount * (1 + int(layouts_.size())) + (o.compareLighting() ? modeCount - 1 : 0));
    progress_.emplace(steps_, control_.progress);
}

// The output folder (marked incomplete until the report is written), the image writer, and the
// cancel token's action (the report of the runs that finished).
void CompareSession::openOutput() {
    const CompareOptions& o = options_;
    prepareOutputDirectory(o.outDir, o.force, "--out");
    // Until the report is complete the folder says so: an interruption (a cancel request: SIGINT,
    // SIGTERM on the command line) writes
    // the report of the runs that finished and leaves this file, naming the signal; a kill -9
    // leaves it as written here. The finished report removes it.
    incompleteMarker_ = o.outDir / kIncompleteMarker;
    writeFileAtomic(incompleteMarker_, "gbufferlab compare started " + model_.run.date +
                                           " and has not finished: this folder is incomplete\n");
    // Image files are written on a worker thread while the next run renders; at most two runs'
    // images wait (each job owns its images: memory stays bounded).
    // In bands a run's images span the frame while its bands do not: one run waits at most.
    // With many cores (a GPU workstation) two runs' files are written at once: each run's files
    // already go side by side, but one 4K PNG is one core's work and the next run is ready sooner.
    // GBL_WRITER_NICE=N (1-19) runs the files' encoders at that nice value (measurements): on
    // lavapipe they share the cores with the passes and stretch the passes' timestamps. At 19 the
    // default comparison's passes took 27.4 s against 32.9-33.2 s, for 1-3% less wall time and
    // 0.63 GB more peak memory (the writer falls behind and its queue holds images), so the
    // default stays 0 (bench/RESULTS.md, 2026-11-25).
    imageWriter_.emplace(bandPlan_.banded() || hardwareThreads() < 8 ? 1 : 2, bandPlan_.banded() ? 1 : 2,
                         writerNiceness());
    imageOutput_ = ImageOutput{&*imageWriter_, o.exrType, o.errorExr};
    // Several scenes: the comparison's own action (the report of the scenes that finished) runs
    // after this scene's partial report, and is put back when this scene is done.
    if (control_.cancel) {
        control_.cancel->setAction([this, outer = shared_ ? shared_->onInterrupt : std::function<void(int)>{}](int signal) {
            writeInterruptedReport(signal);
            if (outer) outer(signal);
        });
        interruptGuard_.token = control_.cancel;
        interruptGuard_.restore = shared_ ? shared_->onInterrupt : std::function<void(int)>{};
    }
}

// The renderer over this comparison's scene with the environment's IBL (one pre-computation per
// environment across a suite's scenes).
void CompareSession::createRenderer() {
    const CompareOptions& o = options_;
    const VulkanContext& ctx = *ctx_;
    std::optional<HostScope> rendererScope(std::in_place, "set-up: renderer and IBL");
    if (shared_) {  // one pre-computation per environment, whichever scenes it lights
        auto ibl = shared_->ibl.find(o.envPath);
        if (ibl == shared_->ibl.end())
            ibl = shared_->ibl.emplace(o.envPath, loadOrComputeIbl(ctx, inputs_.environment, o.iblSettings)).first;
        renderer_.emplace(ctx, inputs_.scene, inputs_.environment, ibl->second, &shared_->pipelines);
    } else {
        renderer_.emplace(ctx, inputs_.scene, inputs_.environment, loadOrComputeIbl(ctx, inputs_.environment, o.iblSettings));
    }
    rendererScope.reset();
}

CompareSession::InterruptActionGuard::~InterruptActionGuard() {
    if (token) token->setAction(restore);
}

// Every run renders the same way but for the IBL mode and the camera, and decodes its G-buffer
// for the metrics.
RenderSettings CompareSession::settingsFor(IblMode mode, int view) const {
    const CompareOptions& o = options_;
    RenderSettings settings;
    settings.camera = views_[size_t(view)].camera;
    settings.width = o.width;
    settings.height = o.height;
    settings.specularIbl = mode;
    settings.groundTruthSamples = o.gtBatchSamples;
    settings.splitSumShaderSamples = o.splitSumShaderSamples;
    settings.groundTruthNoiseTarget = o.gtNoise;
    settings.groundTruthMaxBatches = o.gtMaxBatches;
    settings.decodeSurfaces = true;
    settings.readTargetWords = false;
    settings.keepOnDevice = gpuEval_;
    // On a CPU device (lavapipe) with the metrics on the CPU, the read-back decodes the raw
    // target words with each layout's CPU codec instead of running the decode pass: the
    // codec's vectorised loops beat readGBuffer JIT-compiled by llvmpipe on the same cores,
    // and the words are a fraction of the decoded floats (bench/RESULTS.md, "Read-back on
    // the CPU codec"). On a GPU the decode pass is cheap and stays.
    settings.decodeOnCpu = !gpuEval_ && ctx_->info.type == VK_PHYSICAL_DEVICE_TYPE_CPU;
    return settings;
}

// Every run's pipelines are built now, side by side on worker threads (timed as shader compile),
// and reused by every view and IBL mode; a layout whose wiring or pipeline fails is left to fail
// in its own run.
void CompareSession::preparePipelines() {
    std::vector<GBufferWiring> wirings = {referenceWiring_};
    for (const Layout& layout : layouts_) {
        try {
            wirings.push_back(generateWiring(layout, wiringOptions_));
        } catch (const std::exception&) {
        }
    }
    RenderSettings decodeSettings = settingsFor(options_.modes[0], 0);
    if (bandPlan_.banded()) decodeSettings.bandRows = bandPlan_.bands.front().imageRows;
    renderer_->preparePipelines(wirings, decodeSettings, options_.modes);
    if (decodeSettings.decodeOnCpu) {
        std::vector<std::string> onDevice;
        for (const GBufferWiring& w : wirings)
            if (!Renderer::decodesOnCpu(w, decodeSettings)) onDevice.push_back(w.layoutName);
        model_.run.notes.push_back(
            "read-back: G-buffer words decoded on the host by each layout's CPU codec (the bit-exact mirror of "
            "readGBuffer), not by the decode pass" +
            (onDevice.empty() ? std::string() : "; by the decode pass: " + joinList(onDevice)));
    }
}

// The same exposure for the reference and every layout of the view: the engine's, metered on the
// reference (its first IBL mode) as UE4's histogram auto-exposure does (auto_exposure.h). The
// covered fraction says how much of the view the scene fills (the rest is environment).
void CompareSession::observeView(int view, const Image& referenceHdr, bool meter) {
    size_t covered = 0;
    const size_t n = referenceHdr.pixelCount();
    if (referenceHdr.channels == 4)
        for (size_t i = 0; i < n; ++i) covered += referenceHdr.pixels[i * 4 + 3] >= 0.5f ? 1 : 0;
    const double fraction = n ? double(covered) / double(n) : 0.0;
    std::optional<double> metered;
    if (meter) {
        metered = double(float(gbl::meterExposure(referenceHdr).exposure));
        viewExposures_.at(size_t(view)) = float(*metered);
    }
    // A view that shows nothing a layout can change (no geometry; a reference clipped to black or
    // white) would score every layout PSNR inf, FLIP 0: it is measured by no metric, and said so.
    const std::string nothing = nothingToMeasure(referenceHdr, exposure(view));
    std::lock_guard lock(modelMutex_);
    model_.run.viewCoverage.resize(views_.size(), 0.0);
    model_.run.viewCoverage[size_t(view)] = fraction;
    model_.run.viewNotMeasured.resize(views_.size());
    model_.run.viewNotMeasured[size_t(view)] = nothing;
    if (!metered) return;
    model_.run.viewExposures.resize(views_.size(), 0.0);
    model_.run.viewExposures[size_t(view)] = *metered;
    if (view == 0) model_.run.exposure = *metered;  // the images' (view 0's)
}

std::string CompareSession::viewNotMeasured(int view) {
    std::lock_guard lock(modelMutex_);
    const auto& why = model_.run.viewNotMeasured;
    return size_t(view) < why.size() ? why[size_t(view)] : std::string();
}

void CompareSession::finishRuns(ReportModel& model) const {
    for (RunReport& r : model.runs) finishViews(r, model.run.viewNotMeasured);
    // Bandwidth as GPUs pay it: every run of a layout whose view-0 words were measured (the
    // G-buffer is the same under every IBL mode).
    for (RunReport& r : model.runs) {
        const auto c = compression_.find(r.layout);
        if (c == compression_.end() || r.status != RunStatus::Ok) continue;
        for (const Layout& layout : layouts_)
            if (layout.name == r.layout) r.effective = computeEffectiveBandwidth(layout, c->second, 1, lighting_);
    }
    // The note that says what the means are over says which views they leave out.
    for (size_t v = 0; v < model.run.viewNotMeasured.size(); ++v)
        if (!model.run.viewNotMeasured[v].empty())
            model.run.notes.push_back("view " + std::to_string(v) + " is not measured (" + model.run.viewNotMeasured[v] +
                                      "): it is in no mean, spread, rank or verdict");
}

RunReport CompareSession::makeRun(const Layout& layout, const std::string& mode) const {
    RunReport run;
    run.layout = layout.name;
    run.title = layout.title;
    run.source = layout.source.text();
    run.pipeline = pipelineName(layout.pipeline);
    run.iblMode = mode;
    const BandwidthReport bw = computeBandwidth(layout, options_.width, options_.height);
    run.bytesPerPixel = bytesPerPixelOf(bw);
    run.bandwidth = bw.frames;
    if (lighting_.readsPerPixel != 1.0)  // --lighting volumes: the lighting pass reads that many times
        for (FrameTraffic& f : run.bandwidth) f = computeFrameTraffic(layout, f.width, f.height, f.samples, lighting_);
    return run;
}

void CompareSession::record(RunReport&& run, int view) {
    std::lock_guard lock(modelMutex_);
    // A view with nothing to measure adds no numbers: its metrics are left out of every mean.
    if (run.status == RunStatus::Ok && size_t(view) < model_.run.viewNotMeasured.size() &&
        !model_.run.viewNotMeasured[size_t(view)].empty())
        clearMeasurements(run);
    if (view == 0) {
        if (run.status == RunStatus::Ok) {
            run.views.push_back({run.attributes, run.image});
            addSingleFrameView(run, run);
        }
        model_.runs.push_back(std::move(run));
    } else {
        RunReport& first = model_.runs.at(runIndex_);
        if (first.status == RunStatus::Ok) {
            if (run.status == RunStatus::Ok) {
                first.views.push_back({run.attributes, run.image});
                addSingleFrameView(first, run);
            } else {
                first.status = RunStatus::Failed;
                first.error = "view " + std::to_string(view) + ": " + run.error;
            }
        }
    }
    ++runIndex_;
}

// SIGINT, SIGTERM (a cancel request): the report of the runs that finished, the folder left marked
// incomplete. Once: a second request, or interrupted() after the action, finds it written.
void CompareSession::writeInterruptedReport(int signal) {
    ReportModel partial;
    {
        std::lock_guard lock(modelMutex_);
        if (reportComplete_ || interruptionStarted_) return;
        interruptionStarted_ = true;
        partial = model_;
    }
    // Every run in `partial` queued its images before it was recorded: they are written before
    // the report that names them (a job writes through temporaries as always).
    imageWriter_->drain();
    std::lock_guard lock(modelMutex_);
    if (reportComplete_) return;
    // What never ran is said, to people and to programs: a run of view 0 not reached has no row
    // (interruption.notRun, named by the verdict where it fits a budget); a row whose later views
    // were not reached is the mean of the views it has, and names the others.
    const std::string signalText = signalName(signal);
    ReportInterruption interruption;
    interruption.signal = signalText;
    interruption.runsPlanned = int(layouts_.size() * options_.modes.size()) +
                               (options_.compareLighting() ? int(options_.modes.size()) - 1 : 0);
    for (const std::string& mode : options_.modeNames)
        for (const Layout& layout : layouts_) {
            const bool ran = std::any_of(partial.runs.begin(), partial.runs.end(), [&](const RunReport& r) {
                return r.layout == layout.name && r.iblMode == mode;
            });
            if (ran) continue;
            const RunReport planned = makeRun(layout, mode);
            interruption.notRun.push_back({layout.name, mode, planned.bytesPerPixel.total, verdictCountedBytes(planned)});
        }
    const size_t viewCount = views_.size();
    for (RunReport& r : partial.runs) {
        const bool allViews = r.status != RunStatus::Ok || r.views.size() >= viewCount;
        if (allViews) {
            ++interruption.runsFinished;
            continue;
        }
        r.notMeasured = "views " + std::to_string(r.views.size()) + "-" + std::to_string(viewCount - 1) +
                        ": not run (interrupted by " + signalText + ")";
    }
    finishRuns(partial);
    partial.interruption = interruption;
    const std::string what = "INCOMPLETE: interrupted by " + signalText + " after " +
                             std::to_string(interruption.runsFinished) + " of " +
                             std::to_string(interruption.runsPlanned) +
                             " runs; this report lists only the runs that finished" +
                             (interruption.notRun.empty() ? std::string()
                                                          : " (" + std::to_string(interruption.notRun.size()) +
                                                                " not run at all)");
    partial.run.notes.push_back(what);
    writeReport(options_.outDir, partial);
    writeFileAtomic(incompleteMarker_, what + "\n");
    interruptedReport_ = std::move(partial);
}

app::CompareResult CompareSession::finish() {
    const fs::path& outDir = options_.outDir;
    {
        std::lock_guard lock(modelMutex_);
        finishRuns(model_);
        ScopedStage timed(Stage::Report);
        model_.significance = rankWithSignificance(model_);
        model_.classSignificance = rankLayerClassesWithSignificance(model_);
    }

    app::CompareResult result;
    result.outDir = outDir;
    std::vector<std::string> writeErrors;  // image files of no run (the references', the figure)
    {
        ScopedStage timed(Stage::Report);
        // What is still being written is waited for here, so the report names only files that
        // exist. A run whose images could not be written fails, as it did when they were written
        // in line; any other file that could not be written is an error of the command.
        std::lock_guard lock(modelMutex_);
        std::optional<HostScope> finishScope(std::in_place, "report: waiting for the image files");
        std::vector<WriteFailure> failures = imageWriter_->finish();
        finishScope.reset();
        HostScope reportScope("report: html, json, csv");
        writeErrors = failRunsOfWriteFailures(model_, failures);
        writeReport(outDir, model_);
        result.timings = collectTimings(StageClock::global().read(), gpuPassMs_,
                                        ctx_->info.type == VK_PHYSICAL_DEVICE_TYPE_CPU);
        writeTimings(outDir, *result.timings);
        std::error_code ec;
        fs::remove(incompleteMarker_, ec);
        reportComplete_ = true;
    }
    if (interruptGuard_.token) interruptGuard_.token->setAction(interruptGuard_.restore);
    interruptGuard_.token = nullptr;
    hostProfileAdd("compare: up to the report (then teardown)", StageClock::global().read().totalMs / 1e3);
    result.report = model_;
    // A file that could not be written is an error of the command, one line each, never lost.
    result.errors = writeErrors;
    // The report lists what failed and why; the exit status says that something did, so that
    // scripts and CI notice (2 runs failed of 7: exit 4).
    const auto failed = std::count_if(model_.runs.begin(), model_.runs.end(),
                                      [](const RunReport& r) { return r.status == RunStatus::Failed; });
    // No view had anything to measure: the report says why, and the exit status that nothing was.
    const auto& why = model_.run.viewNotMeasured;
    if (!why.empty() && std::none_of(why.begin(), why.end(), [](const std::string& w) { return w.empty(); })) {
        result.errors.push_back("no view had anything to measure (view 0: " + why.front() +
                                "); no layout was measured (see " + escapeText((outDir / "report.html").string()) + ")");
        result.exitStatus = kExitRunsFailed;
    } else if (failed > 0) {
        result.errors.push_back(std::to_string(failed) + " of " + std::to_string(model_.runs.size()) +
                                " runs failed (see the FAILED rows above and in " +
                                escapeText((outDir / "report.html").string()) + ")");
        result.exitStatus = kExitRunsFailed;
    } else {
        result.exitStatus = writeErrors.empty() ? 0 : 1;
    }
    return result;
}

app::CompareResult CompareSession::interrupted(int signal) {
    // An action running on the asking thread is waited for, and none runs after.
    if (interruptGuard_.token) interruptGuard_.token->setAction(interruptGuard_.restore);
    interruptGuard_.token = nullptr;
    writeInterruptedReport(signal);  // unless the action wrote it
    app::CompareResult result;
    result.interruptedBy = signal;
    result.exitStatus = 128 + signal;
    result.outDir = options_.outDir;
    std::lock_guard lock(modelMutex_);
    result.report = interruptedReport_;
    return result;
}

}  // namespace gbl::compare
