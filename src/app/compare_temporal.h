#pragma once
// compare --temporal N: one sequence of N jittered frames of a wiring rendered and resolved
// (image/temporal_resolve.h), and the first frame's metrics beside the resolved ones.
#include "compare_runs.h"
#include "renderer.h"
#include "report_model.h"
#include "temporal_resolve.h"

namespace gbl::compare {

struct TemporalRender {
    // hdr: the resolve; surfaces: the temporal mean of the decoded attributes (SurfaceMean);
    // timings: the sums over the frames.
    RenderOutput resolved;
    RenderOutput first;  // frame 0 as rendered (hdr and surfaces)
};

// Renders frames 0 .. frames - 1 of `settings` with temporalJitter's offsets and frame indices,
// accumulating as they come (no frame is kept but the first): only the G-buffer, lighting and
// read-back run per frame; the pipelines and the IBL pre-computation are the renderer's.
TemporalRender renderTemporal(Renderer& renderer, const GBufferWiring& wiring, const RenderSettings& settings,
                              int frames, ResolveMethod method);

// The first frames' metrics (test frame 0 against reference frame 0, whose prepared tone map and
// FLIP half `reference.prepared` holds) into run.singleFrame.
void measureSingleFrame(RunReport& run, const RenderOutput& testFirst, const ReferenceRender& referenceFirst,
                        float exposure, bool hdrFlip);

// A view's single-frame metrics into run.singleFrame->views; after the last view, their mean
// (finishSingleFrameViews, as finishViews does for the run).
void addSingleFrameView(RunReport& into, const RunReport& run);
void finishSingleFrameViews(RunReport& run);

}  // namespace gbl::compare
