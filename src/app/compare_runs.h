#pragma once
// compare, one run: its metrics against the reference into the report model, and its error
// images, EXR render and worst-region crops (compare_session_view.cpp drives the runs).
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "background_writer.h"
#include "image_io.h"
#include "gpu_evaluator.h"
#include "renderer.h"
#include "report_model.h"
#include "run_metrics.h"

namespace gbl::compare {

struct ReferenceRender {
    RenderOutput output;
    std::string renderPng;  // relative to the report dir
    std::unique_ptr<PreparedReference> prepared;  // of output.hdr, shared by the runs measured against it
    // --eval gpu: the evaluator the runs are measured with, on output.device (not owned).
    GpuEvaluator* evaluator = nullptr;
    // compare --temporal N (N > 1): `output` is the resolve of the N frames (compare_temporal.h),
    // this the first frame, prepared, for the runs' single-frame metrics.
    std::unique_ptr<ReferenceRender> firstFrame;
    // The view's pixels drawn forward (render/forward_mask.h), left out of every metric of the runs
    // measured against this reference (RunMetricsOptions::excluded); null: none.
    std::shared_ptr<const std::vector<uint8_t>> forwardMask;
};

// The render's device images as the GPU evaluator takes them (RenderSettings::keepOnDevice).
DeviceRender deviceView(const RenderOutput& r);

// Copies a run's metrics (run_metrics.h) into its report row.
void fillMetrics(RunReport& run, const RunMetrics& m);

// How a run's image files are written: on `writer`'s threads when set (the paths go into the
// report at once; the files follow while the next run renders; a failed job's `what` is the run's
// file prefix), else before measureRun returns; EXR files (render.exr, errors.exr) as `exrType`.
struct ImageOutput {
    BackgroundWriter* writer = nullptr;
    ExrPixelType exrType = ExrPixelType::Float32;
    bool errorExr = false;  // errors.exr (--error-exr; the CPU evaluation only)
};

// The comparison of one rendered run against its reference: metrics, images, crops. `test` is
// moved from when `releaseTest` (its surfaces are freed once measured: peak memory at 4K; with a
// writer, its HDR image too, handed to the writer).
// With reference.evaluator (--eval gpu) the metrics and the error images are computed on the
// device from test.device: only numbers and 8-bit images come back (render.exr and the log
// preview read the HDR image back; errors.exr, whose float maps stay on the device, is not
// written).
void measureRun(RunReport& run, RenderOutput& test, const ReferenceRender& reference, const std::filesystem::path& outDir,
                const std::string& prefix, float exposure, bool hdrFlip, bool releaseTest, bool writeImages = true,
                const ImageOutput& output = {});

// Image files that could not be written: a run whose files they were (its file prefix) fails
// with the message, its images unnamed; the others come back as one line each, and are noted in
// the report ("not written: ...").
std::vector<std::string> failRunsOfWriteFailures(ReportModel& model, const std::vector<WriteFailure>& failures);

// The files of a run measured on the device (--eval gpu, bands): the evaluator's 8-bit images, the
// HDR render (render.exr, render_log.png) and the worst-region crops; their names go into `run`.
// `hdr` gives the HDR image when the files are written: on the writer's thread, so that a
// download from the device overlaps the next run (on an H200 a 4K download took 85 ms).
void queueDeviceImages(RunReport& run, GpuErrorImages&& images, const RunMetrics& metrics,
                       std::function<std::shared_ptr<const Image>()> hdr, const std::filesystem::path& outDir,
                       const std::string& prefix, const ImageOutput& output);

}  // namespace gbl::compare
