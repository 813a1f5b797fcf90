#include "compare_temporal.h"

#include "run_metrics.h"
#include "stage_clock.h"
#include "view_stats.h"

namespace gbl::compare {

TemporalRender renderTemporal(Renderer& renderer, const GBufferWiring& wiring, const RenderSettings& settings,
                              int frames, ResolveMethod method) {
    const std::vector<JitterOffset> jitter = temporalJitter(frames);
    HdrResolve hdr(method);
    SurfaceMean surfaces;
    TemporalRender out;
    for (int k = 0; k < int(jitter.size()); ++k) {
        RenderSettings s = settings;
        s.jitterX = jitter[size_t(k)].x;
        s.jitterY = jitter[size_t(k)].y;
        s.frameIndex = uint32_t(k);
        RenderOutput frame = renderer.render(wiring, s);
        out.resolved.timings.gbufferMs += frame.timings.gbufferMs;
        out.resolved.timings.lightingMs += frame.timings.lightingMs;
        {
            ScopedStage timed(Stage::Metrics);  // the accumulation is the resolve's, not the render's
            hdr.add(frame.hdr);
            surfaces.add(frame.surfaces);
        }
        if (k == 0) out.first = std::move(frame);
    }
    ScopedStage timed(Stage::Metrics);
    out.resolved.hdr = hdr.resolved();
    out.resolved.surfaces = surfaces.mean();
    return out;
}

void measureSingleFrame(RunReport& run, const RenderOutput& testFirst, const ReferenceRender& referenceFirst,
                        float exposure, bool hdrFlip) {
    ScopedStage timed(Stage::Metrics);
    RunMetricsOptions options;
    options.hdrFlip = hdrFlip;
    options.prepared = referenceFirst.prepared.get();
    options.excluded = referenceFirst.forwardMask.get();
    const RunMetrics m = computeRunMetrics(referenceFirst.output.surfaces, testFirst.surfaces,
                                           referenceFirst.output.hdr, testFirst.hdr, exposure, options);
    RunReport single;
    fillMetrics(single, m);
    run.singleFrame = SingleFrameMetrics{single.attributes, single.image, {}};
}

void addSingleFrameView(RunReport& into, const RunReport& run) {
    if (!run.singleFrame || !into.singleFrame) return;
    into.singleFrame->views.push_back({run.singleFrame->attributes, run.singleFrame->image});
}

void finishSingleFrameViews(RunReport& run) {
    if (!run.singleFrame) return;
    SingleFrameMetrics& s = *run.singleFrame;
    if (s.views.size() > 1) {
        RunReport mean;
        mean.views = s.views;
        averageViews(mean);
        s.attributes = mean.attributes;
        s.image = mean.image;
    }
    s.views.clear();
}

}  // namespace gbl::compare
