// `gbufferlab search`: layouts found under a byte budget. Renders the float reference once per
// view on the GPU, explores layouts with the fast CPU evaluation (src/search), writes the Pareto
// front as layout files, and confirms it with full GPU renders through `compare`.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>

#include "cli_args.h"
#include "commands.h"
#include "compare_views.h"
#include "scene_suite.h"
#include "error.h"
#include "fast_eval.h"
#include "file_io.h"
#include "flip.h"
#include "ibl_cache.h"
#include "layout_catalog.h"
#include "layout_packer.h"
#include "layout_search.h"
#include "parallel_for.h"
#include "renderer.h"
#include "scene_inputs.h"
#include "search_front.h"
#include "search_metrics.h"
#include "search_reference.h"
#include "search_report.h"
#include "search_space.h"
#include "tone_map.h"
#include "vk_context.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {

constexpr const char* kJournal = "search-journal.tsv";

std::string duration(double seconds) {
    const int s = int(std::lround(std::max(seconds, 0.0)));
    char buf[32];
    if (s >= 3600) std::snprintf(buf, sizeof(buf), "%dh%02dm", s / 3600, s / 60 % 60);
    else if (s >= 60) std::snprintf(buf, sizeof(buf), "%dm%02ds", s / 60, s % 60);
    else std::snprintf(buf, sizeof(buf), "%ds", s);
    return buf;
}

// The CPU re-shade of the reference against its GPU render, mean over views: LDR-FLIP, and the
// mean relative error of covered pixels' luminance (relative to max(Y, 1 % of the image's mean),
// run_metrics' relative-luminance convention).
void reshadeAgreement(const search::FastEvaluator& eval, const SearchReference& ref, double& flip, double& meanRel) {
    flip = 0.0;
    meanRel = 0.0;
    for (size_t v = 0; v < ref.views.size(); ++v) {
        const Image& cpu = eval.referenceHdr(v);
        const Image& gpu = ref.gpuHdr[v];
        flip += flipStats(flipLdr(toneMapToSrgb8AsFloat(gpu), toneMapToSrgb8AsFloat(cpu))).mean / double(ref.views.size());
        auto lum = [](const Image& im, size_t i) {
            return 0.2126 * im.pixels[i * 4] + 0.7152 * im.pixels[i * 4 + 1] + 0.0722 * im.pixels[i * 4 + 2];
        };
        double mean = 0.0, sum = 0.0;
        size_t covered = 0;
        for (size_t i = 0; i < gpu.pixelCount(); ++i) mean += lum(gpu, i) / double(gpu.pixelCount());
        for (size_t i = 0; i < gpu.pixelCount(); ++i)
            if (ref.views[v].shade.covered[i]) {
                sum += std::abs(lum(cpu, i) - lum(gpu, i)) / std::max(lum(gpu, i), 0.01 * mean);
                ++covered;
            }
        meanRel += (covered ? sum / double(covered) : 0.0) / double(ref.views.size());
    }
}

}  // namespace

