// compare's flags: parsed and checked in the order the command used to, so that of several bad
// values the same one is named first.
#include "compare_flags.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "cli_args.h"
#include "compare_bands.h"
#include "error.h"
#include "file_io.h"
#include "ibl_cache.h"
#include "scene_suite.h"

namespace gbl::compare {

namespace {

std::string sizeText(uint32_t width, uint32_t height) { return std::to_string(width) + "x" + std::to_string(height); }

std::vector<FlagSpec> compareFlags() {
    return {
        {"scene", "FILE", "glTF 2.0 scene (.gltf/.glb), builtin (the built-in scene: the sphere grid and its "
                          "surroundings) or a scene-suite .toml; give it several times to compare every layout on "
                          "every scene. Default: the bundled suite, scenes/default-suite.toml (the built-in scene, "
                          "FlightHelmet and WaterBottle), at " + sizeText(kDefaultSuiteWidth, kDefaultSuiteHeight) +
                          " and " + std::to_string(kDefaultSuiteViews) + " views unless --size / --views "
                          "(docs/compare.md)", true},
        {"env", "FILE", "equirectangular environment (.hdr/.exr) of the scenes given by --scene; default: the "
                        "built-in sky"},
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
        {"size", "WxH", "image size (default 1920x1080; without --scene " +
                            sizeText(kDefaultSuiteWidth, kDefaultSuiteHeight) + ")"},
        {"views", "N", "cameras measured (default 3: the scene camera, an orbit about the scene's centre, a grazing "
                       "view of the ground; more add orbit views); every metric is the mean over them with its "
                       "spread; per-pixel images are the first view's"},
        {"out", "DIR", "output directory, new or empty (default: out/compare-<time>)"},
        {"force", "", "write into a non-empty --out directory, replacing files of the same name"},
        {"device", "NAME", "cpu (lavapipe, default), gpu, an index or a name from `gbufferlab devices`"},
        {"exposure", "X", "exposure for tone-mapped images and their metrics; default: automatic, each view's from its "
                           "reference as UE4's histogram auto-exposure meters it (80-98.3 percentile average luminance "
                           "mapped to 1; docs/compare.md)"},
        {"native-formats", "", "render targets in their real UNORM/SRGB/float formats where the layout allows"},
        {"hdr-flip", "", "also compute HDR-FLIP over the linear images (costs one FLIP per exposure: 14 on the "
                         "built-in sky)"},
        {"no-hdr-flip", "", "skip HDR-FLIP (the default; kept for older scripts)"},
        {"float32-exr", "", "write the EXR files (renders, errors.exr) as 32-bit float instead of half (16-bit "
                            "float: half the bytes; values within 2^-11 relative, clamped to +-65504)"},
        {"error-exr", "", "also write each run's per-pixel errors as float channels (runs/<layout>/<mode>/errors.exr; "
                          "16 MB a run at 1080p); needs the CPU evaluation, which --eval auto then picks"},
        {"eval", "WHERE", "where the metrics are computed: auto (default: gpu on a GPU, cpu on a CPU device such as "
                          "lavapipe), gpu (compute passes beside the render, only numbers and 8-bit images come "
                          "back, no errors.exr) or cpu (the measure library, the oracle)"},
        {"band-rows", "N|auto", "render and measure the frame in bands of N rows (a multiple of 8), each with FLIP's "
                                "halo, on the device evaluator: bounded memory at 4K, at the price of rendering the "
                                "reference again for every run; 0: whole frames; auto (default): bands of " +
                                    std::to_string(kAutoBandRows) + " rows on a CPU device above " +
                                    std::to_string(kAutoBandPixels) + " pixels, unless --eval cpu or ground-truth"},
        {"temporal", "N", "render N frames per view with Halton(2,3) sub-pixel jitter, the same for the reference and "
                          "every layout, and measure the resolved images, as temporal anti-aliasing shows them "
                          "(default 1: one frame, no jitter; at most " + std::to_string(kMaxTemporalFrames) +
                              "; docs/compare.md)"},
        {"resolve", "HOW", "--temporal's resolve: mean (default: the uniform mean of the frames in linear HDR, the "
                           "converged history of a still camera) or exp (exponential history, current-frame weight "
                           "0.1)"},
        {"lighting", "HOW", "how the lighting pass reads the G-buffer in the traffic figures: tiled (default) or "
                            "clustered, once per pixel; volumes:L, once per covering light volume, L the mean per "
                            "pixel; volumes, L counted from the scene's lights (docs/bandwidth.md)"},
        {"no-compression", "", "skip the framebuffer-compression model (the report's effective bytes per GPU "
                               "class; docs/bandwidth.md)"},
        {"validation", "", "enable Vulkan validation layers"},
        {"help", "", "show this help"},
    };
}

void printCompareHelp(const std::vector<FlagSpec>& specs) {
    std::printf("%s", formatHelp("gbufferlab compare [--scene F] [--env F] [--layouts A,B,...|all] [--ibl MODES] "
                                 "[--size WxH] [--out DIR]",
                                 "Renders the float reference and each layout at the same camera, and reports "
                                 "what each loses\n(attribute and image error, FLIP, error images) and costs "
                                 "(bytes per pixel, bandwidth).\nWithout --scene: every layout on the bundled "
                                 "scenes (the built-in scene, FlightHelmet, WaterBottle),\nwith the verdict across "
                                 "them and how far they agree; --scene builtin: the built-in scene alone.\nWith --ibl listing several modes and "
                                 "ground-truth among them, the reference under each mode is also\ncompared with "
                                 "the reference under ground-truth: the error of the lighting approximation.",
                                 specs)
                           .c_str());
}

// The scenes, the layouts, the size, the exposure and the views. Without --scene: the bundled
// suite, at its own size and views where --size / --views do not say (compare_options.h).
void readScenesAndViews(const ParsedArgs& parsed, CompareOptions& o) {
    const bool defaultSuite = !parsed.has("scene");
    if (defaultSuite && parsed.has("env"))
        throwUserError("gbufferlab compare: --env without --scene: the default compares the bundled scenes, each "
                       "under its own environment (scenes/default-suite.toml); give --scene builtin (or a glTF) "
                       "with --env");
    o.scenePath = parsed.get("scene");
    o.envPath = parsed.get("env");
    o.sceneArgs = defaultSuite ? std::vector<std::string>{defaultSuitePath().string()} : parsed.all("scene");
    if (o.sceneArgs.size() == 1 && o.sceneArgs[0] == "builtin") o.scenePath.clear();
    o.allowOutsideScene = parsed.has("allow-outside-scene");
    if (parsed.has("layouts")) o.layoutsSpec = parsed.get("layouts");
    const auto [width, height] =
        parseSize(parsed.get("size", defaultSuite ? sizeText(kDefaultSuiteWidth, kDefaultSuiteHeight) : "1920x1080"),
                  "--size");
    o.width = width;
    o.height = height;
    o.exposure = parsePositiveFloatFlag(parsed, "exposure", 1.0f);
    o.autoExposure = !parsed.has("exposure");
    o.viewCount = parseIntFlag(parsed, "views", defaultSuite ? kDefaultSuiteViews : 3, 1, 16);
}

// The IBL modes, their samples, the ground truth's convergence, the BRDF LUT.
void readLighting(const ParsedArgs& parsed, CompareOptions& o) {
    o.modeNames = splitFlagList(parsed.get("ibl", "split-sum"), "--ibl");
    o.modes.clear();
    for (size_t i = 0; i < o.modeNames.size(); ++i) {
        o.modes.push_back(parseIblMode(o.modeNames[i]));
        // Each mode's runs go to runs/<layout>/<mode>/: a mode given twice would write its runs
        // twice over the same files and give the table duplicate rows.
        for (size_t k = 0; k < i; ++k)
            if (o.modes[k] == o.modes[i])
                throwUserError("--ibl " + quoteName(parsed.get("ibl")) + ": " + quoteName(o.modeNames[i]) +
                               " is given twice; give each mode once");
    }
    o.splitSumShaderSamples = parseIntFlag(parsed, "samples", 1024, 1, 65536);
    o.gtBatchSamples = parseIntFlag(parsed, "gt-batch-samples", 64, 1, 65536);
    o.gtMaxBatches = parseIntFlag(parsed, "gt-max-batches", 256, 8, 65536);
    o.gtNoise = parsePositiveFloatFlag(parsed, "gt-noise", 0.002f);
    if (parsed.has("brdf-lut")) applyBrdfLutVariant(parsed.get("brdf-lut"), o.iblSettings);
}

// Where the report goes and how its images are written.
void readOutputs(const ParsedArgs& parsed, CompareOptions& o) {
    o.outDir = parsed.has("out") ? std::filesystem::path(parsed.get("out")) : defaultOutputDirectory("compare");
    o.force = parsed.has("force");
    if (parsed.has("hdr-flip") && parsed.has("no-hdr-flip"))
        throwUserError("gbufferlab compare: --hdr-flip and --no-hdr-flip contradict each other; give one");
    o.hdrFlip = parsed.has("hdr-flip");
    o.exrType = parsed.has("float32-exr") ? ExrPixelType::Float32 : ExrPixelType::Half;
}

// Where the metrics are computed: --eval, --error-exr, --band-rows.
void readEvaluation(const ParsedArgs& parsed, CompareOptions& o) {
    o.evalWhere = parsed.get("eval", "auto");
    if (o.evalWhere != "gpu" && o.evalWhere != "cpu" && o.evalWhere != "auto")
        throwUserError("gbufferlab compare: --eval " + o.evalWhere + ": give auto, gpu or cpu");
    // errors.exr holds the CPU oracle's float maps; the device evaluator keeps its maps on the device.
    o.errorExr = parsed.has("error-exr");
    if (o.errorExr && o.evalWhere == "gpu")
        throwUserError("gbufferlab compare: --error-exr needs the CPU evaluation (the device evaluator keeps its "
                       "float maps on the device); give --eval cpu or auto, or drop --error-exr");
    o.groundTruthAsked = std::find(o.modes.begin(), o.modes.end(), IblMode::GroundTruth) != o.modes.end();
    o.bandRowsGiven = parseBandRowsFlag(parsed.get("band-rows", "auto"), o.evalWhere == "cpu", o.groundTruthAsked);
    if (o.errorExr && o.bandRowsGiven.value_or(0) > 0)
        throwUserError("gbufferlab compare: --error-exr with --band-rows " + parsed.get("band-rows") +
                       ": bands are measured on the device evaluator, which keeps its float maps on the device; "
                       "give --band-rows 0, or drop --error-exr");
    if (o.errorExr) o.evalWhere = "cpu";
}

// --temporal N and its --resolve, and what they need of the evaluation.
void readTemporal(const ParsedArgs& parsed, CompareOptions& o) {
    o.temporalFrames = parseIntFlag(parsed, "temporal", 1, 1, kMaxTemporalFrames);
    if (parsed.has("resolve")) {
        const std::string how = parsed.get("resolve");
        if (how == "mean") o.resolve = ResolveMethod::Mean;
        else if (how == "exp") o.resolve = ResolveMethod::Exponential;
        else throwUserError("--resolve " + quoteName(how) + ": give mean or exp");
        if (o.temporalFrames == 1)
            throwUserError("--resolve " + how + " without --temporal N (N > 1): one frame has nothing to resolve; give "
                           "--temporal 8, or drop --resolve");
    }
    if (o.temporalFrames > 1) {
        // The resolve accumulates host images: the CPU evaluation, on whole frames, of a reference
        // that is a single frame's (a ground truth converges on its own).
        const std::string n = std::to_string(o.temporalFrames);
        if (o.evalWhere == "gpu")
            throwUserError("gbufferlab compare: --temporal " + n + " needs the CPU evaluation (the frames are resolved on "
                           "the host); give --eval cpu or auto");
        if (o.bandRowsGiven.value_or(0) > 0)
            throwUserError("gbufferlab compare: --temporal " + n + " with --band-rows " + parsed.get("band-rows") +
                           ": the frames are resolved whole; give --band-rows 0 or auto");
        if (o.groundTruthAsked)
            throwUserError("gbufferlab compare: --temporal " + n + " with --ibl ground-truth: the ground truth converges "
                           "over its own batches, not over jittered frames; drop one of them");
        o.evalWhere = "cpu";
        o.bandRowsGiven = 0u;
    }
}

}  // namespace

std::optional<CompareOptions> parseCompareOptions(const std::vector<std::string>& args) {
    const std::vector<FlagSpec> specs = compareFlags();
    const ParsedArgs parsed = parseArgs("compare", args, specs);
    if (parsed.has("help")) {
        printCompareHelp(specs);
        return std::nullopt;
    }
    if (!parsed.positional.empty())
        throwUserError("gbufferlab compare: unexpected argument '" + parsed.positional[0] + "' (see --help)");

    CompareOptions o;
    readScenesAndViews(parsed, o);
    readLighting(parsed, o);
    readOutputs(parsed, o);
    readEvaluation(parsed, o);
    readTemporal(parsed, o);
    o.device = parsed.get("device");
    o.validation = parsed.has("validation");
    o.nativeFormats = parsed.has("native-formats");
    o.lighting = parseLightingModel(parsed.get("lighting", "tiled"), "--lighting");
    o.compressionModel = !parsed.has("no-compression");
    o.commandLine = "gbufferlab compare";
    for (const auto& a : args) o.commandLine += " " + a;
    return o;
}

}  // namespace gbl::compare
