#pragma once
// compare, the whole comparison: one device, renderer and (with --eval gpu) evaluator for every
// view, IBL mode and layout; the report model the runs fill; the writer their files go to.
//
// The steps, in the order runCompareCommand calls them:
//   CompareSession(options)  set-up: inputs read and validated, device, output folder (marked
//                            INCOMPLETE until the report is written), pipelines built;
//   runView(v) per view      the references under each mode, the lighting approximations against
//                            the ground truth (with --ibl ...,ground-truth), the IBL figure (first
//                            view), then every layout under every mode;
//   finish()                 waits for the image files, writes the report; the exit status.
// An interruption (SIGINT, SIGTERM) at any point after the set-up writes the report of the runs
// that finished (compare_session.cpp).
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "background_writer.h"
#include "compare_bands.h"
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

// Exit status when the report was written but some runs failed (1: bad input, 2: usage, 3: bug).
inline constexpr int kExitRunsFailed = 4;

// What the scenes of one comparison share (compare --scene A --scene B, compare_suite.h): the
// device, every pipeline (those that do not depend on the scene are built once) and the IBL
// pre-computation of each environment. Destroyed after the scenes' sessions.
struct CompareShared {
    std::optional<VulkanContext> ctx;  // created by the first scene's session
    PipelineMemo pipelines;
    std::map<std::string, IblMaps> ibl;  // by environment file ("": the built-in sky)
    CompareShared() = default;
    CompareShared(const CompareShared&) = delete;
    CompareShared& operator=(const CompareShared&) = delete;
    ~CompareShared();
};

class CompareSession {
public:
    // `shared`: the device, pipelines and IBL maps of the other scenes of the comparison (null: its own).
    explicit CompareSession(const CompareOptions& options, CompareShared* shared = nullptr);
    CompareSession(const CompareSession&) = delete;
    CompareSession& operator=(const CompareSession&) = delete;

    int viewCount() const { return int(views_.size()); }
    // Every run of view `view` (0 first: its runs are the report's rows; the later views' add
    // their metrics to those rows, in the same order).
    void runView(int view);
    // After the last view: waits for the image files, writes the report and prints the table.
    // Returns the exit status: 0, 1 (a file could not be written) or kExitRunsFailed.
    int finish();
    // The report (complete after finish()).
    const ReportModel& model() const { return model_; }
    double gpuPassMs() const { return gpuPassMs_; }

private:
    using References = std::map<std::string, ReferenceRender>;  // by IBL mode name

    RenderSettings settingsFor(IblMode mode, int view) const;
    // The view's exposure: --exposure, or metered from the view's first reference (auto_exposure.h).
    float exposure(int view) const { return viewExposures_.at(size_t(view)); }
    // From the view's first reference: its covered fraction, and with `meter` its exposure.
    void observeView(int view, const Image& referenceHdr, bool meter);
    void preparePipelines();
    References renderReferences(int view);
    void compareLightingModes(int view, References& references);
    void addIblFigure(const References& references);  // the IBL figure's rows, its file queued
    void runLayouts(int view, const References& references);
    RunReport makeRun(const Layout& layout, const std::string& mode) const;
    // Into the model: a first view's run as a new row, a later view's into its row.
    void record(RunReport&& run, int view);
    void writeInterruptedReport(int signal);

    const CompareOptions& options_;
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
    std::optional<BackgroundWriter> imageWriter_;
    ImageOutput imageOutput_;
    double gpuPassMs_ = 0.0;  // timestamps of every frame rendered
    std::optional<Renderer> renderer_;
    GBufferWiring referenceWiring_;
    size_t runIndex_ = 0;  // the row of the next run recorded in this view
    size_t bandedReferenceMode_ = 0;  // in bands: the mode whose reference statistics the evaluator holds
    // The interrupt action (set by the constructor) uses the members above: this clears it before
    // any of them is destroyed, on every way out, a constructor that throws included (a member
    // declared last is destroyed first; a destructor's body would not run then).
    struct InterruptActionGuard {
        bool set = false;
        ~InterruptActionGuard();
    } interruptGuard_;
};

}  // namespace gbl::compare
