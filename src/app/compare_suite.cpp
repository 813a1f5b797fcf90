// compare over several scenes (compare_suite.h).
#include "compare_suite.h"

#include <algorithm>
#include <cstdio>
#include <mutex>

#include "compare_session.h"
#include "compare_timings.h"
#include "error.h"
#include "file_io.h"
#include "interrupt.h"  // signalName
#include "scene_suite.h"
#include "stage_clock.h"
#include "suite_report.h"

namespace gbl::compare {

namespace fs = std::filesystem;

namespace {

std::string firstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

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

// What the main thread and an interruption (a cancel request on another thread: the command
// line's signal watcher, interrupt.h) share: the scenes that finished, and whether the final
// report is written (then an interruption writes nothing) or the partial one.
struct SuiteProgress {
    std::mutex mutex;
    SuiteModel model;
    bool complete = false;
    std::optional<SuiteModel> partial;  // the report of the scenes that finished, once written
};

// Each scene's options: the suite's, with the scene's files, exposure, cameras and folder.
CompareOptions sceneOptions(const CompareOptions& o, const SceneSpec& spec) {
    CompareOptions so = o;
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
    return so;
}

// The suite's exit status from its scenes'; the line that says which failed.
void completeResult(app::CompareResult& result, const SuiteModel& model, const fs::path& outDir) {
    int status = 0;
    for (const SuiteScene& s : model.scenes) {
        if (s.exitStatus == kExitRunsFailed) status = kExitRunsFailed;
        else if (s.exitStatus != 0 && status == 0) status = s.exitStatus;
    }
    if (status == kExitRunsFailed) {
        int failed = 0;
        for (const SuiteScene& s : model.scenes) failed += s.ok ? 0 : 1;
        result.errors.push_back(std::to_string(failed) + " of " + std::to_string(model.scenes.size()) +
                                " scenes failed, or some of their runs (see " +
                                escapeText((outDir / "report.html").string()) + ")");
    }
    result.exitStatus = status;
}

}  // namespace

app::CompareResult runCompareSuite(const CompareOptions& options, const app::RunControl& control) {
    const CompareOptions& o = options;
    app::CompareResult result;
    result.outDir = o.outDir;
    if (const int signal = control.cancelSignal()) {  // asked before anything was read or written
        result.interruptedBy = signal;
        result.exitStatus = 128 + signal;
        return result;
    }
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

    // SIGINT, SIGTERM (a cancel request): the top report of the scenes that finished (the scene in
    // progress writes its own partial report first, compare_session.cpp), and INCOMPLETE naming
    // the signal, as a single scene's comparison does. Once.
    SuiteProgress progress;
    const auto interrupted = [&](int signal) {
        std::lock_guard lock(progress.mutex);
        if (progress.complete || progress.partial) return;
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
        progress.partial = std::move(partial);
    };
    // The result of a comparison stopped by a cancel request: the partial report, written now
    // unless the action (on the asking thread) wrote it.
    const auto stopped = [&](int signal) {
        if (control.cancel) control.cancel->setAction({});  // an action running is waited for
        interrupted(signal);
        result.interruptedBy = signal;
        result.exitStatus = 128 + signal;
        std::lock_guard lock(progress.mutex);
        result.suite = progress.partial;
        return result;
    };
    if (control.cancel) control.cancel->setAction(interrupted);
    struct ClearAction {
        CancelToken* token;
        ~ClearAction() {
            if (token) token->setAction({});
        }
    } clearAction{control.cancel};

    SuiteModel model;
    {
        CompareShared shared;  // the device, pipelines and IBL maps of every scene, freed after the last
        shared.onInterrupt = interrupted;
        double gpuPassMs = 0.0;
        for (size_t i = 0; i < scenes.size(); ++i) {
            if (const int signal = control.cancelSignal()) return stopped(signal);
            const SceneSpec& spec = scenes[i];
            const CompareOptions so = sceneOptions(o, spec);
            SuiteScene entry;
            entry.name = spec.name;
            entry.builtin = spec.gltfPath.empty();
            entry.scene = spec.gltfPath.empty() ? "built-in scene" : spec.gltfPath;
            entry.environment = spec.envPath.empty() ? "built-in procedural sky" : spec.envPath;
            if (control.progress)
                control.progress->note("\n== scene " + std::to_string(i + 1) + " of " + std::to_string(scenes.size()) +
                                       ": " + spec.name + " ==");
            try {
                CompareSession comparison(so, control, &shared);
                for (int view = 0; view < comparison.viewCount() && !comparison.cancelled(); ++view)
                    comparison.runView(view);
                if (const int signal = control.cancelSignal()) {
                    comparison.interrupted(signal);  // the scene's own partial report
                    return stopped(signal);
                }
                const app::CompareResult sceneResult = comparison.finish();
                if (control.onReport) control.onReport(sceneResult);
                entry.exitStatus = sceneResult.exitStatus;
                entry.report = sceneResult.report;
                entry.scene = entry.report->run.scene;
                entry.environment = entry.report->run.environment;
                gpuPassMs += comparison.gpuPassMs();
            } catch (const std::exception& e) {
                // This scene's runs fail, the others still run; the exit status says so.
                entry.ok = false;
                entry.error = firstLine(e.what());
                entry.exitStatus = kExitRunsFailed;
                if (control.progress)
                    control.progress->error("scene " + spec.name + " (" + spec.origin + "): " + entry.error);
            }
            std::lock_guard lock(progress.mutex);
            progress.model.scenes.push_back(std::move(entry));
        }
        std::lock_guard lock(progress.mutex);
        model = progress.model;
        completeSuiteModel(model, o);
        writeSuiteReport(o.outDir, model);
        result.timings = collectTimings(StageClock::global().read(), gpuPassMs,
                                        shared.ctx && shared.ctx->info.type == VK_PHYSICAL_DEVICE_TYPE_CPU);
        writeTimings(o.outDir, *result.timings);
        std::error_code ec;
        fs::remove(marker, ec);
        progress.complete = true;
    }
    completeResult(result, model, o.outDir);
    result.suite = std::move(model);
    if (control.onReport) control.onReport(result);
    return result;
}

}  // namespace gbl::compare