int runSearchCommand(const std::vector<std::string>& args) {
    const std::vector<FlagSpec> specs = {
        {"budget", "B", "bytes per pixel, render targets and depth-stencil included (required; " +
                            std::to_string(search::smallestPackedBytes(search::EngineConstraints{})) +
                            "..64: the smallest layout the search packs under the default constraints takes " +
                            std::to_string(search::smallestPackedBytes(search::EngineConstraints{})) + ")"},
        {"scene", "FILE", "glTF 2.0 scene (.gltf/.glb), builtin (the default) or a scene suite .toml; give it "
                          "several times to minimise the mean error over the scenes (as compare --scene)", true},
        {"env", "FILE", "equirectangular environment (.hdr/.exr); default: the built-in sky"},
        {"allow-outside-scene", "", "let the scene's buffer and image URIs point outside its folder"},
        {"size", "WxH", "image size of the evaluation and the confirmation (default 480x270)"},
        {"views", "N", "cameras, as compare --views (default 3)"},
        {"objective", "NAME", "flip (default), psnr or attributes: what the front minimises"},
        {"seed", "S", "seed of the search (default 1); a seed gives the same front every time"},
        {"candidates", "N", "layouts to evaluate (default 600)"},
        {"threads", "N", "candidates evaluated at once (default: every core); does not change the result"},
        {"out", "DIR", "output directory (default out/search-<time>); a directory holding a search journal "
                       "is resumed"},
        {"search-depth", "", "let the search choose the depth format too (D16 included); by default depth keeps a "
                             "layout family's format (D24S8 or D32): it serves shadows, SSAO, SSR, fog and decals, "
                             "which gbufferlab does not model"},
        {"min-bits", "LIST", "minimum bits of each stored attribute, e.g. occlusion=4,roughness=6 (defaults: normal 8, "
                             "roughness 7, base/diffuse/specular colour, metallic and specular 8, occlusion 4; 0: none)"},
        {"no-confirm", "", "skip the full GPU renders of the front and the published layouts"},
        {"device", "NAME", "cpu (lavapipe, default), gpu, an index or a name from `gbufferlab devices`"},
        {"help", "", "show this help"},
    };
    const ParsedArgs parsed = parseArgs("search", args, specs);
    if (parsed.has("help")) {
        std::printf("%s", formatHelp("gbufferlab search --budget B [--scene F] [--env F] [--size WxH] [--views N] "
                                     "[--objective flip|psnr|attributes] [--seed S] [--out DIR] [--min-bits LIST] "
                                     "[--search-depth]",
                                     "Searches G-buffer layouts within B bytes per pixel (encodings, bits, fallbacks, "
                                     "packing into real\nformats), writes the Pareto front of error against bytes as "
                                     "layout files and a report beside\nthe published layouts. The front is over bytes and every metric, under engine constraints\n(depth family, minimum bits, free stencil). Resumable: rerun with "
                                     "the same arguments and --out.",
                                     specs)
                               .c_str());
        return 0;
    }
    if (!parsed.positional.empty())
        throwUserError("gbufferlab search: unexpected argument '" + parsed.positional[0] + "' (see --help)");
    if (!parsed.has("budget")) throwUserError("gbufferlab search: --budget B is required (bytes per pixel, e.g. 16)");
    const int budget = parseIntFlag(parsed, "budget", 16, 4, 64);
    search::EngineConstraints constraints;
    constraints.searchDepth = parsed.has("search-depth");
    if (parsed.has("min-bits")) search::parseMinBits(parsed.get("min-bits"), constraints);
    const int smallest = search::smallestPackedBytes(constraints);
    if (budget < smallest)
        throwUserError("--budget " + std::to_string(budget) + ": no layout fits in " + std::to_string(budget) +
                       " bytes per pixel: the smallest the search can pack (fewest bits of every encoding within "
                       "the engine constraints, the smallest depth format they allow) takes " +
                       std::to_string(smallest) + "; give --budget " + std::to_string(smallest) +
                       " or more (or loosen --min-bits / give --search-depth)");
    const auto [width, height] = parseSize(parsed.get("size", "480x270"), "--size");
    const int viewCount = parseIntFlag(parsed, "views", 3, 1, 16);
    const search::Objective objective = search::parseObjective(parsed.get("objective", "flip"));
    const int seed = parseIntFlag(parsed, "seed", 1, 0, 2147483647);
    const int candidates = parseIntFlag(parsed, "candidates", 600, 1, 1000000);
    const int threads = parseIntFlag(parsed, "threads", hardwareThreads(), 1, 256);
    const bool confirm = !parsed.has("no-confirm");
    const fs::path outDir = parsed.has("out") ? fs::path(parsed.get("out")) : defaultOutputDirectory("search");
    const bool resuming = fs::exists(outDir / kJournal);
    const std::string reuse = "give the --out of an earlier search (a directory holding " + std::string(kJournal) +
                              ") to resume it";
    checkOutputDirectory(outDir, resuming, "--out", reuse);
    const std::vector<std::string> sceneArgs = parsed.all("scene");
    const std::vector<compare::SceneSpec> sceneSpecs = compare::resolveScenes(sceneArgs, parsed.get("env"));
    const bool severalScenes = sceneSpecs.size() > 1;
    if (resuming) {
        std::vector<std::string> inputs = {parsed.get("env")};
        for (const compare::SceneSpec& spec : sceneSpecs) inputs.insert(inputs.end(), {spec.gltfPath, spec.envPath});
        for (const std::string& a : sceneArgs) inputs.push_back(a);
        refuseInputsInsideDirectory(outDir, inputs, "--out");
    }
    // The command as the front files quote it: without what does not change the result (--out,
    // --threads, --device, --no-confirm), so two runs with one seed write the same bytes.
    std::string commandLine = "gbufferlab search";
    for (size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--out" || args[i] == "--threads" || args[i] == "--device") {
            ++i;
            continue;
        }
        if (args[i] != "--no-confirm") commandLine += " " + args[i];
    }

    // Every scene loaded before the device starts (bad input fails fast), then its reference
    // rendered and its fast evaluator built; a search over several scenes minimises the mean.
    struct SceneEval {
        compare::SceneSpec spec;
        SceneInputs inputs;
        IblMaps ibl;
        std::unique_ptr<search::FastEvaluator> evaluator;
    };
    std::vector<std::unique_ptr<SceneEval>> scenes;
    for (const compare::SceneSpec& spec : sceneSpecs) {
        auto scene = std::make_unique<SceneEval>();
        scene->spec = spec;
        scene->inputs = loadSceneInputs(spec.gltfPath, spec.envPath, float(width) / float(height),
                                        GltfLoadOptions{parsed.has("allow-outside-scene")});
        scenes.push_back(std::move(scene));
    }
    VulkanContext ctx(DeviceOptions{parsed.get("device"), false});
    validateResolution(ctx, width, height, "--size", 0, "give a smaller --size");  // search has no bands
    prepareOutputDirectory(outDir, resuming, "--out", reuse);

    // The depth formats candidates and published layouts use: the reference is rendered under each
    // (visibility depends on depth precision; fast_eval.h DepthVariant).
    std::vector<DepthKey> depthKeys;
    auto addKey = [&](const DepthKey& k) {
        if (std::find(depthKeys.begin(), depthKeys.end(), k) == depthKeys.end()) depthKeys.push_back(k);
    };
    for (const auto& d : search::depthFormats()) addKey({d.format, d.reversedZ});
    std::vector<Layout> publishedLayouts;
    for (const std::string& name : listLayoutNames()) {
        if (name == "reference") continue;
        Layout l = loadLayout(name);
        if (l.pipeline != Pipeline::DeferredShading) continue;
        addKey({l.depth.format, l.depth.reversedZ});
        publishedLayouts.push_back(std::move(l));
    }
    double reshadeFlip = 0.0, reshadeMeanRel = 0.0;
    for (auto& scene : scenes) {
        const SceneInputs& inputs = scene->inputs;
        scene->ibl = loadOrComputeIbl(ctx, inputs.environment, IblSettings{});
        Renderer renderer(ctx, inputs.scene, inputs.environment, scene->ibl);
        std::vector<Camera> cameras;
        if (!scene->spec.cameras.empty())
            for (const auto& v : compare::placedViews(inputs.scene, scene->spec.cameras)) cameras.push_back(v.camera);
        else
            for (const auto& v : compare::compareViews(inputs.scene, viewCount, float(width) / float(height))) cameras.push_back(v.camera);
        std::printf("search: rendering the reference%s (%d view%s, %ux%u) on %s\n",
                    severalScenes ? (" of " + scene->spec.name).c_str() : "", int(cameras.size()),
                    cameras.size() > 1 ? "s" : "", width, height, ctx.info.name.c_str());
        SearchReference reference = renderSearchReference(renderer, cameras, width, height, depthKeys);
        std::vector<search::EvalView> views = reference.views;
        scene->evaluator = std::make_unique<search::FastEvaluator>(
            std::move(views), search::shadeLights(inputs.scene.lights), scene->ibl, objective);
        double flip = 0.0, meanRel = 0.0;
        reshadeAgreement(*scene->evaluator, reference, flip, meanRel);
        std::printf("search: CPU re-shade of the reference%s vs its GPU render: FLIP %.5f, mean relative luminance "
                    "error %.5f\n",
                    severalScenes ? (" of " + scene->spec.name).c_str() : "", flip, meanRel);
        reshadeFlip += flip / double(scenes.size());
        reshadeMeanRel += meanRel / double(scenes.size());
    }
    // A candidate's evaluation: the mean over the scenes of each scene's (mean over its views).
    auto evaluatePerScene = [&](const Layout& layout, int evalThreads) {
        std::vector<search::Evaluation> each;
        for (const auto& scene : scenes)
            each.push_back(evalThreads > 1 ? scene->evaluator->evaluate(layout, evalThreads)
                                           : scene->evaluator->evaluate(layout));
        return each;
    };
    auto meanOf = [](const std::vector<search::Evaluation>& each) { return search::meanEvaluation(each); };

    // Everything the result depends on is in the journal's key; --threads and --no-confirm are not.
    search::SearchOptions options;
    options.budgetBytes = budget;
    options.seed = uint64_t(seed);
    options.candidates = candidates;
    options.threads = threads;
    options.journalPath = (outDir / kJournal).string();
    std::string sceneKey;  // one scene: as before this key knew several
    if (!severalScenes) {
        sceneKey = " scene=" + scenes[0]->inputs.scene.source + " env=" + scenes[0]->inputs.environment.source;
    } else {
        sceneKey = " scenes=";
        for (size_t i = 0; i < scenes.size(); ++i)
            sceneKey += (i ? ";" : "") + scenes[i]->spec.name + ":" + scenes[i]->inputs.scene.source + ":" +
                        scenes[i]->inputs.environment.source;
    }
    options.journalKey = "budget=" + std::to_string(budget) + sceneKey + " size=" + std::to_string(width) + "x" +
                         std::to_string(height) + " views=" + std::to_string(viewCount) +
                         " objective=" + search::objectiveName(objective) + " seed=" + std::to_string(seed) + " " +
                         search::constraintsKey(constraints);
    options.constraints = constraints;
    options.progress = [&](const search::SearchProgress& p) {
        std::fprintf(stderr, "search: %d/%d candidates (%d from the journal), %.0f/min, ETA %s", p.evaluated, p.total,
                     p.resumed, p.perMinute, duration(p.etaSeconds).c_str());
        if (p.bestAtBudget)
            std::fprintf(stderr, ", best %d B/px score %.5f", p.bestAtBudget->bytes, p.bestAtBudget->eval.error);
        std::fprintf(stderr, "\n");
    };
    if (resuming) std::printf("search: resuming from %s\n", options.journalPath.c_str());
    const search::SearchResult result = runSearch(
        [&](const std::string& text) {
            const Layout layout = parseLayout(text, "candidate.toml");
            return severalScenes ? meanOf(evaluatePerScene(layout, 1)) : scenes[0]->evaluator->evaluate(layout);
        },
        options);
    if (result.rejectedByValidation)
        throwUserError("search: " + std::to_string(result.rejectedByValidation) +
                       " packed candidates failed validation (a bug in src/search/layout_packer.cpp): " +
                       result.validationMessages.front());
    if (result.rejectedByConstraints)
        throwUserError("search: " + std::to_string(result.rejectedByConstraints) +
                       " packed candidates broke the engine constraints (a bug in src/search/search_constraints.cpp): " +
                       result.constraintMessages.front());
    if (result.front.empty())
        std::printf("search: no candidate fits in %d B/px (%d proposals over budget, %d unpackable, %d duplicates): "
                    "the front is empty; give a larger --budget\n",
                    budget, result.overBudget, result.unpackable, result.duplicates);
    const double evaluatedHere = double(result.evaluated.size()) - double(result.resumed);
    const double perMinute = result.seconds > 0 ? 60.0 * evaluatedHere / result.seconds : 0.0;

    SearchSummary summary;
    summary.commandLine = commandLine;
    summary.objective = search::objectiveName(objective);
    summary.seed = uint64_t(seed);
    summary.budget = budget;
    summary.size = std::to_string(width) + "x" + std::to_string(height);
    summary.views = viewCount;
    summary.candidates = int(result.evaluated.size());
    summary.resumed = result.resumed;
    summary.perMinute = perMinute;
    summary.cpuSecondsPerCandidate = evaluatedHere > 0 ? result.cpuSeconds / evaluatedHere : 0.0;
    summary.threads = threads;
    summary.reshadeFlip = reshadeFlip;
    summary.reshadeMeanRelative = reshadeMeanRel;
    summary.counts = std::to_string(result.overBudget) + " proposals over budget, " +
                     std::to_string(result.duplicates) + " duplicates, " + std::to_string(result.unpackable) +
                     " unpackable, " + std::to_string(result.rejectedByValidation) + " rejected by validation";
    summary.constraints = search::describeConstraints(constraints);
    for (int i : result.front) summary.front.push_back(result.evaluated[size_t(i)]);

    // The published deferred-shading layouts, beside the found ones (deferred lighting is not
    // modelled); first, as the front's files name the one each is set beside.
    std::vector<SearchRow> publishedRows;
    for (const Layout& l : publishedLayouts) {
        SearchRow row;
        row.name = l.name;
        row.bytes = bytesPerPixel(l);
        if (severalScenes) {
            row.fastPerScene = evaluatePerScene(l, threads);
            row.fast = meanOf(row.fastPerScene);
        } else {
            row.fast = scenes[0]->evaluator->evaluate(l, threads);
        }
        row.how = "published";
        publishedRows.push_back(row);
    }
    summary.rows = writeFront(result, outDir / "front", commandLine, summary.objective, uint64_t(seed),
                              summary.constraints, publishedRows);
    if (severalScenes) {
        for (const auto& scene : scenes) summary.sceneNames.push_back(scene->spec.name);
        for (SearchRow& row : summary.rows) row.fastPerScene = evaluatePerScene(loadLayoutFile(row.file), threads);
    }
    summary.rows.insert(summary.rows.end(), publishedRows.begin(), publishedRows.end());

    if (confirm) {
        std::vector<std::string> compareArgs = {"--size", summary.size, "--views", std::to_string(viewCount),
                                                "--out", (outDir / "compare").string(), "--force"};
        // The search's fast evaluation tone-maps at exposure 1: the confirmation too.
        compareArgs.insert(compareArgs.end(), {"--exposure", "1"});
        for (const std::string& scene : sceneArgs) compareArgs.insert(compareArgs.end(), {"--scene", scene});
        if (parsed.has("env")) compareArgs.insert(compareArgs.end(), {"--env", parsed.get("env")});
        if (parsed.has("allow-outside-scene")) compareArgs.push_back("--allow-outside-scene");
        if (parsed.has("device")) compareArgs.insert(compareArgs.end(), {"--device", parsed.get("device")});
        std::string list;
        for (const SearchRow& r : summary.rows) list += (list.empty() ? "" : ",") + (r.found ? r.file : r.name);
        compareArgs.insert(compareArgs.end(), {"--layouts", list});
        std::printf("search: confirming with full GPU renders: gbufferlab compare");
        for (const auto& a : compareArgs) std::printf(" %s", a.c_str());
        std::printf("\n");
        std::fflush(stdout);
        const int rc = runCompareCommand(compareArgs);
        if (rc != 0 && rc != 4) throwUserError("search: the confirming compare failed with status " + std::to_string(rc));
        readConfirmation(outDir / "compare" / "report.json", summary.rows);
        readFullMetrics(outDir / "compare" / "report.json", summary.rows);
    }
    const std::string note = writeSearchReport(summary, outDir);
    size_t written = 0;
    for (const SearchRow& r : summary.rows) written += r.found ? 1 : 0;
    std::printf("search: %zu layouts on the front (bytes and every metric); %zu written to %s\n%s", result.front.size(),
                written, (outDir / "front").string().c_str(), note.c_str());
    std::printf("search: report %s\n", (outDir / "search-report.md").string().c_str());
    return 0;
}

}  // namespace gbl
