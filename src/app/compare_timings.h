#pragma once
// Where a comparison's time went, stage by stage (stage_clock.h), against the GPU passes' own time
// (the timestamp queries of every frame rendered), with the shader cache's counters and the
// warm-ups by pass kind: written as timings.json for bench/, printed by the command line.
#include <filesystem>
#include <map>
#include <string>

#include "stage_clock.h"
#include "warm_up_times.h"

namespace gbl::compare {

struct CompareTimings {
    StageTimes stages;
    double gpuPassMs = 0.0;
    bool cpuDevice = false;  // the passes share the host's cores with the file encoders
    // The shader cache (shader_cache.h) as it stood when the report was written.
    bool cacheEnabled = false;
    int glslangCompiles = 0, spirvCacheHits = 0, spirvCacheInvalid = 0;
    int pipelines = 0, pipelineCacheHits = 0, pipelinesReused = 0;
    std::map<std::string, WarmUpTotal> warmUps;  // warm_up_times.h, per kind
};

// The times now: `stages` as read from the clock, the process's cache counters and warm-ups.
CompareTimings collectTimings(const StageTimes& stages, double gpuPassMs, bool cpuDevice);

// <outDir>/timings.json (schema gbufferlab-timings).
void writeTimings(const std::filesystem::path& outDir, const CompareTimings& timings);

}  // namespace gbl::compare
