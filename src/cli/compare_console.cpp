#include "compare_console.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "budget_verdict.h"
#include "file_io.h"
#include "shader_cache.h"
#include "view_stats.h"
#include "visibility_verdict.h"
#include "warm_up_times.h"

namespace gbl::compare {

namespace fs = std::filesystem;

std::string formatPsnr(double db) {
    if (std::isinf(db)) return "inf";
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.1f dB", db);
    return buf;
}

void printTable(const ReportModel& model) {
    // The layout column is as wide as its longest name ("reference (split-sum-shader vs ground-truth)").
    int w = 20;
    for (const RunReport& r : model.runs) w = std::max(w, int(r.layout.size()));
    const size_t views = model.run.views.size();
    size_t measured = 0;  // a view with nothing to measure is in no mean
    for (size_t i = 0; i < views; ++i)
        measured += i >= model.run.viewNotMeasured.size() || model.run.viewNotMeasured[i].empty();
    if (views > 1)
        std::printf("\nEvery metric is the mean over %d %s; the row under each run gives its spread over them:\n"
                    "± standard deviation, PSNR as min..max dB.",
                    int(measured), measured == views ? "views" : ("of the " + std::to_string(views) + " views").c_str());
    // compare --temporal N: the resolved errors, then the first frame's alone (1f) beside them.
    const bool temporal = model.run.temporalFrames > 1;
    if (temporal)
        std::printf("\n--temporal %d: normal°, albedoΔE, PSNR and FLIP are the resolved images' (%s of %d jittered "
                    "frames; attributes: their temporal mean); \"1f\" columns: frame 0 alone.",
                    model.run.temporalFrames, model.run.temporalResolve.c_str(), model.run.temporalFrames);
    std::printf("\n%-*s %-16s %6s %9s %9s %9s %10s %8s %6s", w, "layout", "ibl", "B/px", "GB/s@1080", "normal°",
                "albedoΔE", "PSNR(tm)", "FLIP", "rank");
    if (temporal) std::printf(" %9s %10s %8s", "normal°1f", "PSNR 1f", "FLIP 1f");
    std::printf("\n");
    for (const RunReport& r : model.runs) {
        if (r.status == RunStatus::Failed) {
            std::printf("%-*s %-16s FAILED: %s\n", w, r.layout.c_str(), r.iblMode.c_str(), r.error.c_str());
            continue;
        }
        if (r.status == RunStatus::NotMeasured) {  // no view had anything to measure: no numbers
            std::printf("%-*s %-16s %6d NOT MEASURED (no view had anything to measure)\n", w, r.layout.c_str(),
                        r.iblMode.c_str(), r.bytesPerPixel.total);
            continue;
        }
        const auto& n = r.attributes[ErrorAttribute::Normal].all;
        const auto& a = r.attributes[ErrorAttribute::DiffuseColor].all;
        const RankRange* rank = model.significance ? model.significance->find(r.layout, r.iblMode) : nullptr;
        std::printf("%-*s %-16s %6d %9.2f %9.3f %9.3f %10s %8.4f %6s", w, r.layout.c_str(), r.iblMode.c_str(),
                    r.bytesPerPixel.total, r.gigabytesPerSecond1080p60().value_or(0.0), n ? n->error.mean : 0.0,
                    a ? a->error.mean : 0.0, formatPsnr(r.image ? r.image->psnrToneMapped : 0.0).c_str(),
                    r.image ? r.image->flipMean : 0.0, rank ? rank->text().c_str() : "");
        if (temporal && r.singleFrame) {
            const auto& n1 = r.singleFrame->attributes[ErrorAttribute::Normal].all;
            const auto& i1 = r.singleFrame->image;
            std::printf(" %9.3f %10s %8.4f", n1 ? n1->error.mean : 0.0,
                        formatPsnr(i1 ? i1->psnrToneMapped : 0.0).c_str(), i1 ? i1->flipMean : 0.0);
        }
        std::printf("\n");
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
    for (size_t v = 0; v < model.run.viewNotMeasured.size(); ++v)
        if (!model.run.viewNotMeasured[v].empty())
            std::printf("view %d not measured: %s; it is left out of every mean, rank and verdict\n", int(v),
                        model.run.viewNotMeasured[v].c_str());
    if (model.significance && !model.significance->ranks.empty())
        std::printf("rank: by mean FLIP; a range (4-6) where the differences are not significant (%s)\n",
                    model.significance->method.c_str());
    if (const auto v = gbufferOrVisibility(model)) std::printf("\nG-buffer or visibility buffer? %s\n", v->answer.c_str());
    printVerdict(model);
}

void printVerdict(const ReportModel& model) {
    const auto v = budgetVerdict(model);
    if (!v) return;
    std::printf("\nVerdict. %s\n", v->basis.c_str());
    for (const BudgetLine& line : v->lines) std::printf("  %s\n", line.sentence.c_str());
}

void reportStageTimes(const fs::path& outDir, const StageTimes& t, double gpuPassMs, bool cpuDevice) {
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
    cache["pipelines_reused"] = c.pipelinesReused.load();
    j["shader_cache"] = cache;
    std::printf("\nshaders: %d compiled by glslang, %d from the SPIR-V cache%s; pipelines: %d created, %d found in "
                "the pipeline cache (driver's report), %d reused across views and modes",
                c.glslangCompiles.load(), c.spirvCacheHits.load(),
                c.spirvCacheInvalid.load() ? (", " + std::to_string(c.spirvCacheInvalid.load()) +
                                              " invalid cache files ignored").c_str()
                                           : "",
                c.pipelines.load(), c.pipelineCacheHits.load(), c.pipelinesReused.load());
    // The warm-ups inside "shader compile" by pass kind (gpu/warm_up_times.h): on llvmpipe, where
    // a first run's JIT compile goes.
    nlohmann::ordered_json warmUps = nlohmann::ordered_json::object();
    for (const auto& [kind, w] : warmUpTotals()) {
        nlohmann::ordered_json k;
        k["count"] = w.count;
        k["ms"] = w.ms;
        k["slowest_ms"] = w.slowestMs;
        k["slowest"] = w.slowest;
        warmUps[kind] = k;
        std::printf("\nwarm-ups %s: %d, %.2f s (slowest %.2f s: %s)", kind.c_str(), w.count, w.ms / 1000.0,
                    w.slowestMs / 1000.0, w.slowest.c_str());
    }
    j["warm_ups"] = warmUps;
    j["total_ms"] = t.totalMs;
    j["gpu_pass_ms"] = gpuPassMs;
    j["total_over_gpu_passes"] = gpuPassMs > 0.0 ? t.totalMs / gpuPassMs : 0.0;
    // A CPU device renders on the cores that encode the files meanwhile, and its timestamps are
    // wall-clock time: the encoders lengthen the passes and flatter the ratio (bench/RESULTS.md,
    // 2026-11-25: 1.64x printed, 2.06x with the encoders at nice 19; bench/run.sh ratio).
    j["gpu_passes_share_host_cores"] = cpuDevice;
    std::printf("\ntotal %.2f s = %.2fx the GPU passes' own %.2f s (timestamps%s)\n", t.totalMs / 1000.0,
                gpuPassMs > 0.0 ? t.totalMs / gpuPassMs : 0.0, gpuPassMs / 1000.0,
                cpuDevice ? "; on this CPU device the passes share the cores with the file encoders, which can "
                            "lengthen them"
                          : "");
    writeFileAtomic(outDir / "timings.json", j.dump(2) + "\n");
}


}  // namespace gbl::compare
