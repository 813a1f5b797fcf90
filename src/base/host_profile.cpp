#include "host_profile.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "env_flag.h"

namespace gbl {
namespace {

struct Table {
    std::mutex mutex;
    std::map<std::string, std::pair<double, unsigned long long>> rows;  // ms, calls
    ~Table() {
        if (rows.empty()) return;
        std::vector<std::pair<std::string, std::pair<double, unsigned long long>>> v(rows.begin(), rows.end());
        std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.second.first > b.second.first; });
        std::fprintf(stderr, "GBL_HOST_PROFILE: host scopes, wall time (scopes nest and overlap across threads)\n");
        std::fprintf(stderr, "  %-34s %7s %11s %10s\n", "scope", "calls", "total ms", "ms/call");
        for (const auto& [name, r] : v)
            std::fprintf(stderr, "  %-34s %7llu %11.1f %10.2f\n", name.c_str(), r.second, r.first, r.first / double(r.second));
    }
};

Table& table() {
    static Table t;
    return t;
}

}  // namespace

bool hostProfileOn() {
    static const bool on = envFlag("GBL_HOST_PROFILE");
    return on;
}

void hostProfileAdd(const char* name, double seconds) {
    if (!hostProfileOn()) return;
    Table& t = table();
    std::lock_guard lock(t.mutex);
    auto& r = t.rows[name];
    r.first += seconds * 1e3;
    ++r.second;
}

}  // namespace gbl
