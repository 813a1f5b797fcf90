// Where a comparison's time went (compare_timings.h): timings.json.
#include "compare_timings.h"

#include <nlohmann/json.hpp>

#include "file_io.h"
#include "shader_cache.h"

namespace gbl::compare {

CompareTimings collectTimings(const StageTimes& stages, double gpuPassMs, bool cpuDevice) {
    CompareTimings t;
    t.stages = stages;
    t.gpuPassMs = gpuPassMs;
    t.cpuDevice = cpuDevice;
    // What "shader compile" paid for: glslang runs and driver pipeline compiles, or cache hits
    // (src/gpu/shader_cache.h). A second run on the same machine shows 0 glslang compiles.
    const ShaderCacheCounters& c = shaderCacheCounters();
    t.cacheEnabled = shaderCacheEnabled();
    t.glslangCompiles = c.glslangCompiles.load();
    t.spirvCacheHits = c.spirvCacheHits.load();
    t.spirvCacheInvalid = c.spirvCacheInvalid.load();
    t.pipelines = c.pipelines.load();
    t.pipelineCacheHits = c.pipelineCacheHits.load();
    t.pipelinesReused = c.pipelinesReused.load();
    // The warm-ups inside "shader compile" by pass kind (gpu/warm_up_times.h): on llvmpipe, where
    // a first run's JIT compile goes.
    t.warmUps = warmUpTotals();
    return t;
}

void writeTimings(const std::filesystem::path& outDir, const CompareTimings& t) {
    nlohmann::ordered_json j;
    j["schema"] = "gbufferlab-timings";
    j["schema_version"] = 1;
    nlohmann::ordered_json stages;
    for (size_t s = 0; s < kStageCount; ++s) stages[stageName(Stage(s))] = t.stages.ms[s];
    j["stages_ms"] = stages;
    nlohmann::ordered_json cache;
    cache["enabled"] = t.cacheEnabled;
    cache["glslang_compiles"] = t.glslangCompiles;
    cache["spirv_cache_hits"] = t.spirvCacheHits;
    cache["spirv_cache_invalid"] = t.spirvCacheInvalid;
    cache["pipelines"] = t.pipelines;
    cache["pipeline_cache_hits"] = t.pipelineCacheHits;
    cache["pipelines_reused"] = t.pipelinesReused;
    j["shader_cache"] = cache;
    nlohmann::ordered_json warmUps = nlohmann::ordered_json::object();
    for (const auto& [kind, w] : t.warmUps) {
        nlohmann::ordered_json k;
        k["count"] = w.count;
        k["ms"] = w.ms;
        k["slowest_ms"] = w.slowestMs;
        k["slowest"] = w.slowest;
        warmUps[kind] = k;
    }
    j["warm_ups"] = warmUps;
    j["total_ms"] = t.stages.totalMs;
    j["gpu_pass_ms"] = t.gpuPassMs;
    j["total_over_gpu_passes"] = t.gpuPassMs > 0.0 ? t.stages.totalMs / t.gpuPassMs : 0.0;
    // A CPU device renders on the cores that encode the files meanwhile, and its timestamps are
    // wall-clock time: the encoders lengthen the passes and flatter the ratio (bench/RESULTS.md,
    // 2026-11-25: 1.64x printed, 2.06x with the encoders at nice 19; bench/run.sh ratio).
    j["gpu_passes_share_host_cores"] = t.cpuDevice;
    writeFileAtomic(outDir / "timings.json", j.dump(2) + "\n");
}

}  // namespace gbl::compare
