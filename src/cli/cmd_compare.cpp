// `gbufferlab compare`: the product's main job. Renders the float reference and every chosen
// layout (under every chosen IBL mode) at the same camera, measures attribute and image error,
// writes error images, the bandwidth model and report.html / report.json / report.csv.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include <nlohmann/json.hpp>
#include <sstream>

#include "bandwidth.h"
#include "cli_args.h"
#include "color_map.h"
#include "commands.h"
#include "error.h"
#include "error_images.h"
#include "file_io.h"
#include "ibl_cache.h"
#include "ibl_figure.h"
#include "ibl_precompute.h"
#include "image_io.h"
#include "interrupt.h"
#include "layout_catalog.h"
#include "progress.h"
#include "renderer.h"
#include "report_html.h"
#include "report_model.h"
#include "run_metrics.h"
#include "scene_inputs.h"
#include "shader_cache.h"
#include "stage_clock.h"
#include "tone_map.h"
#include "view_stats.h"
#include "vk_context.h"
#include "wiring_codegen.h"
#include "worst_regions.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {

constexpr const char* kReferenceLayout = "reference";
constexpr const char* kGroundTruth = "ground-truth";
// In the output folder while it is incomplete (see runCompareCommand).
constexpr const char* kIncompleteMarker = "INCOMPLETE";
// Exit status when the report was written but some runs failed (1: bad input, 2: usage, 3: bug).
constexpr int kExitRunsFailed = 4;

std::string joinList(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
    return out;
}

// Resolves --layouts: "all" (or no flag) = every file in layouts/ but the reference; otherwise
// names or paths. Every file is parsed and validated here, before any rendering.
std::vector<Layout> resolveLayouts(const std::optional<std::string>& spec) {
    std::vector<std::string> names;
    const std::vector<std::string> known = listLayoutNames();
    const std::vector<std::string> given = spec ? splitFlagList(*spec, "--layouts") : std::vector<std::string>{"all"};
    if (given.size() > 1 && std::find(given.begin(), given.end(), "all") != given.end())
        throwUserError("--layouts " + quoteName(*spec) + ": 'all' already names every layout; give all alone, or names");
    if (given.front() == "all") {
        for (const auto& n : known)
            if (n != kReferenceLayout) names.push_back(n);
    } else {
        names = given;
    }
    std::vector<Layout> layouts;
    for (const std::string& n : names) {
        const bool isPath = n.find('/') != std::string::npos || n.find(".toml") != std::string::npos;
        if (!isPath && std::find(known.begin(), known.end(), n) == known.end())
            throwUserError("--layouts: unknown layout " + quoteName(n) + " (known: " + joinList(known) + ", or all)");
        layouts.push_back(loadLayout(n));
    }
    return layouts;
}

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

void fillMetrics(RunReport& run, const RunMetrics& m) {
    run.attributes[ErrorAttribute::Normal] = toReport(m.normal, false);
    run.attributes[ErrorAttribute::BaseColor] = toReport(m.baseColor, true);
    run.attributes[ErrorAttribute::DiffuseColor] = toReport(m.diffuseColor, true);
    run.attributes[ErrorAttribute::SpecularColor] = toReport(m.specularColor, true);
    run.attributes[ErrorAttribute::Roughness] = toReport(m.roughness, false);
    run.attributes[ErrorAttribute::Metallic] = toReport(m.metallic, false);
    run.attributes[ErrorAttribute::Depth] = toReport(m.depth, false);
    ImageErrors e;
    e.rmseLinear = m.image.rmseLinear;
    e.psnrLinear = m.image.psnrLinear;
    e.rmseToneMapped = m.image.rmseToneMapped;
    e.psnrToneMapped = m.image.psnrToneMapped;
    e.maxAbs = m.image.maxAbs;
    e.p99Abs = m.image.p99Abs;
    e.flipMean = m.image.flipMean;
    e.flipMedian = m.image.flipMedian;
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
    if (m.image.hdrFlipComputed) {
        e.hdrFlipMean = m.image.hdrFlipMean;
        e.hdrFlipExposures = m.image.hdrFlipExposures;
    }
    run.image = e;
}

struct ReferenceRender {
    RenderOutput output;
    std::string renderPng;  // relative to the report dir
    std::unique_ptr<PreparedReference> prepared;  // of output.hdr, shared by the runs measured against it
};

std::string isoDate() {
    const std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return buf;
}

std::string formatPsnr(double db) {
    if (std::isinf(db)) return "inf";
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.1f dB", db);
    return buf;
}

