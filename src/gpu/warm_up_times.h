#pragma once
// Where a first run's shader-compile time goes on a driver that compiles at first use: llvmpipe
// (lavapipe) JIT-compiles a pipeline's shader variant at its first draw or dispatch, not at
// vkCreate*Pipelines, so the renderer makes each new pipeline's first use a one-pixel warm-up
// (render/renderer.cpp) and times it here, per kind of pass (issue 14: which shaders dominate a
// first run). One process-wide ledger; thread-safe. compare writes it to timings.json
// ("warm_ups"); GBL_WARM_UP_LOG=1 also prints every warm-up to stderr as it finishes.
#include <chrono>
#include <map>
#include <string>

namespace gbl {

struct WarmUpTotal {
    int count = 0;         // warm-ups of this kind (one per new pipeline)
    double ms = 0.0;       // their wall time together
    double slowestMs = 0.0;
    std::string slowest;   // what the slowest one warmed up (e.g. "lighting (layout ue4, split-sum)")
};

// Adds one warm-up of `kind` ("gbuffer", "material", "lighting", "decode", ...).
void recordWarmUp(const std::string& kind, const std::string& what, double ms);
// Per kind, in name order.
std::map<std::string, WarmUpTotal> warmUpTotals();

// Times its scope as one warm-up (recorded at its end; nothing when `active` is false).
class ScopedWarmUp {
public:
    ScopedWarmUp(std::string kind, std::string what, bool active = true);
    ~ScopedWarmUp();
    ScopedWarmUp(const ScopedWarmUp&) = delete;
    ScopedWarmUp& operator=(const ScopedWarmUp&) = delete;

private:
    std::string kind_, what_;
    bool active_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace gbl
