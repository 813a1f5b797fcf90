#include "eval_profile.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <utility>

#include "env_flag.h"

namespace gbl::evaluate {

bool EvalProfile::wanted() {
    return envFlag("GBL_EVAL_PROFILE");
}

EvalProfile::EvalProfile(std::vector<std::string> kinds, std::string device)
    : kinds_(std::move(kinds)), device_(std::move(device)), ms_(kinds_.size(), 0.0), calls_(kinds_.size(), 0) {}

EvalProfile::~EvalProfile() {
    if (std::accumulate(calls_.begin(), calls_.end(), uint64_t(0)) > 0) std::fputs(summary().c_str(), stderr);
}

void EvalProfile::add(uint32_t kind, double seconds) {
    ms_[kind] += seconds * 1e3;
    ++calls_[kind];
}

std::string EvalProfile::summary() const {
    const double total = std::accumulate(ms_.begin(), ms_.end(), 0.0);
    std::vector<size_t> order(kinds_.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return ms_[a] > ms_[b]; });
    std::string s = "GBL_EVAL_PROFILE: evaluation passes on '" + device_ + "', one submission each, host wall time\n";
    char line[160];
    std::snprintf(line, sizeof line, "  %-18s %7s %11s %10s %7s\n", "pass", "calls", "total ms", "ms/call", "share");
    s += line;
    for (size_t k : order) {
        if (calls_[k] == 0) continue;
        std::snprintf(line, sizeof line, "  %-18s %7llu %11.1f %10.2f %6.1f%%\n", kinds_[k].c_str(),
                      static_cast<unsigned long long>(calls_[k]), ms_[k], ms_[k] / double(calls_[k]),
                      total > 0 ? 100.0 * ms_[k] / total : 0.0);
        s += line;
    }
    std::snprintf(line, sizeof line, "  %-18s %7s %11.1f\n", "all", "", total);
    s += line;
    return s;
}

}  // namespace gbl::evaluate