// The comparison of one rendered run against its reference: metrics, images, crops. `test` is
// moved from when `releaseTest` (its surfaces are freed once measured: peak memory at 4K).
void measureRun(RunReport& run, RenderOutput& test, const ReferenceRender& reference, const fs::path& outDir,
                const std::string& prefix, float exposure, bool hdrFlip, bool releaseTest, bool writeImages = true) {
    RunErrorMaps maps;
    RunMetricsOptions options;
    options.maps = writeImages ? &maps : nullptr;
    options.hdrFlip = hdrFlip;
    options.prepared = reference.prepared.get();
    if (!reference.output.noise.empty()) {
        options.referenceNoise = &reference.output.noise;
        const GroundTruthStats& g = reference.output.groundTruth;
        run.groundTruth = GroundTruthConvergence{g.batches, g.samplesPerPixel, g.targetRelativeNoise,
                                                 g.meanRelativeNoise, g.targetMet, g.lightingMs};
    }
    std::optional<ScopedStage> timed(std::in_place, Stage::Metrics);
    const RunMetrics m =
        releaseTest ? computeRunMetrics(reference.output.surfaces, std::move(test.surfaces), reference.output.hdr,
                                        test.hdr, exposure, options)
                    : computeRunMetrics(reference.output.surfaces, test.surfaces, reference.output.hdr, test.hdr,
                                        exposure, options);
    fillMetrics(run, m);
    if (!writeImages) return;  // views after the first: metrics only
    const int cropSize = std::max(32, std::min(test.hdr.width, test.hdr.height) / 12);
    const std::vector<Crop> crops = findWorstRegions(maps.relLuminance, cropSize, 3);
    timed.emplace(Stage::Report);
    ErrorImageOptions imageOptions;
    imageOptions.label = run.layout + " / " + run.iblMode;
    const ErrorImagePaths paths = writeErrorImages(outDir, prefix, maps, m, imageOptions);
    run.images.render = paths.render;
    // The linear HDR render the image metrics (and HDR-FLIP) were computed on, as 32-bit float.
    run.images.renderExr = prefix + "render.exr";
    writeExr((outDir / run.images.renderExr).string(), test.hdr);
    run.images.hdrPreview = prefix + "render_log.png";
    writePng((outDir / run.images.hdrPreview).string(), logEncodeForPreview(test.hdr));
    run.images.errorHeatmap = paths.heatmap;
    run.images.flip = paths.flip;
    run.images.normalError = paths.normalError;
    run.images.difference = paths.difference;
    run.images.errorsExr = paths.errorsExr;
    if (!crops.empty()) {
        const Image8 heat = applyColorMap(maps.relLuminance, 0.0f, imageOptions.heatMax);
        const auto files = writeCrops(outDir, prefix, crops, srgbFloatTo8(*maps.referenceSrgb),
                                      srgbFloatTo8(maps.testSrgb), heat);
        for (size_t i = 0; i < crops.size(); ++i)
            run.images.crops.push_back({crops[i].x, crops[i].y, crops[i].size, crops[i].size, files[i].reference,
                                        files[i].test, files[i].heat});
    }
}

// compare --views: the cameras. View 0 is the scene's camera; then orbit views about the scene's
// centre (the point the scene camera looks at; for a camera read from a glTF file, whose target is
// only a direction, the centre of the scene's bounds) at the scene camera's distance from it, 35
// degrees above the horizontal,
// azimuths +40, +160, +280, ... degrees from the scene camera's; with 3 or more views the last is a
// grazing view of the ground: 6 degrees above the plane through the bounds' lowest point, at the
// same distance, azimuth -30 degrees, looking at the centre's foot on that plane. Same field of
// view, near and far planes as the scene camera. Up is the scene camera's up.
struct CompareView {
    Camera camera;
    std::string description;
};

std::vector<CompareView> compareViews(const Scene& scene, int count) {
    std::vector<CompareView> views;
    const Camera& base = scene.camera;
    views.push_back({base, "scene camera"});
    if (count <= 1) return views;
    const glm::vec3 up = glm::normalize(base.up);
    const glm::vec3 centre = base.fromFile ? 0.5f * (scene.bounds.min + scene.bounds.max) : base.target;
    float distance = glm::length(base.position - centre);
    if (!(distance > 0.0f) || !std::isfinite(distance)) distance = 1.0f;
    // The scene camera's horizontal direction from the centre (any horizontal one when it looks straight down).
    glm::vec3 from = base.position - centre;
    from -= up * glm::dot(from, up);
    if (glm::length(from) < 1e-6f * distance) from = std::abs(up.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
    from = glm::normalize(from - up * glm::dot(from, up));
    auto place = [&](float azimuthDeg, float elevationDeg, glm::vec3 target) {
        const glm::vec3 h = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(azimuthDeg), up) * glm::vec4(from, 0.0f));
        const float e = glm::radians(elevationDeg);
        Camera c = base;
        c.position = target + distance * (std::cos(e) * h + std::sin(e) * up);
        c.target = target;
        c.up = up;
        c.fromFile = false;
        return c;
    };
    const bool grazing = count >= 3;
    const int orbits = count - 1 - (grazing ? 1 : 0);
    char buf[160];
    for (int k = 0; k < orbits; ++k) {
        const float azimuth = 40.0f + 120.0f * float(k);
        std::snprintf(buf, sizeof(buf), "orbit about the scene's centre: azimuth %+.0f deg, elevation 35 deg",
                      double(azimuth));
        views.push_back({place(azimuth, 35.0f, centre), buf});
    }
    if (grazing) {
        // The ground: the plane through the bounds' lowest point along up.
        const glm::vec3 corners[2] = {scene.bounds.min, scene.bounds.max};
        float low = std::numeric_limits<float>::max();
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 p(corners[i & 1].x, corners[(i >> 1) & 1].y, corners[(i >> 2) & 1].z);
            low = std::min(low, glm::dot(p, up));
        }
        const glm::vec3 foot = centre - up * (glm::dot(centre, up) - low);
        views.push_back({place(-30.0f, 6.0f, foot), "grazing view of the ground: 6 deg above it, azimuth -30 deg"});
    }
    return views;
}

