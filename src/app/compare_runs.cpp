#include "compare_runs.h"

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>

#include "color_map.h"
#include "env_flag.h"
#include "error_images.h"
#include "host_profile.h"
#include "parallel_invoke.h"
#include "image_io.h"
#include "stage_clock.h"
#include "tone_map.h"
#include "worst_regions.h"

namespace gbl::compare {

namespace fs = std::filesystem;

namespace {

std::optional<AttributeStats> toReport(const ClassStats& c, bool color) {
    if (c.error.count == 0) return std::nullopt;
    AttributeStats s;
    s.error = c.error;
    if (color) s.rmse = c.rmse;
    return s;
}

AttributeErrors toReport(const AttributeMetrics& m, bool color) {
    return {toReport(m.all, color), toReport(m.metal, color), toReport(m.dielectric, color)};
}

}  // namespace

void fillMetrics(RunReport& run, const RunMetrics& m) {
    run.attributes[ErrorAttribute::Normal] = toReport(m.normal, false);
    run.attributes[ErrorAttribute::BaseColor] = toReport(m.baseColor, true);
    run.attributes[ErrorAttribute::DiffuseColor] = toReport(m.diffuseColor, true);
    run.attributes[ErrorAttribute::SpecularColor] = toReport(m.specularColor, true);
    run.attributes[ErrorAttribute::Roughness] = toReport(m.roughness, false);
    run.attributes[ErrorAttribute::Metallic] = toReport(m.metallic, false);
    run.attributes[ErrorAttribute::Occlusion] = toReport(m.occlusion, false);
    run.attributes[ErrorAttribute::Depth] = toReport(m.depth, false);
    if (m.layers) {  // a scene with material layers: each over the pixels carrying it
        for (size_t k = 0; k < kLayerAttributeCount; ++k) {
            const ErrorAttribute a = kLayerErrorAttributes[k];
            run.attributes[a] = toReport(m.layers->byAttribute[k], errorAttributeIsColor(a));
        }
    }
    ImageErrors e;
    e.rmseLinear = m.image.rmseLinear;
    e.psnrLinear = m.image.psnrLinear;
    e.rmseToneMapped = m.image.rmseToneMapped;
    e.psnrToneMapped = m.image.psnrToneMapped;
    e.maxAbs = m.image.maxAbs;
    e.p99Abs = m.image.p99Abs;
    e.flipMean = m.image.flipMean;
    e.flipMedian = m.image.flipMedian;
    e.flipTiles = m.image.flipTiles;
    auto cls = [](const ClassImageErrors& c) -> std::optional<ImageClassErrors> {
        if (c.pixels == 0) return std::nullopt;
        ImageClassErrors k;
        k.pixels = int64_t(c.pixels);
        k.relLuminanceMean = c.relLuminanceMean;
        k.rmseLinear = c.rmseLinear;
        k.flipMean = c.flipMean;
        if (c.referenceNoise >= 0.0) k.referenceNoise = c.referenceNoise;
        return k;
    };
    e.covered = cls(m.image.covered);
    e.metal = cls(m.image.metal);
    e.dielectric = cls(m.image.dielectric);
    if (m.image.layerClasses)
        for (LayerClass c : kLayerClasses) {
            const ClassImageErrors& k = (*m.image.layerClasses)[size_t(c)];
            std::optional<ImageClassErrors>& dst = e.*(layerImageClasses()[size_t(c)].second);
            dst = cls(k);
            if (dst) dst->flipTiles = k.flipTiles;
        }
    if (m.image.hdrFlipComputed) {
        e.hdrFlipMean = m.image.hdrFlipMean;
        e.hdrFlipExposures = m.image.hdrFlipExposures;
    }
    run.image = e;
}


DeviceRender deviceView(const RenderOutput& r) {
    if (!r.device) throw std::logic_error("--eval gpu: the render was not kept on the device");
    DeviceRender d;
    d.hdr = &r.device->hdr;
    if (r.device->surfaces[0].image)
        for (size_t k = 0; k < 4; ++k) d.surfaces[k] = &r.device->surfaces[k];
    if (r.device->layers[0].image)
        for (size_t k = 0; k < 4; ++k) d.layers[k] = &r.device->layers[k];
    return d;
}

namespace {

void setGroundTruth(RunReport& run, const ReferenceRender& reference) {
    if (reference.output.noise.empty()) return;
    const GroundTruthStats& g = reference.output.groundTruth;
    run.groundTruth = GroundTruthConvergence{g.batches, g.samplesPerPixel, g.targetRelativeNoise,
                                             g.meanRelativeNoise, g.targetMet, g.lightingMs};
}

void measureRunGpu(RunReport& run, RenderOutput& test, const ReferenceRender& reference, const fs::path& outDir,
                   const std::string& prefix, float exposure, bool hdrFlip, bool releaseTest, bool writeImages,
                   const ImageOutput& output) {
    GpuEvaluator& evaluator = *reference.evaluator;
    setGroundTruth(run, reference);
    std::optional<ScopedStage> timed(std::in_place, Stage::Metrics);
    evaluator.setReference(deviceView(reference.output), exposure,
                           reference.output.noise.empty() ? nullptr : &reference.output.noise);
    GpuErrorImages images;
    GpuEvalOptions options;
    options.hdrFlip = hdrFlip;
    options.images = writeImages ? &images : nullptr;
    // On a GPU the images stay packed until the writer's job unpacks them (GpuErrorImages::unpack),
    // off the main thread; a CPU device's memory is the process's, so it unpacks (and frees) now.
    // GBL_EVAL_DEFER_IMAGES=1 / 0 forces the choice (compare_bands_cli_test runs the GPU's way
    // on lavapipe).
    options.deferImages =
        output.writer && envChoice("GBL_EVAL_DEFER_IMAGES").value_or(test.device->ctx.info.type != VK_PHYSICAL_DEVICE_TYPE_CPU);
    const int width = int(test.device->hdr.extent.width), height = int(test.device->hdr.extent.height);
    options.cropSize = std::max(32, std::min(width, height) / 12);
    if (releaseTest)  // the test's surfaces go as soon as the attributes are measured (peak memory at 4K)
        options.surfacesDone = [&] {
            for (GpuImage& image : test.device->surfaces) destroyImage(test.device->ctx, image);
            for (GpuImage& image : test.device->layers) destroyImage(test.device->ctx, image);
        };
    const RunMetrics m = evaluator.evaluate(deviceView(test), options);
    fillMetrics(run, m);
    if (!writeImages) return;
    timed.emplace(Stage::Report);
    // The job holds the device images until it has downloaded the HDR one (the surfaces are gone).
    auto download = [device = test.device] {
        HostScope scope("job: HDR download");
        return std::make_shared<const Image>(device->downloadHdr());
    };
    queueDeviceImages(run, std::move(images), m, download, outDir, prefix, output);
}

}  // namespace

std::vector<std::string> failRunsOfWriteFailures(ReportModel& model, const std::vector<WriteFailure>& failures) {
    std::vector<std::string> others;
    for (const WriteFailure& f : failures) {
        bool matched = false;
        for (RunReport& r : model.runs) {
            if (r.status != RunStatus::Ok || r.images.render.rfind(f.what, 0) != 0 || f.what.empty()) continue;
            r.status = RunStatus::Failed;
            r.error = f.message;
            r.image.reset();
            r.images = {};  // named files that do not exist
            matched = true;
        }
        if (!matched) others.push_back(f.line());
    }
    for (const std::string& e : others) model.run.notes.push_back("not written: " + e);
    return others;
}

namespace {
// The run's folder, before its files are written side by side (the EXR writer does not create it).
void makeRunDirectory(const fs::path& outDir, const std::string& prefix) {
    std::error_code ec;
    fs::create_directories((outDir / (prefix + "render.exr")).parent_path(), ec);
}
}  // namespace

// The files of a run measured on the device: the 8-bit images the evaluator made, the HDR render
// (render.exr and its log preview) and the crops.
void queueDeviceImages(RunReport& run, GpuErrorImages&& images, const RunMetrics& m,
                       std::function<std::shared_ptr<const Image>()> hdrSource, const fs::path& outDir,
                       const std::string& prefix, const ImageOutput& output) {
    ErrorImageOptions imageOptions;
    imageOptions.label = run.layout + " / " + run.iblMode;
    imageOptions.exrType = output.exrType;
    // Every path is known before any file is written (the report lists them now); the files are
    // written by output.writer's threads when there is one, as on the CPU path.
    run.images.render = prefix + "render.png";
    run.images.errorHeatmap = prefix + "error_heatmap.png";
    run.images.flip = prefix + "flip.png";
    if (!images.normal.pixels.empty() || (images.packed && images.packed->hasNormal())) run.images.normalError = prefix + "normal_error.png";
    run.images.difference = prefix + "difference.png";
    // The linear HDR render the metrics were computed on (ImageOutput::exrType), and its preview.
    run.images.renderExr = prefix + "render.exr";
    run.images.hdrPreview = prefix + "render_log.png";
    for (size_t i = 0; i < images.worst.size(); ++i) {
        const Crop& c = images.worst[i];
        const CropFiles f = cropFileNames(prefix, i);
        run.images.crops.push_back({c.x, c.y, c.size, c.size, f.reference, f.test, f.heat});
    }
    auto owned = std::make_shared<GpuErrorImages>(std::move(images));
    auto write = [outDir, prefix, owned, m, hdrSource = std::move(hdrSource), imageOptions, exrType = output.exrType] {
        GpuErrorImages& g = *owned;
        makeRunDirectory(outDir, prefix);
        std::shared_ptr<const Image> hdr;
        parallelInvoke({[&] { hdr = hdrSource(); },
                        [&] {
                            if (!g.packed) return;
                            HostScope scope("job: unpack the 8-bit images");
                            g.unpack();
                        }});
        // Every file side by side: one 4K file is one core's work, and on a GPU the run's files
        // are most of its time (compare at 4K: report writing 4.5 s of 7.9 s when they ran one by one).
        parallelInvoke({[&] {
                            writeErrorImageBodies(outDir, prefix,
                                                  ErrorImageBodies{g.render, g.heat, g.flip, g.normal, g.difference},
                                                  m, imageOptions);
                        },
                        [&] { writeExr((outDir / (prefix + "render.exr")).string(), *hdr, {}, exrType); },
                        [&] { writePng((outDir / (prefix + "render_log.png")).string(), logEncodeForPreview(*hdr)); },
                        [&] {
                            if (!g.worst.empty()) writeCrops(outDir, prefix, g.worst, g.reference, g.render, g.heat);
                        }});
    };
    HostScope enqueue("run: queue its files (waits when full)");
    if (output.writer) output.writer->enqueue(prefix, std::move(write));  // named by the run's prefix
    else write();
}

void measureRun(RunReport& run, RenderOutput& test, const ReferenceRender& reference, const fs::path& outDir,
                const std::string& prefix, float exposure, bool hdrFlip, bool releaseTest, bool writeImages,
                const ImageOutput& output) {
    if (reference.evaluator) {
        measureRunGpu(run, test, reference, outDir, prefix, exposure, hdrFlip, releaseTest, writeImages, output);
        if (releaseTest) test.device.reset();  // its images are freed once measured (peak memory at 4K)
        return;
    }
    // The run's maps outlive this call when a writer takes them (the job owns them).
    auto maps = std::make_shared<RunErrorMaps>();
    RunMetricsOptions options;
    options.maps = writeImages ? maps.get() : nullptr;
    options.hdrFlip = hdrFlip;
    options.prepared = reference.prepared.get();
    if (!reference.output.noise.empty()) options.referenceNoise = &reference.output.noise;
    options.excluded = reference.forwardMask.get();
    setGroundTruth(run, reference);
    std::optional<ScopedStage> timed(std::in_place, Stage::Metrics);
    const RunMetrics m =
        releaseTest ? computeRunMetrics(reference.output.surfaces, std::move(test.surfaces), reference.output.hdr,
                                        test.hdr, exposure, options)
                    : computeRunMetrics(reference.output.surfaces, test.surfaces, reference.output.hdr, test.hdr,
                                        exposure, options);
    fillMetrics(run, m);
    if (!writeImages) return;  // views after the first: metrics only
    const int cropSize = std::max(32, std::min(test.hdr.width, test.hdr.height) / 12);
    const std::vector<Crop> crops = findWorstRegions(maps->relLuminance, cropSize, 3);
    timed.emplace(Stage::Report);
    ErrorImageOptions imageOptions;
    imageOptions.label = run.layout + " / " + run.iblMode;
    imageOptions.exrType = output.exrType;
    imageOptions.writeErrorExr = output.errorExr;
    // Every path is known before any file is written: the report lists them now.
    const ErrorImagePaths paths = errorImagePaths(prefix, *maps, output.errorExr);
    run.images.render = paths.render;
    // The linear HDR render the image metrics (and HDR-FLIP) were computed on (ImageOutput::exrType).
    run.images.renderExr = prefix + "render.exr";
    run.images.hdrPreview = prefix + "render_log.png";
    run.images.errorHeatmap = paths.heatmap;
    run.images.flip = paths.flip;
    run.images.normalError = paths.normalError;
    run.images.difference = paths.difference;
    run.images.errorsExr = paths.errorsExr;
    for (size_t i = 0; i < crops.size(); ++i) {
        const CropFiles f = cropFileNames(prefix, i);
        run.images.crops.push_back({crops[i].x, crops[i].y, crops[i].size, crops[i].size, f.reference, f.test, f.heat});
    }
    // The writer's job owns the HDR image (moved when the caller is done with it, else copied);
    // written here, it is only borrowed.
    std::shared_ptr<const Image> hdr;
    if (!output.writer) hdr = std::shared_ptr<const Image>(std::shared_ptr<const Image>(), &test.hdr);
    else hdr = std::make_shared<const Image>(releaseTest ? std::move(test.hdr) : test.hdr);
    auto write = [outDir, prefix, maps, m, hdr, crops, imageOptions, exrType = output.exrType] {
        HostScope scope("job: a run's files (host metrics)");
        makeRunDirectory(outDir, prefix);
        parallelInvoke({[&] { writeErrorImages(outDir, prefix, *maps, m, imageOptions); },
                        [&] { writeExr((outDir / (prefix + "render.exr")).string(), *hdr, {}, exrType); },
                        [&] { writePng((outDir / (prefix + "render_log.png")).string(), logEncodeForPreview(*hdr)); },
                        [&] {
                            if (crops.empty()) return;
                            const Image8 heat = applyColorMap(maps->relLuminance, 0.0f, imageOptions.heatMax);
                            writeCrops(outDir, prefix, crops, srgbFloatTo8(*maps->referenceSrgb),
                                       srgbFloatTo8(maps->testSrgb), heat);
                        }});
    };
    // Named by the run's file prefix: a failure is matched back to its run (failRunsOfWriteFailures).
    HostScope enqueue("run: queue its files (waits when full)");
    if (output.writer) output.writer->enqueue(prefix, std::move(write));
    else write();
}


}  // namespace gbl::compare
