// compare over several scenes (compare_suite.h).
#include "compare_suite.h"

#include <algorithm>
#include <cstdio>
#include <mutex>

#include "compare_console.h"
#include "compare_session.h"
#include "error.h"
#include "file_io.h"
#include "interrupt.h"
#include "scene_suite.h"
#include "stage_clock.h"
#include "suite_report.h"

namespace gbl::compare {

namespace fs = std::filesystem;

namespace {

std::string firstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

void printSuiteTable(const SuiteModel& model) {
    int w = 20;
    for (const SuiteLayoutSummary& row : model.summary) w = std::max(w, int(row.layout.size()));
    std::printf("\nAcross %d scenes (error: mean LDR-FLIP over each scene's views; rank 1 = lowest in that scene):\n",
                int(model.scenes.size()));
    std::printf("%-*s %-12s %5s %9s %6s %6s %6s", w, "layout", "ibl", "B/px", "mean FLIP", "tied#", "mean#",
                "worst#");
    for (const SuiteScene& s : model.scenes) std::printf(" %16.16s", s.name.c_str());
    std::printf("\n");
    for (const SuiteLayoutSummary& row : model.summary) {
        std::printf("%-*s %-12s %5d", w, row.layout.c_str(), row.iblMode.c_str(), row.bytesPerPixel);
        if (row.scenesMeasured)
            std::printf(" %9.5f %6s %6.2f %6d", row.meanError, row.tiedRankAcross.c_str(), row.meanRank, row.worstRank);
        else
            std::printf(" %9s %6s %6s %6s", "FAILED", "", "", "");
        for (size_t s = 0; s < model.scenes.size(); ++s) {
            char buf[40] = "-";
            if (row.errors[s]) std::snprintf(buf, sizeof(buf), "%.5f (%s)", *row.errors[s], row.tiedRanks[s].c_str());
            std::printf(" %16s", buf);
        }
        std::printf("\n");
    }
    std::printf("tied#: by mean FLIP over the scenes, a range where differences are not significant (%s); per scene: "
                "its FLIP (its own tied rank); mean#, worst#: plain ranks\n", model.acrossScenes.method.c_str());
    for (const SceneAgreement& g : model.agreement)
        std::printf("rank agreement %s / %s (%s): Kendall's tau-b %.2f, %d of %d layout pairs swap\n", g.sceneA.c_str(),
                    g.sceneB.c_str(), g.iblMode.c_str(), g.tau, int(g.swaps.size()), g.pairs);
    for (const SuiteScene& s : model.scenes)
        if (!s.ok) std::printf("scene %s FAILED: %s\n", s.name.c_str(), s.error.c_str());
}

}  // namespace

bool comparesSeveralScenes(const CompareOptions& options) {
    const auto& a = options.sceneArgs;
    return a.size() > 1 || (a.size() == 1 && a[0].size() > 5 && a[0].compare(a[0].size() - 5, 5, ".toml") == 0);
}

namespace {

// The top report's shared facts, from the scenes that finished (the first one's run).
void completeSuiteModel(SuiteModel& model, const CompareOptions& o) {
    for (const SuiteScene& s : model.scenes)
        if (s.report) {
            model.run = s.report->run;
            break;
        }
    model.run.scene.clear();
    model.run.environment.clear();
    model.run.views.clear();
    model.run.viewNotMeasured.clear();
    model.run.notes = {"each scene's own report, with its images, notes and views, is in scenes/<name>/; "
                       "scenes[i].report below is that report (its paths relative to that folder)",
                       "pipelines, the device and each environment's IBL pre-computation are shared by the "
                       "scenes"};
    if (model.run.commandLine.empty()) model.run.commandLine = o.commandLine;
    summariseSuite(model);
}

// What the main thread and an interruption (the watcher thread, interrupt.h) share: the scenes
// that finished, and whether the final report is written (then an interruption writes nothing).
struct SuiteProgress {
    std::mutex mutex;
    SuiteModel model;
    bool complete = false;
};

}  // namespace

int runCompareSuite(const CompareOptions& options) {
    const CompareOptions& o = options;
    // Everything given is read and checked before the first pixel: the layouts, the scenes' files.
    checkOutputDirectory(o.outDir, o.force, "--out");
    const std::vector<Layout> layouts = resolveLayouts(o.layoutsSpec);
    const std::vector<SceneSpec> scenes = resolveScenes(o.sceneArgs, o.envPath);
    if (o.force) {
        std::vector<std::string> inputs;
        for (const SceneSpec& s : scenes) inputs.insert(inputs.end(), {s.gltfPath, s.envPath});
        for (const std::string& a : o.sceneArgs) inputs.push_back(a);
        for (const Layout& l : layouts) inputs.push_back(l.sourceFile);
        refuseInputsInsideDirectory(o.outDir, inputs, "--out");
    }
    prepareOutputDirectory(o.outDir, o.force, "--out");
    const fs::path marker = o.outDir / "INCOMPLETE";
    writeFileAtomic(marker, "gbufferlab compare over " + std::to_string(scenes.size()) +
                                " scenes has not finished: this folder is incomplete\n");

    // SIGINT, SIGTERM: the top report of the scenes that finished (the scene in progress writes its
    // own partial report first, compare_session.cpp), and INCOMPLETE naming the signal, as a single
    // scene's comparison does.
    SuiteProgress progress;
    const auto interrupted = [&](int signal) {
        std::lock_guard lock(progress.mutex);
        if (progress.complete) return;
        SuiteModel partial = progress.model;
        SuiteInterruption what;
        what.signal = signalName(signal);
        what.scenesPlanned = int(scenes.size());
        for (size_t i = partial.scenes.size(); i < scenes.size(); ++i) what.notFinished.push_back(scenes[i].name);
        partial.interruption = what;
        completeSuiteModel(partial, o);
        writeSuiteReport(o.outDir, partial);
        writeFileAtomic(marker, "INCOMPLETE: interrupted by " + what.signal + " after " +
                                    std::to_string(partial.scenes.size()) + " of " + std::to_string(scenes.size()) +
                                    " scenes; report.json and report.html cover only the scenes that finished\n");
    };
    setInterruptAction(interrupted);
    struct ClearAction {
        ~ClearAction() { setInterruptAction({}); }
    } clearAction;

    std::vector<CompareOptions> sceneOptions(scenes.size(), o);
    SuiteModel model;
    {
        CompareShared shared;  // the device, pipelines and IBL maps of every scene, freed after the last
        shared.onInterrupt = interrupted;
        double gpuPassMs = 0.0;
        for (size_t i = 0; i < scenes.size(); ++i) {
            const SceneSpec& spec = scenes[i];
            CompareOptions& so = sceneOptions[i];
            so.scenePath = spec.gltfPath;
            so.envPath = spec.envPath;
            if (spec.exposure) {
                so.exposure = *spec.exposure;
                so.autoExposure = false;
            }
            if (!spec.cameras.empty()) {
                so.cameras = spec.cameras;
                so.viewCount = int(spec.cameras.size());
            }
            so.outDir = o.outDir / "scenes" / spec.name;
            SuiteScene entry;
            entry.name = spec.name;
            entry.scene = spec.gltfPath.empty() ? "built-in scene" : spec.gltfPath;
            entry.environment = spec.envPath.empty() ? "built-in procedural sky" : spec.envPath;
            std::printf("\n== scene %d of %d: %s ==\n", int(i + 1), int(scenes.size()), spec.name.c_str());
            std::fflush(stdout);
            try {
                CompareSession comparison(so, &shared);
                for (int view = 0; view < comparison.viewCount(); ++view) comparison.runView(view);
                entry.exitStatus = comparison.finish();
                entry.report = comparison.model();
                entry.scene = entry.report->run.scene;
                entry.environment = entry.report->run.environment;
                gpuPassMs += comparison.gpuPassMs();
            } catch (const std::exception& e) {
                // This scene's runs fail, the others still run; the exit status says so.
                entry.ok = false;
                entry.error = firstLine(e.what());
                entry.exitStatus = kExitRunsFailed;
                std::fprintf(stderr, "gbufferlab: error: scene %s (%s): %s\n", spec.name.c_str(), spec.origin.c_str(),
                             entry.error.c_str());
            }
            std::lock_guard lock(progress.mutex);
            progress.model.scenes.push_back(std::move(entry));
        }
        std::lock_guard lock(progress.mutex);
        model = progress.model;
        completeSuiteModel(model, o);
        writeSuiteReport(o.outDir, model);
        printSuiteTable(model);
        reportStageTimes(o.outDir, StageClock::global().read(), gpuPassMs, shared.ctx &&
                             shared.ctx->info.type == VK_PHYSICAL_DEVICE_TYPE_CPU);
        std::error_code ec;
        fs::remove(marker, ec);
        progress.complete = true;
    }
    std::printf("report: %s\n", (o.outDir / "report.html").string().c_str());
    int status = 0;
    for (const SuiteScene& s : model.scenes) {
        if (s.exitStatus == kExitRunsFailed) status = kExitRunsFailed;
        else if (s.exitStatus != 0 && status == 0) status = s.exitStatus;
    }
    if (status == kExitRunsFailed) {
        int failed = 0;
        for (const SuiteScene& s : model.scenes) failed += s.ok ? 0 : 1;
        std::fprintf(stderr, "gbufferlab: error: %d of %d scenes failed, or some of their runs (see %s)\n", failed,
                     int(model.scenes.size()), escapeText((o.outDir / "report.html").string()).c_str());
    }
    return status;
}

}  // namespace gbl::compare