// After the last view: a run's metrics become the mean over its views; one view: as before.
void finishViews(RunReport& run) {
    if (run.views.size() > 1) averageViews(run);
    else run.views.clear();
}

// The material balls of the built-in scene's sphere grid (materials "metal roughness ..." and
// "dielectric roughness ..."), as square crops of a width x height render: metals, then
// dielectrics, each left to right. Empty for other scenes.
std::vector<FigureBall> findFigureBalls(const Scene& scene, uint32_t width, uint32_t height) {
    std::vector<std::pair<float, FigureBall>> metals, dielectrics;
    const CameraMatrices cam = computeCameraMatrices(scene.camera, float(width) / float(height), false);
    for (const Draw& d : scene.draws) {
        if (d.material < 0 || size_t(d.material) >= scene.materials.size()) continue;
        const std::string& name = scene.materials[size_t(d.material)].name;
        const bool metal = name.rfind("metal roughness", 0) == 0;
        if (!metal && name.rfind("dielectric roughness", 0) != 0) continue;
        const glm::vec3 centre(d.model[3]);
        float radius = 0.0f;
        for (uint32_t k = 0; k < d.indexCount; ++k) {
            const Vertex& v = scene.vertices[size_t(d.vertexOffset) + scene.indices[d.firstIndex + k]];
            radius = std::max(radius, glm::length(glm::vec3(d.model * glm::vec4(v.position, 1.0f)) - centre));
        }
        const glm::vec4 clip = cam.viewProj * glm::vec4(centre, 1.0f);
        if (clip.w <= 0.0f) continue;
        const float px = (clip.x / clip.w * 0.5f + 0.5f) * float(width);
        const float py = (clip.y / clip.w * 0.5f + 0.5f) * float(height);
        const float dist = glm::length(centre - scene.camera.position);
        const float rpx = radius / (dist * std::tan(scene.camera.yFovRadians * 0.5f)) * 0.5f * float(height);
        FigureBall b;
        b.size = std::max(4, int(std::ceil(2.2f * rpx)));
        b.x = int(std::floor(px - 0.5f * float(b.size)));
        b.y = int(std::floor(py - 0.5f * float(b.size)));
        // The ball's pixels: the camera ray through each crop pixel's centre hits the sphere.
        // radius is the farthest vertex; the tessellated silhouette lies up to ~1.5% inside it.
        const float inscribed = 0.985f * radius;
        const glm::mat4 inverseViewProj = glm::inverse(cam.viewProj);
        b.mask.assign(size_t(b.size) * size_t(b.size), 0);
        for (int my = 0; my < b.size; ++my)
            for (int mx = 0; mx < b.size; ++mx) {
                const float nx = (float(b.x + mx) + 0.5f) / float(width) * 2.0f - 1.0f;
                const float ny = (float(b.y + my) + 0.5f) / float(height) * 2.0f - 1.0f;
                const glm::vec4 a = inverseViewProj * glm::vec4(nx, ny, 0.0f, 1.0f);
                const glm::vec4 e = inverseViewProj * glm::vec4(nx, ny, 1.0f, 1.0f);
                const glm::vec3 origin = glm::vec3(a) / a.w;
                const glm::vec3 dir = glm::normalize(glm::vec3(e) / e.w - origin);
                const glm::vec3 oc = centre - origin;
                const float along = glm::dot(oc, dir);
                b.mask[size_t(my) * size_t(b.size) + size_t(mx)] =
                    along > 0.0f && glm::dot(oc, oc) - along * along <= inscribed * inscribed ? 1 : 0;
            }
        b.metal = metal;
        const float r = scene.materials[size_t(d.material)].roughnessFactor;
        char label[48];
        std::snprintf(label, sizeof(label), "%s r=%.2f", metal ? "metal" : "dielectric", double(r));
        b.label = label;
        (metal ? metals : dielectrics).push_back({centre.x, b});
    }
    std::vector<FigureBall> balls;
    for (auto* group : {&metals, &dielectrics}) {
        std::sort(group->begin(), group->end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        for (const auto& [x, b] : *group) balls.push_back(b);
    }
    return balls;
}

void printTable(const ReportModel& model) {
    // The layout column is as wide as its longest name ("reference (split-sum-shader vs ground-truth)").
    int w = 20;
    for (const RunReport& r : model.runs) w = std::max(w, int(r.layout.size()));
    const size_t views = model.run.views.size();
    if (views > 1)
        std::printf("\nEvery metric is the mean over %d views; the row under each run gives its spread over them:\n"
                    "± standard deviation, PSNR as min..max dB.",
                    int(views));
    std::printf("\n%-*s %-16s %6s %9s %9s %9s %10s %8s\n", w, "layout", "ibl", "B/px", "GB/s@1080", "normal°",
                "albedoΔE", "PSNR(tm)", "FLIP");
    for (const RunReport& r : model.runs) {
        if (r.status == RunStatus::Failed) {
            std::printf("%-*s %-16s FAILED: %s\n", w, r.layout.c_str(), r.iblMode.c_str(), r.error.c_str());
            continue;
        }
        const auto& n = r.attributes[ErrorAttribute::Normal].all;
        const auto& a = r.attributes[ErrorAttribute::DiffuseColor].all;
        std::printf("%-*s %-16s %6d %9.2f %9.3f %9.3f %10s %8.4f\n", w, r.layout.c_str(), r.iblMode.c_str(),
                    r.bytesPerPixel.total, r.gigabytesPerSecond1080p60().value_or(0.0), n ? n->error.mean : 0.0,
                    a ? a->error.mean : 0.0, formatPsnr(r.image ? r.image->psnrToneMapped : 0.0).c_str(),
                    r.image ? r.image->flipMean : 0.0);
        if (views > 1 && r.views.size() > 1) {
            auto attr = [](ErrorAttribute which) {
                return [which](const RunReport& v) -> std::optional<double> {
                    const auto& s = v.attributes[which].all;
                    if (!s) return std::nullopt;
                    return s->error.mean;
                };
            };
            const ViewSpread ns = viewSpread(r, attr(ErrorAttribute::Normal));
            const ViewSpread as = viewSpread(r, attr(ErrorAttribute::DiffuseColor));
            const ViewSpread p = viewSpread(r, [](const RunReport& v) -> std::optional<double> {
                if (!v.image) return std::nullopt;
                return v.image->psnrToneMapped;
            });
            const ViewSpread f = viewSpread(r, [](const RunReport& v) -> std::optional<double> {
                if (!v.image) return std::nullopt;
                return v.image->flipMean;
            });
            char psnr[32];
            std::snprintf(psnr, sizeof(psnr), "%.1f..%.1f", p.min, p.max);
            std::printf("%-*s %-16s %6s %9s   ±%6.3f   ±%6.3f %10s  ±%6.4f\n", w, "", "  spread", "", "", ns.stddev,
                        as.stddev, psnr, f.stddev);
        }
    }
}

// Where the time went, stage by stage (stage_clock.h), against the GPU passes' own time (the
// timestamp queries of every frame rendered): printed, and written as timings.json for bench/.
void reportStageTimes(const fs::path& outDir, const StageTimes& t, double gpuPassMs) {
    nlohmann::ordered_json j;
    j["schema"] = "gbufferlab-timings";
    j["schema_version"] = 1;
    nlohmann::ordered_json stages;
    std::printf("\ntime by stage (wall):");
    for (size_t s = 0; s < kStageCount; ++s) {
        stages[stageName(Stage(s))] = t.ms[s];
        std::printf("%s %s %.2f s", s ? "," : "", stageName(Stage(s)), t.ms[s] / 1000.0);
    }
    j["stages_ms"] = stages;
    // What "shader compile" paid for: glslang runs and driver pipeline compiles, or cache hits
    // (src/gpu/shader_cache.h). A second run on the same machine shows 0 glslang compiles.
    const ShaderCacheCounters& c = shaderCacheCounters();
    nlohmann::ordered_json cache;
    cache["enabled"] = shaderCacheEnabled();
    cache["glslang_compiles"] = c.glslangCompiles.load();
    cache["spirv_cache_hits"] = c.spirvCacheHits.load();
    cache["spirv_cache_invalid"] = c.spirvCacheInvalid.load();
    cache["pipelines"] = c.pipelines.load();
    cache["pipeline_cache_hits"] = c.pipelineCacheHits.load();
    j["shader_cache"] = cache;
    std::printf("\nshaders: %d compiled by glslang, %d from the SPIR-V cache%s; pipelines: %d created, %d found in "
                "the pipeline cache (driver's report)",
                c.glslangCompiles.load(), c.spirvCacheHits.load(),
                c.spirvCacheInvalid.load() ? (", " + std::to_string(c.spirvCacheInvalid.load()) +
                                              " invalid cache files ignored").c_str()
                                           : "",
                c.pipelines.load(), c.pipelineCacheHits.load());
    j["total_ms"] = t.totalMs;
    j["gpu_pass_ms"] = gpuPassMs;
    j["total_over_gpu_passes"] = gpuPassMs > 0.0 ? t.totalMs / gpuPassMs : 0.0;
    std::printf("\ntotal %.2f s = %.2fx the GPU passes' own %.2f s (timestamps)\n", t.totalMs / 1000.0,
                gpuPassMs > 0.0 ? t.totalMs / gpuPassMs : 0.0, gpuPassMs / 1000.0);
    writeFileAtomic(outDir / "timings.json", j.dump(2) + "\n");
}

}  // namespace

