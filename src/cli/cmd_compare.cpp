// `gbufferlab compare`: the product's main job. Renders the float reference and every chosen
// layout (under every chosen IBL mode) at the same camera, measures attribute and image error,
// writes error images, the bandwidth model and report.html / report.json / report.csv.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include <nlohmann/json.hpp>
#include <sstream>

#include "background_writer.h"
#include "bandwidth.h"
#include "cli_args.h"
#include "color_map.h"
#include "commands.h"
#include "compare_bands.h"
#include "compare_console.h"
#include "compare_runs.h"
#include "compare_views.h"
#include "error.h"
#include "error_images.h"
#include "file_io.h"
#include "ibl_cache.h"
#include "ibl_figure.h"
#include "ibl_precompute.h"
#include "image_io.h"
#include "interrupt.h"
#include "layout_atlas.h"
#include "layout_catalog.h"
#include "env_flag.h"
#include "host_heap.h"
#include "host_profile.h"
#include "parallel_for.h"
#include "parallel_invoke.h"
#include "progress.h"
#include "renderer.h"
#include "report_html.h"
#include "report_model.h"
#include "run_metrics.h"
#include "scene_inputs.h"
#include "shader_cache.h"
#include "stage_clock.h"
#include "tone_map.h"
#include "view_stats.h"
#include "vk_context.h"
#include "wiring_codegen.h"
#include "worst_regions.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {

constexpr const char* kReferenceLayout = "reference";
constexpr const char* kGroundTruth = "ground-truth";
// In the output folder while it is incomplete (see runCompareCommand).
constexpr const char* kIncompleteMarker = "INCOMPLETE";
// Exit status when the report was written but some runs failed (1: bad input, 2: usage, 3: bug).
constexpr int kExitRunsFailed = 4;

std::string joinList(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
    return out;
}

// Resolves --layouts: "all" (or no flag) = every file in layouts/ but the reference; otherwise
// names or paths. Every file is parsed and validated here, before any rendering.
std::vector<Layout> resolveLayouts(const std::optional<std::string>& spec) {
    std::vector<std::string> names;
    const std::vector<std::string> known = listLayoutNames();
    const std::vector<std::string> given = spec ? splitFlagList(*spec, "--layouts") : std::vector<std::string>{"all"};
    if (given.size() > 1 && std::find(given.begin(), given.end(), "all") != given.end())
        throwUserError("--layouts " + quoteName(*spec) + ": 'all' already names every layout; give all alone, or names");
    if (given.front() == "all") {
        for (const auto& n : known)
            if (n != kReferenceLayout) names.push_back(n);
    } else {
        names = given;
    }
    std::vector<Layout> layouts;
    for (const std::string& n : names) {
        const bool isPath = n.find('/') != std::string::npos || n.find(".toml") != std::string::npos;
        if (!isPath && std::find(known.begin(), known.end(), n) == known.end())
            throwUserError("--layouts: unknown layout " + quoteName(n) + " (known: " + joinList(known) + ", or all)");
        layouts.push_back(loadLayout(n));
    }
    return layouts;
}

int writerNiceness() { return int(std::clamp(envLong("GBL_WRITER_NICE").value_or(0), 0L, 19L)); }

std::string isoDate() {
    const std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return buf;
}

}  // namespace

