// The search (search_api.h): the references rendered once on the device, the candidates explored
// on the CPU (src/search), the front written as files, confirmed by a comparison, reported.
#include "search_api.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "compare_views.h"
#include "effective_bandwidth.h"
#include "error.h"
#include "file_io.h"
#include "flip.h"
#include "ibl_cache.h"
#include "layout_catalog.h"
#include "layout_packer.h"
#include "layout_search.h"
#include "parallel_for.h"
#include "renderer.h"
#include "scene_inputs.h"
#include "scene_suite.h"
#include "search_front.h"
#include "search_metrics.h"
#include "search_reference.h"
#include "search_space.h"
#include "tone_map.h"
#include "vk_context.h"

namespace gbl::app {

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

void note(const RunControl& control, const std::string& line) {
    if (control.progress) control.progress->note(line);
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

// One scene of the search: its inputs, IBL maps and the fast evaluator of its reference.
struct SceneEval {
    compare::SceneSpec spec;
    SceneInputs inputs;
    IblMaps ibl;
    std::unique_ptr<search::FastEvaluator> evaluator;
};

// Everything one search holds between its steps.
struct SearchRun {
    const SearchOptions& options;
    const RunControl& control;
    bool resuming = false;
    int threads = 0;
    std::vector<std::unique_ptr<SceneEval>> scenes;
    std::optional<VulkanContext> ctx;
    std::vector<DepthKey> depthKeys;  // the depth formats candidates and published layouts use
    std::vector<Layout> publishedLayouts;
    double reshadeFlip = 0.0, reshadeMeanRel = 0.0;

    bool severalScenes() const { return scenes.size() > 1; }
    // A candidate's evaluation per scene, each the mean over its views.
    std::vector<search::Evaluation> evaluatePerScene(const Layout& layout, int evalThreads) const {
        std::vector<search::Evaluation> each;
        for (const auto& scene : scenes)
            each.push_back(evalThreads > 1 ? scene->evaluator->evaluate(layout, evalThreads)
                                           : scene->evaluator->evaluate(layout));
        return each;
    }
    // search --budget-model: the layout's effective bytes per pixel under the class, the mean over
    // the scenes of view 0's (the CPU codec's words of the reference Surfaces, compressed).
    double effectiveBytes(const Layout& layout, int evalThreads) const {
        double sum = 0.0;
        for (const auto& scene : scenes)
            sum += effectiveBytesPerPixel(layout, scene->evaluator->compressWords(layout, 0, std::max(1, evalThreads)),
                                          options.budgetModel);
        return scenes.empty() ? 0.0 : sum / double(scenes.size());
    }
    // ... and over the scenes: the mean of each scene's.
    search::Evaluation evaluate(const Layout& layout, int evalThreads) const {
        if (severalScenes()) return search::meanEvaluation(evaluatePerScene(layout, evalThreads));
        return evalThreads > 1 ? scenes[0]->evaluator->evaluate(layout, evalThreads) : scenes[0]->evaluator->evaluate(layout);
    }
};

// Every input checked and every scene loaded before the device starts (bad input fails fast);
// then the device, and the output folder.
void prepareInputs(SearchRun& run) {
    const SearchOptions& o = run.options;
    requirePackableBudget(o.budget, o.constraints);
    const fs::path& outDir = o.outDir;
    run.resuming = fs::exists(outDir / kJournal);
    const std::string reuse = "give the --out of an earlier search (a directory holding " + std::string(kJournal) +
                              ") to resume it";
    checkOutputDirectory(outDir, run.resuming, "--out", reuse);
    const std::vector<compare::SceneSpec> sceneSpecs = compare::resolveScenes(o.sceneArgs, o.envPath);
    if (run.resuming) {
        std::vector<std::string> inputs = {o.envPath};
        for (const compare::SceneSpec& spec : sceneSpecs) inputs.insert(inputs.end(), {spec.gltfPath, spec.envPath});
        for (const std::string& a : o.sceneArgs) inputs.push_back(a);
        refuseInputsInsideDirectory(outDir, inputs, "--out");
    }
    for (const compare::SceneSpec& spec : sceneSpecs) {
        auto scene = std::make_unique<SceneEval>();
        scene->spec = spec;
        scene->inputs = loadSceneInputs(spec.gltfPath, spec.envPath, float(o.width) / float(o.height),
                                        GltfLoadOptions{o.allowOutsideScene});
        run.scenes.push_back(std::move(scene));
    }
    run.ctx.emplace(DeviceOptions{o.device, false});
    validateResolution(*run.ctx, o.width, o.height, "--size", 0, "give a smaller --size");  // search has no bands
    prepareOutputDirectory(outDir, run.resuming, "--out", reuse);
}

// The depth formats candidates and published layouts use: the reference is rendered under each
// (visibility depends on depth precision; fast_eval.h DepthVariant). The published layouts are
// the deferred-shading ones of layouts/ (deferred lighting is not modelled).
void choosePublishedLayouts(SearchRun& run) {
    auto addKey = [&](const DepthKey& k) {
        if (std::find(run.depthKeys.begin(), run.depthKeys.end(), k) == run.depthKeys.end()) run.depthKeys.push_back(k);
    };
    for (const auto& d : search::depthFormats()) addKey({d.format, d.reversedZ});
    for (const std::string& name : listLayoutNames()) {
        if (name == "reference") continue;
        Layout l = loadLayout(name);
        if (l.pipeline != Pipeline::DeferredShading) continue;
        addKey({l.depth.format, l.depth.reversedZ});
        run.publishedLayouts.push_back(std::move(l));
    }
}

// Each scene's reference rendered on the device, its fast evaluator built, and the CPU re-shade
// checked against the GPU's render.
void renderReferences(SearchRun& run) {
    const SearchOptions& o = run.options;
    const VulkanContext& ctx = *run.ctx;
    for (auto& scene : run.scenes) {
        const SceneInputs& inputs = scene->inputs;
        scene->ibl = loadOrComputeIbl(ctx, inputs.environment, IblSettings{});
        Renderer renderer(ctx, inputs.scene, inputs.environment, scene->ibl);
        std::vector<Camera> cameras;
        if (!scene->spec.cameras.empty())
            for (const auto& v : compare::placedViews(inputs.scene, scene->spec.cameras)) cameras.push_back(v.camera);
        else
            for (const auto& v : compare::compareViews(inputs.scene, o.viewCount, float(o.width) / float(o.height)))
                cameras.push_back(v.camera);
        const std::string of = run.severalScenes() ? " of " + scene->spec.name : "";
        char line[512];
        std::snprintf(line, sizeof(line), "search: rendering the reference%s (%d view%s, %ux%u) on %s", of.c_str(),
                      int(cameras.size()), cameras.size() > 1 ? "s" : "", o.width, o.height, ctx.info.name.c_str());
        note(run.control, line);
        SearchReference reference = renderSearchReference(renderer, cameras, o.width, o.height, run.depthKeys);
        std::vector<search::EvalView> views = reference.views;
        scene->evaluator = std::make_unique<search::FastEvaluator>(
            std::move(views), search::shadeLights(inputs.scene.lights), scene->ibl, o.objective);
        double flip = 0.0, meanRel = 0.0;
        reshadeAgreement(*scene->evaluator, reference, flip, meanRel);
        std::snprintf(line, sizeof(line),
                      "search: CPU re-shade of the reference%s vs its GPU render: FLIP %.5f, mean relative luminance "
                      "error %.5f",
                      of.c_str(), flip, meanRel);
        note(run.control, line);
        run.reshadeFlip += flip / double(run.scenes.size());
        run.reshadeMeanRel += meanRel / double(run.scenes.size());
    }
}

// Everything the result depends on is in the journal's key; --threads and --no-confirm are not.
std::string journalKey(const SearchRun& run) {
    const SearchOptions& o = run.options;
    std::string sceneKey;  // one scene: as before this key knew several
    if (!run.severalScenes()) {
        sceneKey = " scene=" + run.scenes[0]->inputs.scene.source + " env=" + run.scenes[0]->inputs.environment.source;
    } else {
        sceneKey = " scenes=";
        for (size_t i = 0; i < run.scenes.size(); ++i)
            sceneKey += (i ? ";" : "") + run.scenes[i]->spec.name + ":" + run.scenes[i]->inputs.scene.source + ":" +
                        run.scenes[i]->inputs.environment.source;
    }
    return "budget=" + std::to_string(o.budget) + (o.budgetModel == "nominal" ? "" : " budget_model=" + o.budgetModel) +
           sceneKey + " size=" + std::to_string(o.width) + "x" +
           std::to_string(o.height) + " views=" + std::to_string(o.viewCount) +
           " objective=" + search::objectiveName(o.objective) + " seed=" + std::to_string(o.seed) + " " +
           search::constraintsKey(o.constraints);
}

// The search itself, on the CPU; stopped between rounds when the caller asks.
search::SearchResult exploreCandidates(const SearchRun& run) {
    const SearchOptions& o = run.options;
    search::SearchOptions options;
    // --budget-model: nominal bytes up to twice the budget are explored; the effective bytes decide.
    options.budgetBytes = o.budgetModel == "nominal" ? o.budget : std::min(64, 2 * o.budget);
    options.seed = o.seed;
    options.candidates = o.candidates;
    options.threads = run.threads;
    options.journalPath = (o.outDir / kJournal).string();
    options.journalKey = journalKey(run);
    options.constraints = o.constraints;
    // The layers join the search space when a scene carries one (issue 40: a scene without them
    // searches what it searched before).
    for (const auto& scene : run.scenes)
        for (const Material& m : scene->inputs.scene.materials) options.layers = options.layers || m.layers() != 0;
    options.progress = [&](const search::SearchProgress& p) {
        if (!run.control.progress) return;
        char line[256];
        int n = std::snprintf(line, sizeof(line), "search: %d/%d candidates (%d from the journal), %.0f/min, ETA %s",
                              p.evaluated, p.total, p.resumed, p.perMinute, duration(p.etaSeconds).c_str());
        if (p.bestAtBudget && n > 0 && size_t(n) < sizeof(line))
            std::snprintf(line + n, sizeof(line) - size_t(n), ", best %d B/px score %.5f", p.bestAtBudget->bytes,
                          p.bestAtBudget->eval.error);
        run.control.progress->status(line);
    };
    options.stop = [&] { return run.control.cancelSignal() != 0; };
    if (run.resuming) note(run.control, "search: resuming from " + options.journalPath);
    search::SearchResult result = search::runSearch(
        [&](const std::string& text) { return run.evaluate(parseLayout(text, "candidate.toml"), 1); }, options);
    if (result.rejectedByValidation)
        throwUserError("search: " + std::to_string(result.rejectedByValidation) +
                       " packed candidates failed validation (a bug in src/search/layout_packer.cpp): " +
                       result.validationMessages.front());
    if (result.rejectedByConstraints)
        throwUserError("search: " + std::to_string(result.rejectedByConstraints) +
                       " packed candidates broke the engine constraints (a bug in src/search/search_constraints.cpp): " +
                       result.constraintMessages.front());
    return result;
}

// search --budget-model: every candidate's bytes become its effective bytes under the class
// (rounded up to whole bytes, as the front files name them); those over the budget leave the
// running, and the front is taken again over what is left. The journal keeps the nominal bytes.
search::SearchResult applyBudgetModel(const SearchRun& run, search::SearchResult found) {
    const SearchOptions& o = run.options;
    if (o.budgetModel == "nominal") return found;
    std::vector<double> effective(found.evaluated.size(), 0.0);
    parallelFor(int64_t(found.evaluated.size()), run.threads, [&](int64_t begin, int64_t end) {
        for (int64_t i = begin; i < end; ++i) {
            const search::Candidate& c = found.evaluated[size_t(i)];
            effective[size_t(i)] =
                run.effectiveBytes(parseLayout(search::layoutText("candidate", "", c.body), "candidate.toml"), 1);
        }
    });
    std::vector<search::Candidate> kept;
    std::vector<int> keptIndex;
    int over = 0;
    for (size_t i = 0; i < found.evaluated.size(); ++i) {
        search::Candidate c = found.evaluated[i];
        c.bytes = int(std::ceil(effective[i] - 1e-9));
        found.evaluated[i].bytes = c.bytes;
        if (c.bytes > o.budget) {
            ++over;
            continue;
        }
        kept.push_back(c);
        keptIndex.push_back(int(i));
    }
    found.front.clear();
    for (int k : search::paretoFront(kept)) found.front.push_back(keptIndex[size_t(k)]);
    found.overBudget += over;
    note(run.control, "search: --budget-model " + o.budgetModel + ": " + std::to_string(kept.size()) + " of " +
                          std::to_string(found.evaluated.size()) + " candidates fit " + std::to_string(o.budget) +
                          " B/px in effective bytes; the front is over effective bytes");
    return found;
}

// The report's facts of the run, and its whole front.
SearchSummary summarise(const SearchRun& run, const search::SearchResult& result) {
    const SearchOptions& o = run.options;
    const double evaluatedHere = double(result.evaluated.size()) - double(result.resumed);
    SearchSummary summary;
    summary.commandLine = o.commandLine;
    summary.objective = search::objectiveName(o.objective);
    summary.seed = o.seed;
    summary.budget = o.budget;
    summary.size = std::to_string(o.width) + "x" + std::to_string(o.height);
    summary.views = o.viewCount;
    summary.candidates = int(result.evaluated.size());
    summary.resumed = result.resumed;
    summary.perMinute = result.seconds > 0 ? 60.0 * evaluatedHere / result.seconds : 0.0;
    summary.cpuSecondsPerCandidate = evaluatedHere > 0 ? result.cpuSeconds / evaluatedHere : 0.0;
    summary.threads = run.threads;
    summary.reshadeFlip = run.reshadeFlip;
    summary.reshadeMeanRelative = run.reshadeMeanRel;
    summary.counts = std::to_string(result.overBudget) + " proposals over budget, " +
                     std::to_string(result.duplicates) + " duplicates, " + std::to_string(result.unpackable) +
                     " unpackable, " + std::to_string(result.rejectedByValidation) + " rejected by validation";
    summary.constraints = search::describeConstraints(o.constraints);
    if (o.budgetModel != "nominal")  // search --budget-model: what the bytes of the front and the rows count
        summary.constraints.push_back("Bytes per pixel are effective bytes under " + o.budgetModel +
                                      " (--budget-model): the targets as the framebuffer-compression model stores the "
                                      "CPU codec's words of view 0, depth nominal, rounded up (docs/bandwidth.md)");
    for (int i : result.front) summary.front.push_back(result.evaluated[size_t(i)]);
    return summary;
}

// The front's layout files, beside the published deferred-shading layouts (first, as the front's
// files name the one each is set beside); every row evaluated per scene when there are several.
void writeFrontRows(const SearchRun& run, const search::SearchResult& result, SearchSummary& summary) {
    const SearchOptions& o = run.options;
    std::vector<SearchRow> publishedRows;
    for (const Layout& l : run.publishedLayouts) {
        SearchRow row;
        row.name = l.name;
        row.bytes = o.budgetModel == "nominal" ? bytesPerPixel(l) : int(std::ceil(run.effectiveBytes(l, run.threads) - 1e-9));
        if (run.severalScenes()) {
            row.fastPerScene = run.evaluatePerScene(l, run.threads);
            row.fast = search::meanEvaluation(row.fastPerScene);
        } else {
            row.fast = run.scenes[0]->evaluator->evaluate(l, run.threads);
        }
        row.how = "published";
        publishedRows.push_back(row);
    }
    summary.rows = writeFront(result, o.outDir / "front", o.commandLine, summary.objective, o.seed,
                              summary.constraints, publishedRows);
    if (run.severalScenes()) {
        for (const auto& scene : run.scenes) summary.sceneNames.push_back(scene->spec.name);
        for (SearchRow& row : summary.rows) row.fastPerScene = run.evaluatePerScene(loadLayoutFile(row.file), run.threads);
    }
    summary.rows.insert(summary.rows.end(), publishedRows.begin(), publishedRows.end());
}

// The confirmation: every row rendered in full by a comparison into <out>/compare, as
// `gbufferlab compare` with the arguments below would run it.
CompareResult confirmRows(const SearchRun& run, SearchSummary& summary) {
    const SearchOptions& o = run.options;
    std::vector<std::string> args = {"--size", summary.size, "--views", std::to_string(o.viewCount),
                                     "--out", (o.outDir / "compare").string(), "--force"};
    // The search's fast evaluation tone-maps at exposure 1: the confirmation too.
    args.insert(args.end(), {"--exposure", "1"});
    for (const std::string& scene : o.sceneArgs) args.insert(args.end(), {"--scene", scene});
    if (!o.envPath.empty()) args.insert(args.end(), {"--env", o.envPath});
    if (o.allowOutsideScene) args.push_back("--allow-outside-scene");
    if (!o.device.empty()) args.insert(args.end(), {"--device", o.device});
    std::string list;
    for (const SearchRow& r : summary.rows) list += (list.empty() ? "" : ",") + (r.found ? r.file : r.name);
    args.insert(args.end(), {"--layouts", list});
    compare::CompareOptions c;
    c.sceneArgs = o.sceneArgs;
    c.scenePath = o.sceneArgs.empty() ? std::string() : o.sceneArgs.back();
    if (o.sceneArgs.size() == 1 && o.sceneArgs[0] == "builtin") c.scenePath.clear();
    c.envPath = o.envPath;
    c.allowOutsideScene = o.allowOutsideScene;
    c.layoutsSpec = list;
    c.width = o.width;
    c.height = o.height;
    c.viewCount = o.viewCount;
    c.outDir = o.outDir / "compare";
    c.force = true;
    c.exposure = 1.0f;
    c.autoExposure = false;
    c.device = o.device;
    c.commandLine = "gbufferlab compare";
    for (const std::string& a : args) c.commandLine += " " + a;
    note(run.control, "search: confirming with full GPU renders: " + c.commandLine);
    CompareResult confirmation = runComparison(c, run.control);
    if (confirmation.interrupted()) return confirmation;
    const int rc = confirmation.exitStatus;
    if (rc != 0 && rc != compare::kExitRunsFailed)
        throwUserError("search: the confirming compare failed with status " + std::to_string(rc));
    readConfirmation(o.outDir / "compare" / "report.json", summary.rows);
    readFullMetrics(o.outDir / "compare" / "report.json", summary.rows);
    return confirmation;
}

SearchResult interrupted(int signal) {
    SearchResult result;
    result.interruptedBy = signal;
    result.exitStatus = 128 + signal;
    return result;
}

}  // namespace

int SearchResult::layoutsWritten() const {
    int written = 0;
    for (const SearchRow& r : summary.rows) written += r.found ? 1 : 0;
    return written;
}

void requirePackableBudget(int budget, const search::EngineConstraints& constraints) {
    const int smallest = search::smallestPackedBytes(constraints);
    if (budget < smallest)
        throwUserError("--budget " + std::to_string(budget) + ": no layout fits in " + std::to_string(budget) +
                       " bytes per pixel: the smallest the search can pack (fewest bits of every encoding within "
                       "the engine constraints, the smallest depth format they allow) takes " +
                       std::to_string(smallest) + "; give --budget " + std::to_string(smallest) +
                       " or more (or loosen --min-bits / give --search-depth)");
}

SearchResult runSearch(const SearchOptions& options, const RunControl& control) {
    if (const int signal = control.cancelSignal()) return interrupted(signal);
    SearchRun run{options, control};
    run.threads = options.threads > 0 ? options.threads : hardwareThreads();
    prepareInputs(run);
    choosePublishedLayouts(run);
    renderReferences(run);
    if (const int signal = control.cancelSignal()) return interrupted(signal);
    const search::SearchResult found = applyBudgetModel(run, exploreCandidates(run));
    if (const int signal = control.cancelSignal()) return interrupted(signal);
    if (found.front.empty())
        note(control, "search: no candidate fits in " + std::to_string(options.budget) + " B/px (" +
                          std::to_string(found.overBudget) + " proposals over budget, " +
                          std::to_string(found.unpackable) + " unpackable, " + std::to_string(found.duplicates) +
                          " duplicates): the front is empty; give a larger --budget");

    SearchResult result;
    result.outDir = options.outDir;
    result.summary = summarise(run, found);
    writeFrontRows(run, found, result.summary);
    if (options.confirm) {
        result.confirmation = confirmRows(run, result.summary);
        if (result.confirmation->interrupted()) {
            result.interruptedBy = result.confirmation->interruptedBy;
            result.exitStatus = result.confirmation->exitStatus;
            return result;
        }
    }
    result.closingNote = writeSearchReport(result.summary, options.outDir);
    return result;
}

}  // namespace gbl::app