int runCompareCommand(const std::vector<std::string>& args) {
    const std::vector<FlagSpec> specs = {
        {"scene", "FILE", "glTF 2.0 scene (.gltf/.glb); default: the built-in scene (the sphere grid and its surroundings)"},
        {"env", "FILE", "equirectangular environment (.hdr/.exr); default: the built-in sky"},
        {"allow-outside-scene", "", "let the scene's buffer and image URIs point outside its folder"},
        {"layouts", "A,B,...", "layouts to compare (names in layouts/ or .toml paths), or all (default)"},
        {"ibl", "MODES", "specular IBL modes, comma-separated (default split-sum; known: " +
                             joinList(iblModeNames()) + ")"},
        {"samples", "N", "samples per pixel of the split-sum-shader IBL mode (default 1024)"},
        {"gt-noise", "X", "ground truth: add batches until the mean relative noise (standard error of the "
                          "luminance / luminance) over covered pixels is at most X (default 0.002)"},
        {"gt-batch-samples", "N", "ground truth: steps per batch, each one GGX + one environment sample (default 64)"},
        {"gt-max-batches", "N", "ground truth: stop after N batches even if the noise target is not met (default 256)"},
        {"brdf-lut", "VARIANT", "split-sum BRDF LUT: converged (visible-normal sampling, 4096 samples; default) or "
                                "seed (the seed's IntegrateBRDF, 1024 samples)"},
        {"size", "WxH", "image size (default 1920x1080)"},
        {"views", "N", "cameras measured (default 3: the scene camera, an orbit about the scene's centre, a grazing "
                       "view of the ground; more add orbit views); every metric is the mean over them with its "
                       "spread; per-pixel images are the first view's"},
        {"out", "DIR", "output directory, new or empty (default: out/compare-<time>)"},
        {"force", "", "write into a non-empty --out directory, replacing files of the same name"},
        {"device", "NAME", "cpu (lavapipe, default), gpu, an index or a name from `gbufferlab devices`"},
        {"exposure", "X", "exposure for tone-mapped images and their metrics (default 1)"},
        {"native-formats", "", "render targets in their real UNORM/SRGB/float formats where the layout allows"},
        {"hdr-flip", "", "also compute HDR-FLIP over the linear images (costs one FLIP per exposure: 14 on the "
                         "built-in sky)"},
        {"no-hdr-flip", "", "skip HDR-FLIP (the default; kept for older scripts)"},
        {"validation", "", "enable Vulkan validation layers"},
        {"help", "", "show this help"},
    };
    const ParsedArgs parsed = parseArgs("compare", args, specs);
    if (parsed.has("help")) {
        std::printf("%s", formatHelp("gbufferlab compare [--scene F] [--env F] [--layouts A,B,...|all] [--ibl MODES] "
                                     "[--size WxH] [--out DIR]",
                                     "Renders the float reference and each layout at the same camera, and reports "
                                     "what each loses\n(attribute and image error, FLIP, error images) and costs "
                                     "(bytes per pixel, bandwidth).\nWith --ibl listing several modes and "
                                     "ground-truth among them, the reference under each mode is also\ncompared with "
                                     "the reference under ground-truth: the error of the lighting approximation.",
                                     specs)
                               .c_str());
        return 0;
    }
    if (!parsed.positional.empty())
        throwUserError("gbufferlab compare: unexpected argument '" + parsed.positional[0] + "' (see --help)");
    StageClock::global().start();
    std::optional<ScopedStage> timedSetup(std::in_place, Stage::Setup);
    const auto [width, height] = parseSize(parsed.get("size", "1920x1080"), "--size");
    const float exposure = parsePositiveFloatFlag(parsed, "exposure", 1.0f);
    const int viewCount = parseIntFlag(parsed, "views", 3, 1, 16);
    std::vector<IblMode> modes;
    std::vector<std::string> modeNames = splitFlagList(parsed.get("ibl", "split-sum"), "--ibl");
    for (const auto& n : modeNames) modes.push_back(parseIblMode(n));
    const int splitSumShaderSamples = parseIntFlag(parsed, "samples", 1024, 1, 65536);
    const int gtBatchSamples = parseIntFlag(parsed, "gt-batch-samples", 64, 1, 65536);
    const int gtMaxBatches = parseIntFlag(parsed, "gt-max-batches", 256, 8, 65536);
    const double gtNoise = parsePositiveFloatFlag(parsed, "gt-noise", 0.002f);
    IblSettings iblSettings;
    if (parsed.has("brdf-lut")) applyBrdfLutVariant(parsed.get("brdf-lut"), iblSettings);
    const fs::path outDir = parsed.has("out") ? fs::path(parsed.get("out")) : defaultOutputDirectory("compare");
    const bool force = parsed.has("force");
    if (parsed.has("hdr-flip") && parsed.has("no-hdr-flip"))
        throwUserError("gbufferlab compare: --hdr-flip and --no-hdr-flip contradict each other; give one");
    const bool hdrFlip = parsed.has("hdr-flip");
    checkOutputDirectory(outDir, force, "--out");

    // Everything the user gave is read and validated before the first pixel is rendered.
    const std::vector<Layout> layouts =
        resolveLayouts(parsed.has("layouts") ? std::optional<std::string>(parsed.get("layouts")) : std::nullopt);
    const Layout referenceLayout = loadLayout(kReferenceLayout);
    const SceneInputs inputs = loadSceneInputs(parsed.get("scene"), parsed.get("env"), float(width) / float(height),
                                                GltfLoadOptions{parsed.has("allow-outside-scene")});

    VulkanContext ctx(DeviceOptions{parsed.get("device"), parsed.has("validation")});
    validateResolution(ctx, width, height, "--size");
    WiringOptions wiringOptions;
    wiringOptions.nativeFormats = parsed.has("native-formats");

    ReportModel model;
    model.run.scene = inputs.scene.source;
    model.run.environment = inputs.environment.source;
    model.run.width = int(width);
    model.run.height = int(height);
    model.run.device = {ctx.info.name, ctx.info.driver, ctx.info.typeName};
    model.run.date = isoDate();
    model.run.commandLine = "gbufferlab compare";
    for (const auto& a : args) model.run.commandLine += " " + a;
    model.run.iblModes = modeNames;
    model.run.exposure = exposure;
    model.reference.layout = kReferenceLayout;
    model.run.notes.push_back("split-sum BRDF LUT: " + brdfLutVariantName(iblSettings) + " (--brdf-lut)");

    const bool compareLighting = modes.size() > 1 &&
                                 std::find(modeNames.begin(), modeNames.end(), kGroundTruth) != modeNames.end();
    const std::vector<CompareView> views = compareViews(inputs.scene, viewCount);
    for (const CompareView& v : views) model.run.views.push_back(v.description);
    if (viewCount > 1)
        model.run.notes.push_back("every metric is the mean over " + std::to_string(viewCount) +
                                  " views (--views); images and crops are the first view's (the scene camera)");
    const int steps =
        viewCount * (int(modes.size()) * (1 + int(layouts.size())) + (compareLighting ? int(modes.size()) - 1 : 0));
    Progress progress(steps, stderr);
    prepareOutputDirectory(outDir, force, "--out");
    // Until the report is complete the folder says so: an interruption (SIGINT, SIGTERM) writes
    // the report of the runs that finished and leaves this file, naming the signal; a kill -9
    // leaves it as written here. The finished report removes it.
    const fs::path incompleteMarker = outDir / kIncompleteMarker;
    writeFileAtomic(incompleteMarker, "gbufferlab compare started " + model.run.date +
                                          " and has not finished: this folder is incomplete\n");
    std::mutex modelMutex;  // model.runs, shared with the interrupt action
    bool reportComplete = false;
    setInterruptAction([&](int signal) {
        std::lock_guard lock(modelMutex);
        if (reportComplete) return;
        ReportModel partial = model;
        for (RunReport& r : partial.runs) finishViews(r);
        const std::string what = std::string("INCOMPLETE: interrupted by ") + signalName(signal) + " after " +
                                 std::to_string(partial.runs.size()) + " of " + std::to_string(steps - int(modes.size())) +
                                 " runs; this report lists only the runs that finished";
        partial.run.notes.push_back(what);
        writeReport(outDir, partial);
        writeFileAtomic(incompleteMarker, what + "\n");
    });
    timedSetup.reset();
    double gpuPassMs = 0.0;  // timestamps of every frame rendered

    Renderer renderer(ctx, inputs.scene, inputs.environment, loadOrComputeIbl(ctx, inputs.environment, iblSettings));
    const GBufferWiring referenceWiring = generateWiring(referenceLayout, {});
    // Every run renders the same way but for the IBL mode, and decodes its G-buffer for metrics.
    auto settingsFor = [&](IblMode mode, int view) {
        RenderSettings settings;
        settings.camera = views[size_t(view)].camera;
        settings.width = width;
        settings.height = height;
        settings.specularIbl = mode;
        settings.groundTruthSamples = gtBatchSamples;
        settings.splitSumShaderSamples = splitSumShaderSamples;
        settings.groundTruthNoiseTarget = gtNoise;
        settings.groundTruthMaxBatches = gtMaxBatches;
        settings.decodeSurfaces = true;
        settings.readTargetWords = false;
        return settings;
    };
    // compare --views: every view renders the references and every run again; the runs of views
    // after the first add their metrics to the first view's run (RunReport::views), in the same order.
    for (int view = 0; view < viewCount; ++view) {
        const bool firstView = view == 0;
        const std::string viewLabel = viewCount > 1 ? " [view " + std::to_string(view) + "]" : "";
        size_t runIndex = 0;
        auto record = [&](RunReport&& run) {
            std::lock_guard lock(modelMutex);
            if (firstView) {
                    if (run.status == RunStatus::Ok) run.views.push_back({run.attributes, run.image});
                    model.runs.push_back(std::move(run));
                } else {
                    RunReport& first = model.runs.at(runIndex);
                    if (first.status == RunStatus::Ok) {
                        if (run.status == RunStatus::Ok) {
                            first.views.push_back({run.attributes, run.image});
                        } else {
                            first.status = RunStatus::Failed;
                            first.error = "view " + std::to_string(view) + ": " + run.error;
                        }
                    }
            }
            ++runIndex;
        };
        std::map<std::string, ReferenceRender> references;
        for (size_t m = 0; m < modes.size(); ++m) {
            progress.begin("reference / " + modeNames[m] + viewLabel);
            ReferenceRender ref;
            ref.output = renderer.render(referenceWiring, settingsFor(modes[m], view));
            gpuPassMs += ref.output.timings.gbufferMs + ref.output.timings.lightingMs;
            if (firstView) {
            ref.renderPng = "reference-" + modeNames[m] + ".png";
            const std::string renderExr = "reference-" + modeNames[m] + ".exr";
            ScopedStage timed(Stage::Report);
            writePng((outDir / ref.renderPng).string(), toneMapToSrgb8(ref.output.hdr, exposure));
            writeExr((outDir / renderExr).string(), ref.output.hdr);
            const std::string preview = "reference-" + modeNames[m] + "-log.png";
            writePng((outDir / preview).string(), logEncodeForPreview(ref.output.hdr));
            model.reference.images.push_back({modeNames[m], ref.renderPng, renderExr, preview});
            }
            std::string gtNote;
            if (modes[m] == IblMode::GroundTruth) {
                const GroundTruthStats& g = ref.output.groundTruth;
                char buf[256];
                std::snprintf(buf, sizeof(buf),
                              "ground truth: %d batches x %d steps (%d samples per pixel, GGX + environment by MIS), mean "
                              "relative noise %.5f (target %.5f%s), lighting %.0f ms GPU on %s",
                              g.batches, gtBatchSamples, g.samplesPerPixel, g.meanRelativeNoise, g.targetRelativeNoise,
                              g.targetMet ? ", met" : ", NOT met", g.lightingMs, ctx.info.name.c_str());
                gtNote = buf;
                std::lock_guard lock(modelMutex);
                model.run.notes.push_back(gtNote + viewLabel);
            }
            progress.end("G-buffer " + std::to_string(int(ref.output.timings.gbufferMs)) + " ms, lighting " +
                         std::to_string(int(ref.output.timings.lightingMs)) + " ms" +
                         (gtNote.empty() ? "" : ", " + std::to_string(ref.output.groundTruth.batches) + " batches"));
            ReferenceRender& stored = references[modeNames[m]] = std::move(ref);
            ScopedStage timedPrepare(Stage::Metrics);
            stored.prepared = std::make_unique<PreparedReference>(stored.output.hdr, exposure);
        }

        auto makeRun = [&](const Layout& layout, const std::string& mode) {
            RunReport run;
            run.layout = layout.name;
            run.title = layout.title;
            run.source = layout.source.text();
            run.pipeline = pipelineName(layout.pipeline);
            run.iblMode = mode;
            const BandwidthReport bw = computeBandwidth(layout, width, height);
            run.bytesPerPixel = bytesPerPixelOf(bw);
            run.bandwidth = bw.frames;
            return run;
        };

        // The lighting approximations: the reference layout under each mode vs under ground truth.
        if (compareLighting) {
            const ReferenceRender& truth = references.at(kGroundTruth);
            for (const auto& mode : modeNames) {
                if (mode == kGroundTruth) continue;
                progress.begin("lighting " + mode + " vs " + kGroundTruth + viewLabel);
                RunReport run = makeRun(referenceLayout, mode);
                run.layout = std::string(kReferenceLayout) + " (" + mode + " vs " + kGroundTruth + ")";
                ReferenceRender& approx = references.at(mode);
                run.times = PassTimes{approx.output.timings.gbufferMs, approx.output.timings.lightingMs, ctx.info.name};
                measureRun(run, approx.output, truth, outDir, "lighting/" + mode + "/", exposure, hdrFlip, false, firstView);
                progress.end("PSNR " + formatPsnr(run.image->psnrToneMapped) + ", FLIP " +
                             std::to_string(run.image->flipMean).substr(0, 6));
                record(std::move(run));
            }
        }

        // The seed's figure: rows = modes (enum order: ground truth first), columns = the grid's balls.
        if (compareLighting && firstView) {
            const std::vector<FigureBall> balls = findFigureBalls(inputs.scene, width, height);
            if (balls.empty()) {
                model.run.notes.push_back("IBL figure: only for the built-in scene (it crops the sphere grid's balls)");
            } else {
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
                    for (const RunReport& r : model.runs) {
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
                    renders.push_back(toneMapToSrgb8(references.at(name).output.hdr, exposure));
                    figure.rows.push_back(std::move(row));
                }
                writePng((outDir / figure.png).string(),
                         composeIblFigure(renders, balls, captions, "IBL modes vs ground truth: metals, then dielectrics, "
                                                                    "roughness 0.05 to 1"));
                model.iblFigure = std::move(figure);
            }
        }

        for (size_t m = 0; m < modes.size(); ++m) {
            const ReferenceRender& ref = references.at(modeNames[m]);
            for (const Layout& layout : layouts) {
                progress.begin(layout.name + " / " + modeNames[m] + viewLabel);
                if (!firstView && model.runs.at(runIndex).status == RunStatus::Failed) {
                    progress.end("skipped: failed in view 0");
                    ++runIndex;
                    continue;
                }
                RunReport run = makeRun(layout, modeNames[m]);
                try {
                    RenderOutput out = renderer.render(generateWiring(layout, wiringOptions), settingsFor(modes[m], view));
                    gpuPassMs += out.timings.gbufferMs + out.timings.lightingMs;
                    run.times = PassTimes{out.timings.gbufferMs, out.timings.lightingMs, ctx.info.name};
                    measureRun(run, out, ref, outDir, "runs/" + layout.name + "/" + modeNames[m] + "/", exposure, hdrFlip, true,
                               firstView);
                    progress.end("PSNR " + formatPsnr(run.image->psnrToneMapped) + ", FLIP " +
                                 std::to_string(run.image->flipMean).substr(0, 6));
                } catch (const std::exception& e) {
                    // One layout that cannot be rendered must not sink the others: report it as failed.
                    run.status = RunStatus::Failed;
                    run.error = e.what();
                    run.image.reset();
                    progress.end("FAILED: " + std::string(e.what()).substr(0, 200));
                }
                record(std::move(run));
            }
        }
    }  // views
    {
        std::lock_guard lock(modelMutex);
        for (RunReport& r : model.runs) finishViews(r);
    }

    {
        ScopedStage timed(Stage::Report);
        std::lock_guard lock(modelMutex);
        writeReport(outDir, model);
        printTable(model);
        reportStageTimes(outDir, StageClock::global().read(), gpuPassMs);
        std::error_code ec;
        fs::remove(incompleteMarker, ec);
        reportComplete = true;
    }
    setInterruptAction({});
    std::printf("report: %s\n", (outDir / "report.html").string().c_str());
    // The report lists what failed and why; the exit status says that something did, so that
    // scripts and CI notice (2 runs failed of 7: exit 4).
    const auto failed = std::count_if(model.runs.begin(), model.runs.end(),
                                      [](const RunReport& r) { return r.status == RunStatus::Failed; });
    if (failed > 0) {
        std::fprintf(stderr, "gbufferlab: error: %d of %d runs failed (see the FAILED rows above and in %s)\n",
                     int(failed), int(model.runs.size()), escapeText((outDir / "report.html").string()).c_str());
        return kExitRunsFailed;
    }
    return 0;
}

}  // namespace gbl