int runCompareCommand(const std::vector<std::string>& args) {
    using namespace compare;
    const std::vector<FlagSpec> specs = {
        {"scene", "FILE", "glTF 2.0 scene (.gltf/.glb); default: the built-in scene (the sphere grid and its surroundings)"},
        {"env", "FILE", "equirectangular environment (.hdr/.exr); default: the built-in sky"},
        {"allow-outside-scene", "", "let the scene's buffer and image URIs point outside its folder"},
        {"layouts", "A,B,...", "layouts to compare (names in layouts/ or .toml paths), or all (default)"},
        {"ibl", "MODES", "specular IBL modes, comma-separated (default split-sum; known: " +
                             joinList(iblModeNames()) + ")"},
        {"samples", "N", "samples per pixel of the split-sum-shader IBL mode (default 1024)"},
        {"gt-noise", "X", "ground truth: add batches until the mean relative noise (standard error of the "
                          "luminance / luminance) over covered pixels is at most X (default 0.002)"},
        {"gt-batch-samples", "N", "ground truth: steps per batch, each one GGX + one environment sample (default 64)"},
        {"gt-max-batches", "N", "ground truth: stop after N batches even if the noise target is not met (default 256)"},
        {"brdf-lut", "VARIANT", "split-sum BRDF LUT: converged (visible-normal sampling, 4096 samples; default) or "
                                "seed (the seed's IntegrateBRDF, 1024 samples)"},
        {"size", "WxH", "image size (default 1920x1080)"},
        {"views", "N", "cameras measured (default 3: the scene camera, an orbit about the scene's centre, a grazing "
                       "view of the ground; more add orbit views); every metric is the mean over them with its "
                       "spread; per-pixel images are the first view's"},
        {"out", "DIR", "output directory, new or empty (default: out/compare-<time>)"},
        {"force", "", "write into a non-empty --out directory, replacing files of the same name"},
        {"device", "NAME", "cpu (lavapipe, default), gpu, an index or a name from `gbufferlab devices`"},
        {"exposure", "X", "exposure for tone-mapped images and their metrics (default 1)"},
        {"native-formats", "", "render targets in their real UNORM/SRGB/float formats where the layout allows"},
        {"hdr-flip", "", "also compute HDR-FLIP over the linear images (costs one FLIP per exposure: 14 on the "
                         "built-in sky)"},
        {"no-hdr-flip", "", "skip HDR-FLIP (the default; kept for older scripts)"},
        {"float32-exr", "", "write the EXR files (renders, errors.exr) as 32-bit float instead of half (16-bit "
                            "float: half the bytes; values within 2^-11 relative, clamped to +-65504)"},
        {"eval", "WHERE", "where the metrics are computed: auto (default: gpu on a GPU, cpu on a CPU device such as "
                          "lavapipe), gpu (compute passes beside the render, only numbers and 8-bit images come "
                          "back, no errors.exr) or cpu (the measure library, the oracle)"},
        {"band-rows", "N|auto", "render and measure the frame in bands of N rows (a multiple of 8), each with FLIP's "
                                "halo, on the device evaluator: bounded memory at 4K, at the price of rendering the "
                                "reference again for every run; 0: whole frames; auto (default): bands of " +
                                    std::to_string(kAutoBandRows) + " rows on a CPU device above " +
                                    std::to_string(kAutoBandPixels) + " pixels, unless --eval cpu or ground-truth"},
        {"validation", "", "enable Vulkan validation layers"},
        {"help", "", "show this help"},
    };
    const ParsedArgs parsed = parseArgs("compare", args, specs);
    if (parsed.has("help")) {
        std::printf("%s", formatHelp("gbufferlab compare [--scene F] [--env F] [--layouts A,B,...|all] [--ibl MODES] "
                                     "[--size WxH] [--out DIR]",
                                     "Renders the float reference and each layout at the same camera, and reports "
                                     "what each loses\n(attribute and image error, FLIP, error images) and costs "
                                     "(bytes per pixel, bandwidth).\nWith --ibl listing several modes and "
                                     "ground-truth among them, the reference under each mode is also\ncompared with "
                                     "the reference under ground-truth: the error of the lighting approximation.",
                                     specs)
                               .c_str());
        return 0;
    }
    if (!parsed.positional.empty())
        throwUserError("gbufferlab compare: unexpected argument '" + parsed.positional[0] + "' (see --help)");
    StageClock::global().start();
    std::optional<ScopedStage> timedSetup(std::in_place, Stage::Setup);
    const auto [width, height] = parseSize(parsed.get("size", "1920x1080"), "--size");
    const float exposure = parsePositiveFloatFlag(parsed, "exposure", 1.0f);
    const int viewCount = parseIntFlag(parsed, "views", 3, 1, 16);
    std::vector<IblMode> modes;
    std::vector<std::string> modeNames = splitFlagList(parsed.get("ibl", "split-sum"), "--ibl");
    for (const auto& n : modeNames) modes.push_back(parseIblMode(n));
    const int splitSumShaderSamples = parseIntFlag(parsed, "samples", 1024, 1, 65536);
    const int gtBatchSamples = parseIntFlag(parsed, "gt-batch-samples", 64, 1, 65536);
    const int gtMaxBatches = parseIntFlag(parsed, "gt-max-batches", 256, 8, 65536);
    const double gtNoise = parsePositiveFloatFlag(parsed, "gt-noise", 0.002f);
    IblSettings iblSettings;
    if (parsed.has("brdf-lut")) applyBrdfLutVariant(parsed.get("brdf-lut"), iblSettings);
    const fs::path outDir = parsed.has("out") ? fs::path(parsed.get("out")) : defaultOutputDirectory("compare");
    const bool force = parsed.has("force");
    if (parsed.has("hdr-flip") && parsed.has("no-hdr-flip"))
        throwUserError("gbufferlab compare: --hdr-flip and --no-hdr-flip contradict each other; give one");
    const bool hdrFlip = parsed.has("hdr-flip");
    const ExrPixelType exrType = parsed.has("float32-exr") ? ExrPixelType::Float32 : ExrPixelType::Half;
    const std::string evalWhere = parsed.get("eval", "auto");
    if (evalWhere != "gpu" && evalWhere != "cpu" && evalWhere != "auto")
        throwUserError("gbufferlab compare: --eval " + evalWhere + ": give auto, gpu or cpu");
    const bool groundTruthAsked = std::find(modes.begin(), modes.end(), IblMode::GroundTruth) != modes.end();
    const std::optional<uint32_t> bandRowsGiven =
        parseBandRowsFlag(parsed.get("band-rows", "auto"), evalWhere == "cpu", groundTruthAsked);
    checkOutputDirectory(outDir, force, "--out");

    // Everything the user gave is read and validated before the first pixel is rendered.
    const std::vector<Layout> layouts =
        resolveLayouts(parsed.has("layouts") ? std::optional<std::string>(parsed.get("layouts")) : std::nullopt);
    const Layout referenceLayout = loadLayout(kReferenceLayout);
    const SceneInputs inputs = loadSceneInputs(parsed.get("scene"), parsed.get("env"), float(width) / float(height),
                                                GltfLoadOptions{parsed.has("allow-outside-scene")});

    std::optional<HostScope> contextScope(std::in_place, "set-up: Vulkan context");
    VulkanContext ctx(DeviceOptions{parsed.get("device"), parsed.has("validation")});
    contextScope.reset();
    // --eval auto: the metrics run where the render ran. On a CPU device (lavapipe) that is the
    // CPU, where the measure library's vectorised code beats the same passes JIT-compiled by
    // llvmpipe (bench/RESULTS.md: warm 1080p compare 7.09x the GPU passes with --eval gpu,
    // 3.50x with --eval cpu, back to back); on a GPU it is the evaluate library's compute passes.
    // --band-rows auto: bands where a whole frame would not fit comfortably, i.e. on a CPU device
    // (device memory is host memory) at 4K-class sizes; never against the user's --eval cpu or for
    // a ground truth (it converges over the whole frame).
    const uint32_t bandRows = bandRowsGiven ? *bandRowsGiven
                              : (evalWhere == "cpu" || groundTruthAsked)
                                  ? 0u
                                  : autoBandRows(ctx.info.type == VK_PHYSICAL_DEVICE_TYPE_CPU, width, height);
    const BandPlan bandPlan = planBands(height, bandRows, bandRows ? flipHaloRows() : 0u);
    // Whole frames: freed images stay with the allocator for the next run (host_heap.h); in bands
    // the peak memory is the point. (The device memory recycler on lavapipe as well, on top of
    // this: 18% more minor faults and 250 MB more peak for no faster run, 6 layouts x 3 views.)
    retainHostBlocks(!bandPlan.banded());
    const bool gpuEval = bandPlan.banded() || evalWhere == "gpu" ||
                         (evalWhere == "auto" && ctx.info.type != VK_PHYSICAL_DEVICE_TYPE_CPU);
    validateResolution(ctx, width, height, "--size");
    WiringOptions wiringOptions;
    wiringOptions.nativeFormats = parsed.has("native-formats");

    ReportModel model;
    model.run.scene = inputs.scene.source;
    model.run.environment = inputs.environment.source;
    model.run.width = int(width);
    model.run.height = int(height);
    model.run.device = {ctx.info.name, ctx.info.driver, ctx.info.typeName};
    model.run.date = isoDate();
    model.run.commandLine = "gbufferlab compare";
    for (const auto& a : args) model.run.commandLine += " " + a;
    model.run.iblModes = modeNames;
    model.run.exposure = exposure;
    model.run.exrPrecision = exrPixelTypeName(exrType);
    model.reference.layout = kReferenceLayout;
    for (const Layout& l : layouts) model.atlas.push_back(atlasEntryOf(l));
    model.run.notes.push_back("split-sum BRDF LUT: " + brdfLutVariantName(iblSettings) + " (--brdf-lut)");
    // --eval gpu: one evaluator for every run (its working planes are allocated once).
    std::unique_ptr<GpuEvaluator> evaluator;
    if (gpuEval) {
        HostScope scope("set-up: GPU evaluator");
        evaluator = std::make_unique<GpuEvaluator>(ctx, width, height, bandPlan.maxImageRows());
        model.run.notes.push_back("metrics computed on the device (--eval gpu): quantiles from histograms (within "
                                  "0.1 %), worst regions on 8-pixel tiles, no errors.exr");
    }
    if (bandPlan.banded()) {
        model.run.notes.push_back(
            "rendered and measured in " + std::to_string(bandPlan.bands.size()) + " bands of " +
            std::to_string(bandPlan.bandRows) + " rows with " + std::to_string(bandPlan.halo) +
            " rows of FLIP halo each side (--band-rows" + (bandRowsGiven ? "" : " auto") +
            "): the same numbers as whole frames; the reference is rendered again for every run, and the pass "
            "times are the layout's own, summed over its bands");
    }

    const bool compareLighting = modes.size() > 1 &&
                                 std::find(modeNames.begin(), modeNames.end(), kGroundTruth) != modeNames.end();
    const std::vector<CompareView> views = compareViews(inputs.scene, viewCount);
    for (const CompareView& v : views) model.run.views.push_back(v.description);
    if (viewCount > 1)
        model.run.notes.push_back("every metric is the mean over " + std::to_string(viewCount) +
                                  " views (--views); images and crops are the first view's (the scene camera)");
    const int steps =
        viewCount * (int(modes.size()) * (1 + int(layouts.size())) + (compareLighting ? int(modes.size()) - 1 : 0));
    Progress progress(steps, stderr);
    prepareOutputDirectory(outDir, force, "--out");
    // Until the report is complete the folder says so: an interruption (SIGINT, SIGTERM) writes
    // the report of the runs that finished and leaves this file, naming the signal; a kill -9
    // leaves it as written here. The finished report removes it.
    const fs::path incompleteMarker = outDir / kIncompleteMarker;
    writeFileAtomic(incompleteMarker, "gbufferlab compare started " + model.run.date +
                                          " and has not finished: this folder is incomplete\n");
    std::mutex modelMutex;  // model.runs, shared with the interrupt action
    bool reportComplete = false;
    // Image files are written on a worker thread while the next run renders; at most two runs'
    // images wait (each job owns its images: memory stays bounded).
    // In bands a run's images span the frame while its bands do not: one run waits at most.
    // With many cores (a GPU workstation) two runs' files are written at once: each run's files
    // already go side by side, but one 4K PNG is one core's work and the next run is ready sooner.
    // GBL_WRITER_NICE=N (1-19) runs the files' encoders at that nice value (measurements): on
    // lavapipe they share the cores with the passes and stretch the passes' timestamps. At 19 the
    // default comparison's passes took 27.4 s against 32.9-33.2 s, for 1-3% less wall time and
    // 0.63 GB more peak memory (the writer falls behind and its queue holds images), so the
    // default stays 0 (bench/RESULTS.md, eighth session).
    BackgroundWriter imageWriter(bandPlan.banded() || hardwareThreads() < 8 ? 1 : 2, bandPlan.banded() ? 1 : 2,
                                 writerNiceness());
    const ImageOutput imageOutput{&imageWriter, exrType};
    // The action below uses this function's locals: it is cleared on every way out (an exception
    // included), before they are destroyed.
    struct ClearInterruptAction {
        ~ClearInterruptAction() { setInterruptAction({}); }
    } clearInterruptAction;
    setInterruptAction([&](int signal) {
        ReportModel partial;
        {
            std::lock_guard lock(modelMutex);
            if (reportComplete) return;
            partial = model;
        }
        // Every run in `partial` queued its images before it was recorded: they are written
        // before the report that names them (a job writes through temporaries as always).
        imageWriter.drain();
        std::lock_guard lock(modelMutex);
        if (reportComplete) return;
        for (RunReport& r : partial.runs) finishViews(r);
        const std::string what = std::string("INCOMPLETE: interrupted by ") + signalName(signal) + " after " +
                                 std::to_string(partial.runs.size()) + " of " + std::to_string(steps - int(modes.size())) +
                                 " runs; this report lists only the runs that finished";
        partial.run.notes.push_back(what);
        writeReport(outDir, partial);
        writeFileAtomic(incompleteMarker, what + "\n");
    });
    timedSetup.reset();
    double gpuPassMs = 0.0;  // timestamps of every frame rendered

    // Every run renders the same way but for the IBL mode, and decodes its G-buffer for metrics.
    auto settingsFor = [&](IblMode mode, int view) {
        RenderSettings settings;
        settings.camera = views[size_t(view)].camera;
        settings.width = width;
        settings.height = height;
        settings.specularIbl = mode;
        settings.groundTruthSamples = gtBatchSamples;
        settings.splitSumShaderSamples = splitSumShaderSamples;
        settings.groundTruthNoiseTarget = gtNoise;
        settings.groundTruthMaxBatches = gtMaxBatches;
        settings.decodeSurfaces = true;
        settings.readTargetWords = false;
        settings.keepOnDevice = gpuEval;
        // On a CPU device (lavapipe) with the metrics on the CPU, the read-back decodes the raw
        // target words with each layout's CPU codec instead of running the decode pass: the
        // codec's vectorised loops beat readGBuffer JIT-compiled by llvmpipe on the same cores,
        // and the words are a fraction of the decoded floats (bench/RESULTS.md, "Read-back on
        // the CPU codec"). On a GPU the decode pass is cheap and stays.
        settings.decodeOnCpu = !gpuEval && ctx.info.type == VK_PHYSICAL_DEVICE_TYPE_CPU;
        return settings;
    };
    std::optional<HostScope> rendererScope(std::in_place, "set-up: renderer and IBL");
    Renderer renderer(ctx, inputs.scene, inputs.environment, loadOrComputeIbl(ctx, inputs.environment, iblSettings));
    rendererScope.reset();
    const GBufferWiring referenceWiring = generateWiring(referenceLayout, {});
    {
        // Every run's pipelines are built now, side by side on worker threads (timed as shader
        // compile), and reused by every view and IBL mode; a layout whose wiring or pipeline
        // fails is left to fail in its own run.
        std::vector<GBufferWiring> wirings = {referenceWiring};
        for (const Layout& layout : layouts) {
            try {
                wirings.push_back(generateWiring(layout, wiringOptions));
            } catch (const std::exception&) {
            }
        }
        RenderSettings decodeSettings = settingsFor(modes[0], 0);
        if (bandPlan.banded()) decodeSettings.bandRows = bandPlan.bands.front().imageRows;
        renderer.preparePipelines(wirings, decodeSettings, modes);
        if (decodeSettings.decodeOnCpu) {
            std::vector<std::string> onDevice;
            for (const GBufferWiring& w : wirings)
                if (!Renderer::decodesOnCpu(w, decodeSettings)) onDevice.push_back(w.layoutName);
            model.run.notes.push_back(
                "read-back: G-buffer words decoded on the host by each layout's CPU codec (the bit-exact mirror of "
                "readGBuffer), not by the decode pass" +
                (onDevice.empty() ? std::string() : "; by the decode pass: " + joinList(onDevice)));
        }
    }
    // compare --views: every view renders the references and every run again; the runs of views
    // after the first add their metrics to the first view's run (RunReport::views), in the same order.
    for (int view = 0; view < viewCount; ++view) {
        const bool firstView = view == 0;
        const std::string viewLabel = viewCount > 1 ? " [view " + std::to_string(view) + "]" : "";
        size_t runIndex = 0;
        auto record = [&](RunReport&& run) {
            std::lock_guard lock(modelMutex);
            if (firstView) {
                    if (run.status == RunStatus::Ok) run.views.push_back({run.attributes, run.image});
                    model.runs.push_back(std::move(run));
                } else {
                    RunReport& first = model.runs.at(runIndex);
                    if (first.status == RunStatus::Ok) {
                        if (run.status == RunStatus::Ok) {
                            first.views.push_back({run.attributes, run.image});
                        } else {
                            first.status = RunStatus::Failed;
                            first.error = "view " + std::to_string(view) + ": " + run.error;
                        }
                    }
            }
            ++runIndex;
        };
        std::map<std::string, ReferenceRender> references;
        size_t bandedReferenceMode = 0;  // in bands: whose statistics the evaluator holds
        for (size_t m = 0; m < modes.size(); ++m) {
            progress.begin("reference / " + modeNames[m] + viewLabel);
            ReferenceRender ref;
            if (bandPlan.banded()) {  // its statistics into the evaluator, its HDR image for the files
                ref.output.timings = renderReferenceInBands(renderer, referenceWiring, settingsFor(modes[m], view),
                                                            bandPlan, *evaluator, exposure,
                                                            firstView ? &ref.output.hdr : nullptr);
                bandedReferenceMode = m;
            } else {
                ref.output = renderer.render(referenceWiring, settingsFor(modes[m], view));
            }
            gpuPassMs += ref.output.timings.gbufferMs + ref.output.timings.lightingMs;
            // --eval gpu keeps the render on the device; its files (and the IBL figure) need it here.
            const bool hostHdr = firstView || compareLighting;
            if (gpuEval && !bandPlan.banded() && ref.output.hdr.empty() && hostHdr) {
                ScopedStage timed(Stage::Readback);
                ref.output.hdr = ref.output.device->downloadHdr();
            }
            if (firstView) {
            ref.renderPng = "reference-" + modeNames[m] + ".png";
            const std::string renderExr = "reference-" + modeNames[m] + ".exr";
            ScopedStage timed(Stage::Report);
            const std::string preview = "reference-" + modeNames[m] + "-log.png";
            imageWriter.enqueue("images of the reference / " + modeNames[m],
                                [png = (outDir / ref.renderPng).string(), exr = (outDir / renderExr).string(),
                                 log = (outDir / preview).string(), exposure, exrType,
                                 hdr = gpuEval && !compareLighting  // the files are its last use
                                           ? std::make_shared<const Image>(std::move(ref.output.hdr))
                                           : std::make_shared<const Image>(ref.output.hdr)] {
                                    // Side by side (each file is one core's work: 4K on a GPU)
                                    parallelInvoke({[&] { writePng(png, toneMapToSrgb8(*hdr, exposure)); },
                                                    [&] { writeExr(exr, *hdr, {}, exrType); },
                                                    [&] { writePng(log, logEncodeForPreview(*hdr)); }});
                                });
            model.reference.images.push_back({modeNames[m], ref.renderPng, renderExr, preview});
            }
            std::string gtNote;
            if (modes[m] == IblMode::GroundTruth) {
                const GroundTruthStats& g = ref.output.groundTruth;
                char buf[256];
                std::snprintf(buf, sizeof(buf),
                              "ground truth: %d batches x %d steps (%d samples per pixel, GGX + environment by MIS), mean "
                              "relative noise %.5f (target %.5f%s), lighting %.0f ms GPU on %s",
                              g.batches, gtBatchSamples, g.samplesPerPixel, g.meanRelativeNoise, g.targetRelativeNoise,
                              g.targetMet ? ", met" : ", NOT met", g.lightingMs, ctx.info.name.c_str());
                gtNote = buf;
                std::lock_guard lock(modelMutex);
                model.run.notes.push_back(gtNote + viewLabel);
            }
            progress.end("G-buffer " + std::to_string(int(ref.output.timings.gbufferMs)) + " ms, lighting " +
                         std::to_string(int(ref.output.timings.lightingMs)) + " ms" +
                         (gtNote.empty() ? "" : ", " + std::to_string(ref.output.groundTruth.batches) + " batches"));
            ReferenceRender& stored = references[modeNames[m]] = std::move(ref);
            if (gpuEval) {
                stored.evaluator = evaluator.get();
                if (!compareLighting) stored.output.hdr = Image{};  // written; the metrics read the device's
                continue;
            }
            ScopedStage timedPrepare(Stage::Metrics);
            stored.prepared = std::make_unique<PreparedReference>(stored.output.hdr, exposure);
        }

        auto makeRun = [&](const Layout& layout, const std::string& mode) {
            RunReport run;
            run.layout = layout.name;
            run.title = layout.title;
            run.source = layout.source.text();
            run.pipeline = pipelineName(layout.pipeline);
            run.iblMode = mode;
            const BandwidthReport bw = computeBandwidth(layout, width, height);
            run.bytesPerPixel = bytesPerPixelOf(bw);
            run.bandwidth = bw.frames;
            return run;
        };

        // The lighting approximations: the reference layout under each mode vs under ground truth.
        if (compareLighting) {
            const ReferenceRender& truth = references.at(kGroundTruth);
            for (const auto& mode : modeNames) {
                if (mode == kGroundTruth) continue;
                progress.begin("lighting " + mode + " vs " + kGroundTruth + viewLabel);
                RunReport run = makeRun(referenceLayout, mode);
                run.layout = std::string(kReferenceLayout) + " (" + mode + " vs " + kGroundTruth + ")";
                ReferenceRender& approx = references.at(mode);
                run.times = PassTimes{approx.output.timings.gbufferMs, approx.output.timings.lightingMs, ctx.info.name};
                measureRun(run, approx.output, truth, outDir, "lighting/" + mode + "/", exposure, hdrFlip, false, firstView,
                           imageOutput);
                progress.end("PSNR " + formatPsnr(run.image->psnrToneMapped) + ", FLIP " +
                             std::to_string(run.image->flipMean).substr(0, 6));
                record(std::move(run));
            }
        }

        // The seed's figure: rows = modes (enum order: ground truth first), columns = the grid's balls.
        if (compareLighting && firstView) {
            const std::vector<FigureBall> balls = findFigureBalls(inputs.scene, width, height);
            if (balls.empty()) {
                model.run.notes.push_back("IBL figure: only for the built-in scene (it crops the sphere grid's balls)");
            } else {
                ScopedStage timed(Stage::Report);
                IblFigure figure;
                figure.png = "ibl-figure.png";
                for (const FigureBall& b : balls) figure.columns.push_back(b.label);
                std::vector<Image8> renders;
                std::vector<std::string> captions;
                for (const std::string& name : iblModeNames()) {
                    if (!references.count(name)) continue;
                    IblFigureRow row;
                    row.iblMode = name;
                    for (const RunReport& r : model.runs) {
                        if (!r.image) continue;
                        if (name == kGroundTruth) {
                            if (r.image->metal && r.image->metal->referenceNoise) row.metalNoise = r.image->metal->referenceNoise;
                            if (r.image->dielectric && r.image->dielectric->referenceNoise)
                                row.dielectricNoise = r.image->dielectric->referenceNoise;
                        } else if (r.iblMode == name) {
                            if (r.image->metal) row.metalError = r.image->metal->relLuminanceMean;
                            if (r.image->dielectric) row.dielectricError = r.image->dielectric->relLuminanceMean;
                        }
                    }
                    row.caption = iblFigureCaption(row);
                    captions.push_back(row.caption);
                    renders.push_back(toneMapToSrgb8(references.at(name).output.hdr, exposure));
                    figure.rows.push_back(std::move(row));
                }
                imageWriter.enqueue("the IBL figure",
                                    [path = (outDir / figure.png).string(),
                                     picture = std::make_shared<const Image8>(composeIblFigure(
                                         renders, balls, captions,
                                         "IBL modes vs ground truth: metals, then dielectrics, roughness 0.05 to 1"))] {
                                        writePng(path, *picture);
                                    });
                model.iblFigure = std::move(figure);
            }
        }

        for (size_t m = 0; m < modes.size(); ++m) {
            const ReferenceRender& ref = references.at(modeNames[m]);
            if (bandPlan.banded() && bandedReferenceMode != m) {  // the evaluator holds another mode's
                const PassTimings t = renderReferenceInBands(renderer, referenceWiring, settingsFor(modes[m], view),
                                                             bandPlan, *evaluator, exposure, nullptr);
                gpuPassMs += t.gbufferMs + t.lightingMs;
                bandedReferenceMode = m;
            }
            for (const Layout& layout : layouts) {
                progress.begin(layout.name + " / " + modeNames[m] + viewLabel);
                if (!firstView && model.runs.at(runIndex).status == RunStatus::Failed) {
                    progress.end("skipped: failed in view 0");
                    ++runIndex;
                    continue;
                }
                RunReport run = makeRun(layout, modeNames[m]);
                try {
                    const std::string prefix = "runs/" + layout.name + "/" + modeNames[m] + "/";
                    const GBufferWiring wiring = generateWiring(layout, wiringOptions);
                    if (bandPlan.banded()) {
                        const PassTimings t =
                            measureRunInBands(run, renderer, referenceWiring, wiring, settingsFor(modes[m], view),
                                              bandPlan, *evaluator, outDir, prefix, hdrFlip, firstView, imageOutput,
                                              gpuPassMs);
                        run.times = PassTimes{t.gbufferMs, t.lightingMs, ctx.info.name};
                    } else {
                        RenderOutput out = renderer.render(wiring, settingsFor(modes[m], view));
                        gpuPassMs += out.timings.gbufferMs + out.timings.lightingMs;
                        run.times = PassTimes{out.timings.gbufferMs, out.timings.lightingMs, ctx.info.name};
                        measureRun(run, out, ref, outDir, prefix, exposure, hdrFlip, true, firstView, imageOutput);
                    }
                    progress.end("PSNR " + formatPsnr(run.image->psnrToneMapped) + ", FLIP " +
                                 std::to_string(run.image->flipMean).substr(0, 6));
                } catch (const std::exception& e) {
                    // One layout that cannot be rendered must not sink the others: report it as failed.
                    run.status = RunStatus::Failed;
                    run.error = e.what();
                    run.image.reset();
                    progress.end("FAILED: " + std::string(e.what()).substr(0, 200));
                }
                record(std::move(run));
            }
        }
    }  // views
    {
        std::lock_guard lock(modelMutex);
        for (RunReport& r : model.runs) finishViews(r);
    }

    std::vector<std::string> writeErrors;  // image files of no run (the references', the figure)
    {
        ScopedStage timed(Stage::Report);
        // What is still being written is waited for here, so the report names only files that
        // exist. A run whose images could not be written fails, as it did when they were written
        // in line; any other file that could not be written is an error of the command.
        std::lock_guard lock(modelMutex);
        std::optional<HostScope> finishScope(std::in_place, "report: waiting for the image files");
        std::vector<WriteFailure> failures = imageWriter.finish();
        finishScope.reset();
        HostScope reportScope("report: html, json, csv");
        writeErrors = failRunsOfWriteFailures(model, failures);
        writeReport(outDir, model);
        printTable(model);
        reportStageTimes(outDir, StageClock::global().read(), gpuPassMs);
        std::error_code ec;
        fs::remove(incompleteMarker, ec);
        reportComplete = true;
    }
    setInterruptAction({});
    hostProfileAdd("compare: up to the report (then teardown)", StageClock::global().read().totalMs / 1e3);
    std::printf("report: %s\n", (outDir / "report.html").string().c_str());
    // A file that could not be written is an error of the command, one line each, never lost.
    for (const std::string& e : writeErrors) std::fprintf(stderr, "gbufferlab: error: %s\n", e.c_str());
    // The report lists what failed and why; the exit status says that something did, so that
    // scripts and CI notice (2 runs failed of 7: exit 4).
    const auto failed = std::count_if(model.runs.begin(), model.runs.end(),
                                      [](const RunReport& r) { return r.status == RunStatus::Failed; });
    if (failed > 0) {
        std::fprintf(stderr, "gbufferlab: error: %d of %d runs failed (see the FAILED rows above and in %s)\n",
                     int(failed), int(model.runs.size()), escapeText((outDir / "report.html").string()).c_str());
        return kExitRunsFailed;
    }
    return writeErrors.empty() ? 0 : 1;
}

}  // namespace gbl
