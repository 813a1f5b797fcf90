// compare, one view: the references under each IBL mode, the lighting approximations against the
// ground truth, the IBL figure (first view), then every layout under every mode.
#include <cstdio>

#include "compare_session.h"
#include "compare_temporal.h"
#include "compare_text.h"
#include "forward_mask.h"
#include "host_profile.h"
#include "ibl_figure.h"
#include "image_io.h"
#include "parallel_invoke.h"
#include "run_metrics.h"
#include "stage_clock.h"
#include "tone_map.h"

namespace gbl::compare {

void CompareSession::runView(int view) {
    runIndex_ = 0;
    bandedReferenceMode_ = 0;
    References references = renderReferences(view);
    if (options_.compareLighting()) {
        compareLightingModes(view, references);
        if (view == 0) addIblFigure(references);
    }
    runLayouts(view, references);
}

CompareSession::References CompareSession::renderReferences(int view) {
    const CompareOptions& o = options_;
    const bool firstView = view == 0;
    const std::string viewLabel = o.viewCount > 1 ? " [view " + std::to_string(view) + "]" : "";
    References references;
    // The view's pixels drawn forward (render/forward_mask.h): counted here, left out of every
    // metric of every run measured against these references.
    std::shared_ptr<const std::vector<uint8_t>> forwardMask;
    if (forwardScene_) {
        progress_->begin("forward-drawn pixels" + viewLabel);
        auto mask = std::make_shared<std::vector<uint8_t>>(
            renderForwardMask(*renderer_, inputs_.scene, settingsFor(o.modes[0], view)));
        size_t count = 0;
        for (uint8_t m : *mask) count += m ? 1 : 0;
        const double percent = mask->empty() ? 0.0 : 100.0 * double(count) / double(mask->size());
        char buf[200];
        std::snprintf(buf, sizeof buf, "%.2f %% of pixels forward, excluded", percent);
        progress_->end(buf);
        std::string materials;
        for (const Material& m : inputs_.scene.materials)
            if (!m.forward.empty() && materials.find(m.forward) == std::string::npos)
                materials += (materials.empty() ? "" : ", ") + m.forward;
        {
            std::lock_guard lock(modelMutex_);
            model_.run.notes.push_back(std::string(buf) + " from every metric (materials drawn forward by deferred "
                                       "engines: " + materials + ")" + viewLabel);
        }
        forwardMask = std::move(mask);
    }
    for (size_t m = 0; m < o.modes.size(); ++m) {
        progress_->begin("reference / " + o.modeNames[m] + viewLabel);
        ReferenceRender ref;
        // The view's exposure (metered on its first reference unless --exposure) and covered fraction.
        const bool observe = m == 0, meter = o.autoExposure && observe;
        if (bandPlan_.banded()) {  // its statistics into the evaluator, its HDR image for the files
            if (meter) {  // the exposure is needed before the evaluator takes the reference's statistics
                Image metered;
                const PassTimings t = renderReferenceInBands(*renderer_, referenceWiring_, settingsFor(o.modes[m], view),
                                                             bandPlan_, *evaluator_, 1.0f, &metered);
                gpuPassMs_ += t.gbufferMs + t.lightingMs;
                observeView(view, metered, true);
            }
            ref.output.timings = renderReferenceInBands(*renderer_, referenceWiring_, settingsFor(o.modes[m], view),
                                                        bandPlan_, *evaluator_, exposure(view),
                                                        firstView || (observe && !meter) ? &ref.output.hdr : nullptr);
            if (observe && !meter) observeView(view, ref.output.hdr, false);
            if (!firstView) ref.output.hdr = Image{};
            bandedReferenceMode_ = m;
        } else if (o.temporalFrames > 1) {  // the resolve; its first frame for the single-frame metrics
            TemporalRender t = renderTemporal(*renderer_, referenceWiring_, settingsFor(o.modes[m], view),
                                              o.temporalFrames, o.resolve);
            ref.output = std::move(t.resolved);
            ref.firstFrame = std::make_unique<ReferenceRender>();
            ref.firstFrame->output = std::move(t.first);
        } else {
            ref.output = renderer_->render(referenceWiring_, settingsFor(o.modes[m], view));
        }
        gpuPassMs_ += ref.output.timings.gbufferMs + ref.output.timings.lightingMs;
        // --eval gpu keeps the render on the device; its files (and the IBL figure) need it here.
        const bool hostHdr = firstView || o.compareLighting() || observe;
        if (gpuEval_ && !bandPlan_.banded() && ref.output.hdr.empty() && hostHdr) {
            ScopedStage timed(Stage::Readback);
            ref.output.hdr = ref.output.device->downloadHdr();
        }
        if (observe && !bandPlan_.banded()) {
            ScopedStage timed(Stage::Metrics);
            observeView(view, ref.output.hdr, meter);
        }
        if (firstView) {
            ref.renderPng = "reference-" + o.modeNames[m] + ".png";
            const std::string renderExr = "reference-" + o.modeNames[m] + ".exr";
            ScopedStage timed(Stage::Report);
            const std::string preview = "reference-" + o.modeNames[m] + "-log.png";
            imageWriter_->enqueue("images of the reference / " + o.modeNames[m],
                                  [png = (o.outDir / ref.renderPng).string(), exr = (o.outDir / renderExr).string(),
                                   log = (o.outDir / preview).string(), exposure = this->exposure(view), exrType = o.exrType,
                                   hdr = gpuEval_ && !o.compareLighting()  // the files are its last use
                                             ? std::make_shared<const Image>(std::move(ref.output.hdr))
                                             : std::make_shared<const Image>(ref.output.hdr)] {
                                      // Side by side (each file is one core's work: 4K on a GPU)
                                      parallelInvoke({[&] { writePng(png, toneMapToSrgb8(*hdr, exposure)); },
                                                      [&] { writeExr(exr, *hdr, {}, exrType); },
                                                      [&] { writePng(log, logEncodeForPreview(*hdr)); }});
                                  });
            model_.reference.images.push_back({o.modeNames[m], ref.renderPng, renderExr, preview});
        }
        std::string gtNote;
        if (o.modes[m] == IblMode::GroundTruth) {
            const GroundTruthStats& g = ref.output.groundTruth;
            char buf[256];
            std::snprintf(buf, sizeof(buf),
                          "ground truth: %d batches x %d steps (%d samples per pixel, GGX + environment by MIS), mean "
                          "relative noise %.5f (target %.5f%s), lighting %.0f ms GPU on %s",
                          g.batches, o.gtBatchSamples, g.samplesPerPixel, g.meanRelativeNoise, g.targetRelativeNoise,
                          g.targetMet ? ", met" : ", NOT met", g.lightingMs, ctx_->info.name.c_str());
            gtNote = buf;
            std::lock_guard lock(modelMutex_);
            model_.run.notes.push_back(gtNote + viewLabel);
        }
        const std::string nothing = observe ? viewNotMeasured(view) : std::string();
        progress_->end("G-buffer " + std::to_string(int(ref.output.timings.gbufferMs)) + " ms, lighting " +
                       std::to_string(int(ref.output.timings.lightingMs)) + " ms" +
                       (gtNote.empty() ? "" : ", " + std::to_string(ref.output.groundTruth.batches) + " batches") +
                       (nothing.empty() ? "" : "; this view is not measured: " + nothing));
        ref.forwardMask = forwardMask;
        if (ref.firstFrame) ref.firstFrame->forwardMask = forwardMask;
        ReferenceRender& stored = references[o.modeNames[m]] = std::move(ref);
        if (gpuEval_) {
            stored.evaluator = evaluator_.get();
            if (!o.compareLighting()) stored.output.hdr = Image{};  // written; the metrics read the device's
            continue;
        }
        ScopedStage timedPrepare(Stage::Metrics);
        stored.prepared = std::make_unique<PreparedReference>(stored.output.hdr, exposure(view));
        if (stored.firstFrame)
            stored.firstFrame->prepared =
                std::make_unique<PreparedReference>(stored.firstFrame->output.hdr, exposure(view));
    }
    return references;
}

// The lighting approximations: the reference layout under each mode vs under ground truth.
void CompareSession::compareLightingModes(int view, References& references) {
    const CompareOptions& o = options_;
    const bool firstView = view == 0;
    const std::string viewLabel = o.viewCount > 1 ? " [view " + std::to_string(view) + "]" : "";
    const ReferenceRender& truth = references.at(kGroundTruth);
    for (const auto& mode : o.modeNames) {
        if (mode == kGroundTruth) continue;
        progress_->begin("lighting " + mode + " vs " + kGroundTruth + viewLabel);
        RunReport run = makeRun(referenceLayout_, mode);
        run.layout = std::string(kReferenceLayout) + " (" + mode + " vs " + kGroundTruth + ")";
        ReferenceRender& approx = references.at(mode);
        run.times = PassTimes{approx.output.timings.gbufferMs, approx.output.timings.lightingMs, ctx_->info.name};
        measureRun(run, approx.output, truth, o.outDir, "lighting/" + mode + "/", exposure(view), o.hdrFlip, false,
                   firstView, imageOutput_);
        const std::string nothing = viewNotMeasured(view);
        progress_->end(!nothing.empty() ? "not measured: " + nothing
                                        : "PSNR " + formatPsnr(run.image->psnrToneMapped) + ", FLIP " +
                                              std::to_string(run.image->flipMean).substr(0, 6));
        record(std::move(run), view);
    }
}

// The seed's figure: rows = modes (enum order: ground truth first), columns = the grid's balls.
void CompareSession::addIblFigure(const References& references) {
    const CompareOptions& o = options_;
    const std::vector<FigureBall> balls = findFigureBalls(inputs_.scene, o.width, o.height);
    if (balls.empty()) {
        model_.run.notes.push_back("IBL figure: only for the built-in scene (it crops the sphere grid's balls)");
        return;
    }
    ScopedStage timed(Stage::Report);
    IblFigure figure;
    figure.png = "ibl-figure.png";
    for (const FigureBall& b : balls) figure.columns.push_back(b.label);
    std::vector<Image8> renders;
    std::vector<std::string> captions;
    for (const std::string& name : iblModeNames()) {
        if (!references.count(name)) continue;
        IblFigureRow row;
        row.iblMode = name;
        for (const RunReport& r : model_.runs) {
            if (!r.image) continue;
            if (name == kGroundTruth) {
                if (r.image->metal && r.image->metal->referenceNoise) row.metalNoise = r.image->metal->referenceNoise;
                if (r.image->dielectric && r.image->dielectric->referenceNoise)
                    row.dielectricNoise = r.image->dielectric->referenceNoise;
            } else if (r.iblMode == name) {
                if (r.image->metal) row.metalError = r.image->metal->relLuminanceMean;
                if (r.image->dielectric) row.dielectricError = r.image->dielectric->relLuminanceMean;
            }
        }
        row.caption = iblFigureCaption(row);
        captions.push_back(row.caption);
        renders.push_back(toneMapToSrgb8(references.at(name).output.hdr, exposure(0)));
        figure.rows.push_back(std::move(row));
    }
    imageWriter_->enqueue("the IBL figure",
                          [path = (o.outDir / figure.png).string(),
                           picture = std::make_shared<const Image8>(composeIblFigure(
                               renders, balls, captions,
                               "IBL modes vs ground truth: metals, then dielectrics, roughness 0.05 to 1"))] {
                              writePng(path, *picture);
                          });
    model_.iblFigure = std::move(figure);
}

void CompareSession::runLayouts(int view, const References& references) {
    const CompareOptions& o = options_;
    const bool firstView = view == 0;
    const std::string viewLabel = o.viewCount > 1 ? " [view " + std::to_string(view) + "]" : "";
    // A view with nothing to measure adds no numbers; its layouts are rendered only in view 0,
    // whose images the report shows.
    const std::string nothing = viewNotMeasured(view);
    const bool skipView = !firstView && !nothing.empty();
    for (size_t m = 0; m < o.modes.size(); ++m) {
        const ReferenceRender& ref = references.at(o.modeNames[m]);
        if (bandPlan_.banded() && bandedReferenceMode_ != m && !skipView) {  // the evaluator holds another mode's
            const PassTimings t = renderReferenceInBands(*renderer_, referenceWiring_, settingsFor(o.modes[m], view),
                                                         bandPlan_, *evaluator_, exposure(view), nullptr);
            gpuPassMs_ += t.gbufferMs + t.lightingMs;
            bandedReferenceMode_ = m;
        }
        for (const Layout& layout : layouts_) {
            if (cancelled()) return;  // asked to stop: no run starts after the request
            progress_->begin(layout.name + " / " + o.modeNames[m] + viewLabel);
            if (!firstView && model_.runs.at(runIndex_).status == RunStatus::Failed) {
                progress_->end("skipped: failed in view 0");
                ++runIndex_;
                continue;
            }
            RunReport run = makeRun(layout, o.modeNames[m]);
            if (skipView) {
                progress_->end("skipped: this view is not measured");
                record(std::move(run), view);
                continue;
            }
            try {
                const std::string prefix = "runs/" + layout.name + "/" + o.modeNames[m] + "/";
                const GBufferWiring wiring = generateWiring(layout, wiringOptions_);
                RenderSettings settings = settingsFor(o.modes[m], view);
                // Bandwidth as GPUs pay it: view 0's words under the first mode into the compression
                // model (compare_compression.h) as they are read back.
                std::optional<CompressionCapture> capture;
                if (o.compressionModel && firstView && m == 0) {
                    capture.emplace(layout, o.width, o.height);
                    settings.onTargetWords = capture->callback();
                }
                if (bandPlan_.banded()) {
                    const PassTimings t =
                        measureRunInBands(run, *renderer_, referenceWiring_, wiring, settings,
                                          bandPlan_, *evaluator_, o.outDir, prefix, o.hdrFlip, firstView,
                                          imageOutput_, gpuPassMs_);
                    run.times = PassTimes{t.gbufferMs, t.lightingMs, ctx_->info.name};
                } else if (o.temporalFrames > 1) {
                    // N jittered frames resolved; frame 0 measured alone beside the resolve.
                    TemporalRender t = renderTemporal(*renderer_, wiring, settings, o.temporalFrames, o.resolve);
                    gpuPassMs_ += t.resolved.timings.gbufferMs + t.resolved.timings.lightingMs;
                    const double frames = double(o.temporalFrames);  // the times of one frame: their mean
                    run.times = PassTimes{t.resolved.timings.gbufferMs / frames, t.resolved.timings.lightingMs / frames,
                                          ctx_->info.name};
                    measureSingleFrame(run, t.first, *ref.firstFrame, exposure(view), o.hdrFlip);
                    t.first = RenderOutput{};
                    measureRun(run, t.resolved, ref, o.outDir, prefix, exposure(view), o.hdrFlip, true, firstView,
                               imageOutput_);
                } else {
                    RenderOutput out = renderer_->render(wiring, settings);
                    gpuPassMs_ += out.timings.gbufferMs + out.timings.lightingMs;
                    run.times = PassTimes{out.timings.gbufferMs, out.timings.lightingMs, ctx_->info.name};
                    measureRun(run, out, ref, o.outDir, prefix, exposure(view), o.hdrFlip, true, firstView, imageOutput_);
                }
                if (capture)
                    if (std::optional<FrameCompression> f = capture->finish()) {
                        std::lock_guard lock(modelMutex_);
                        compression_[layout.name] = std::move(*f);
                    }
                if (!nothing.empty())
                    progress_->end("not measured: " + nothing);
                else
                    progress_->end("PSNR " + formatPsnr(run.image->psnrToneMapped) + ", FLIP " +
                                   std::to_string(run.image->flipMean).substr(0, 6) +
                                   (run.singleFrame && run.singleFrame->image
                                        ? " (one frame: " + std::to_string(run.singleFrame->image->flipMean).substr(0, 6) + ")"
                                        : std::string()));
            } catch (const std::exception& e) {
                // One layout that cannot be rendered must not sink the others: report it as failed.
                run.status = RunStatus::Failed;
                run.error = e.what();
                run.image.reset();
                progress_->end("FAILED: " + std::string(e.what()).substr(0, 200));
            }
            record(std::move(run), view);
        }
    }
}

}  // namespace gbl::compare
