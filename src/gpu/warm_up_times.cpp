#include "warm_up_times.h"

#include <cstdio>
#include <cstdlib>
#include <mutex>

#include "env_flag.h"

namespace gbl {

namespace {

std::mutex& ledgerMutex() {
    static std::mutex m;
    return m;
}

std::map<std::string, WarmUpTotal>& ledger() {
    static std::map<std::string, WarmUpTotal> totals;
    return totals;
}

bool logEachWarmUp() {
    static const bool on = envFlag("GBL_WARM_UP_LOG");
    return on;
}

}  // namespace

void recordWarmUp(const std::string& kind, const std::string& what, double ms) {
    {
        std::lock_guard lock(ledgerMutex());
        WarmUpTotal& t = ledger()[kind];
        ++t.count;
        t.ms += ms;
        if (ms > t.slowestMs) {
            t.slowestMs = ms;
            t.slowest = what;
        }
    }
    if (logEachWarmUp()) std::fprintf(stderr, "warm-up %s: %.1f ms\n", what.c_str(), ms);
}

std::map<std::string, WarmUpTotal> warmUpTotals() {
    std::lock_guard lock(ledgerMutex());
    return ledger();
}

ScopedWarmUp::ScopedWarmUp(std::string kind, std::string what, bool active)
    : kind_(std::move(kind)), what_(std::move(what)), active_(active), start_(std::chrono::steady_clock::now()) {}

ScopedWarmUp::~ScopedWarmUp() {
    if (!active_) return;
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    recordWarmUp(kind_, what_, ms);
}

}  // namespace gbl
