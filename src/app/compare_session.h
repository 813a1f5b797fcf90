#pragma once
// compare, the whole comparison: one device, renderer and (with --eval gpu) evaluator for every
// view, IBL mode and layout; the report model the runs fill; the writer their files go to.
//
// The steps, in the order runComparison (compare_api.h) calls them:
//   CompareSession(options, control)  set-up: inputs read and validated, device, output folder
//                            (marked INCOMPLETE until the report is written), pipelines built;
//   runView(v) per view      the references under each mode, the lighting approximations against
//                            the ground truth (with --ibl ...,ground-truth), the IBL figure (first
//                            view), then every layout under every mode;
//   finish()                 waits for the image files, writes the report; the result.
// A cancel request (RunControl::cancel; the command line's on SIGINT, SIGTERM) at any point after
// the set-up writes the report of the runs that finished (compare_session.cpp), at once on the
// asking thread; the runs stop at the next layout, and interrupted(signal) gives the result.
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "background_writer.h"
#include "compare_api.h"
#include "compare_bands.h"
#include "compare_compression.h"
#include "compare_options.h"
#include "compare_runs.h"
#include "compare_views.h"
#include "gpu_evaluator.h"
#include "progress.h"
#include "renderer.h"
#include "report_model.h"
#include "scene_inputs.h"
#include "vk_context.h"
#include "wiring_codegen.h"

namespace gbl::compare {

// What the scenes of one comparison share (compare --scene A --scene B, compare_suite.h): the
// device, every pipeline (those that do not depend on the scene are built once) and the IBL
// pre-computation of each environment. Destroyed after the scenes' sessions.
struct CompareShared {
    std::optional<VulkanContext> ctx;  // created by the first scene's session
    PipelineMemo pipelines;
    std::map<std::string, IblMaps> ibl;  // by environment file ("": the built-in sky)
    // The comparison's own cancel action (the report of the scenes that finished): a scene's
    // session runs it after writing its own partial report, and puts it back when it finishes.
    std::function<void(int signal)> onInterrupt;
    CompareShared() = default;
    CompareShared(const CompareShared&) = delete;
    CompareShared& operator=(const CompareShared&) = delete;
    ~CompareShared();
};

class CompareSession {
public:
    // `shared`: the device, pipelines and IBL maps of the other scenes of the comparison (null: its own).
    CompareSession(const CompareOptions& options, const app::RunControl& control, CompareShared* shared = nullptr);
    CompareSession(const CompareSession&) = delete;
    CompareSession& operator=(const CompareSession&) = delete;

    int viewCount() const { return int(views_.size()); }
    // Every run of view `view` (0 first: its runs are the report's rows; the later views' add
    // their metrics to those rows, in the same order).
    void runView(int view);
    // After the last view: waits for the image files, writes the report. The result's exit status:
    // 0, 1 (a file could not be written) or kExitRunsFailed.
    app::CompareResult finish();
    // Instead of finish() when the control's cancel was asked: the report of the runs that finished
    // (written by the cancel action, or now), the exit status 128 + `signal`.
    app::CompareResult interrupted(int signal);
    // Whether the control's cancel was asked (the runs stop at the next layout).
    bool cancelled() const { return control_.cancelSignal() != 0; }
    // The report (complete after finish()).
    const ReportModel& model() const { return model_; }
    double gpuPassMs() const { return gpuPassMs_; }

private:
    using References = std::map<std::string, ReferenceRender>;  // by IBL mode name

    RenderSettings settingsFor(IblMode mode, int view) const;
    // The view's exposure: --exposure, or metered from the view's first reference (auto_exposure.h).
    float exposure(int view) const { return viewExposures_.at(size_t(view)); }
    // From the view's first reference: its covered fraction, with `meter` its exposure, and whether
    // it has anything to measure (measure/view_content.h).
    void observeView(int view, const Image& referenceHdr, bool meter);
    // Why view `view` has nothing to measure, "" when it has (set by observeView).
    std::string viewNotMeasured(int view);
    // After the last view (or an interruption): each run's metrics the mean over its measured views,
    // the views left out named, a run with none measured NotMeasured.
    void finishRuns(ReportModel& model) const;
    void preparePipelines();
    // The constructor's steps, in its order.
    void loadInputs();
    void openDevice();
    void describeRun();
    void placeViews();
    void openOutput();
    void createRenderer();
    References renderReferences(int view);
    void compareLightingModes(int view, References& references);
    void addIblFigure(const References& references);  // the IBL figure's rows, its file queued
    void runLayouts(int view, const References& references);
    RunReport makeRun(const Layout& layout, const std::string& mode) const;
    // Into the model: a first view's run as a new row, a later view's into its row.
    void record(RunReport&& run, int view);
    void writeInterruptedReport(int signal);

    const CompareOptions& options_;
    const app::RunControl& control_;
    CompareShared* shared_ = nullptr;
    std::vector<Layout> layouts_;
    Layout referenceLayout_;
    SceneInputs inputs_;
    std::optional<VulkanContext> ownCtx_;
    const VulkanContext* ctx_ = nullptr;  // &*ownCtx_, or the shared one
    BandPlan bandPlan_;
    bool gpuEval_ = false;
    // Some material of the scene is drawn forward (transmission, volume: render/forward_mask.h):
    // each view's references carry the mask of its pixels, left out of every metric.
    bool forwardScene_ = false;
    WiringOptions wiringOptions_;
    ReportModel model_;
    std::unique_ptr<GpuEvaluator> evaluator_;
    std::vector<CompareView> views_;
    std::vector<float> viewExposures_;  // per view (compare --exposure: all the same)
    int steps_ = 0;  // progress steps: references, lighting comparisons and runs, every view
    std::optional<Progress> progress_;
    std::filesystem::path incompleteMarker_;
    std::mutex modelMutex_;  // model_.runs, shared with the interrupt action
    bool reportComplete_ = false;
    bool interruptionStarted_ = false;              // writeInterruptedReport ran, or runs
    std::optional<ReportModel> interruptedReport_;  // the partial report, once written
    std::optional<BackgroundWriter> imageWriter_;
    ImageOutput imageOutput_;
    double gpuPassMs_ = 0.0;  // timestamps of every frame rendered
    std::optional<Renderer> renderer_;
    GBufferWiring referenceWiring_;
    size_t runIndex_ = 0;  // the row of the next run recorded in this view
    size_t bandedReferenceMode_ = 0;  // in bands: the mode whose reference statistics the evaluator holds
    // Bandwidth as GPUs pay it: the lighting model resolved (volumes counted from the scene's lights),
    // and each layout's compressed sizes from view 0's words (compare_compression.h), by layout name.
    LightingModel lighting_;
    std::map<std::string, FrameCompression> compression_;
    // The cancel action (set by the constructor) uses the members above: this clears it before
    // any of them is destroyed, on every way out, a constructor that throws included (a member
    // declared last is destroyed first; a destructor's body would not run then).
    struct InterruptActionGuard {
        CancelToken* token = nullptr;      // set: the action is the token's
        std::function<void(int)> restore;  // the comparison's own action (CompareShared::onInterrupt), or none
        ~InterruptActionGuard();
    } interruptGuard_;
};

}  // namespace gbl::compare
