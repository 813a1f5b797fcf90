#include "memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>

#include "error.h"

namespace gbl {
namespace {

// A container's limit: cgroup v2's memory.max ("max" when unlimited), else v1's
// memory.limit_in_bytes (a huge number when unlimited). 0 when neither says anything.
uint64_t cgroupLimit() {
    for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        std::ifstream in(path);
        std::string text;
        if (!(in >> text) || text == "max") continue;
        const uint64_t v = std::strtoull(text.c_str(), nullptr, 10);
        if (v > 0) return v;
    }
    return 0;
}

uint64_t machineMemory() {
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long pageSize = ::sysconf(_SC_PAGESIZE);
    uint64_t bytes = pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : 0;
    if (const uint64_t limit = cgroupLimit(); limit > 0 && (bytes == 0 || limit < bytes)) bytes = limit;
    return bytes ? bytes : uint64_t(4) << 30;  // unknown: assume a small machine
}

}  // namespace

MemoryBudget makeMemoryBudget(const char* env, uint64_t machineBytes) {
    MemoryBudget b;
    b.machineBytes = machineBytes;
    if (env && *env) {
        const uint64_t asked = parseByteCount(env);
        if (asked == 0)
            throwUserError("GBL_MEMORY_BUDGET=" + quoteName(env) +
                           ": not a size above 0; give bytes or a number with K, M, G or T, e.g. GBL_MEMORY_BUDGET=8G");
        b.bytes = std::min(asked, b.machineBytes);
        b.source = "GBL_MEMORY_BUDGET=" + std::string(env) +
                   (asked > b.machineBytes ? ", capped at the machine's " + formatBytes(double(b.machineBytes)) : "");
        return b;
    }
    b.bytes = b.machineBytes / 4 * 3;
    b.source = "3/4 of the machine's " + formatBytes(double(b.machineBytes)) + "; GBL_MEMORY_BUDGET sets another";
    return b;
}

uint64_t parseByteCount(const std::string& text) {
    size_t i = 0;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
    if (i == 0 || i > 19) return 0;
    const uint64_t n = std::strtoull(text.substr(0, i).c_str(), nullptr, 10);
    std::string unit = text.substr(i);
    if (!unit.empty() && (unit.back() == 'B' || unit.back() == 'b')) unit.pop_back();  // "8GB", "8GiB"
    if (unit.size() == 2 && (unit[1] == 'i' || unit[1] == 'I')) unit.pop_back();
    int shift = 0;
    if (unit.empty()) shift = 0;
    else if (unit.size() == 1 && std::string("kKmMgGtT").find(unit[0]) != std::string::npos)
        shift = 10 * (1 + int(std::string("kmgt").find(char(std::tolower(static_cast<unsigned char>(unit[0]))))));
    else
        return 0;
    if (shift > 0 && n > (std::numeric_limits<uint64_t>::max() >> shift)) return 0;
    return n << shift;
}

const MemoryBudget& memoryBudget() {
    static const MemoryBudget budget = makeMemoryBudget(std::getenv("GBL_MEMORY_BUDGET"), machineMemory());
    return budget;
}

std::string formatBytes(double bytes) {
    static const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int u = 0;
    while (bytes >= 1024.0 && u < 6) {
        bytes /= 1024.0;
        ++u;
    }
    char buf[48];
    if (u == 0) std::snprintf(buf, sizeof buf, "%.0f B", bytes);
    else if (!std::isfinite(bytes) || bytes >= 1e6) std::snprintf(buf, sizeof buf, "more than 1024 %s", units[u]);
    else std::snprintf(buf, sizeof buf, bytes < 10.0 ? "%.1f %s" : "%.0f %s", bytes, units[u]);
    return buf;
}

bool fitsMemoryBudget(double bytes) { return bytes <= double(memoryBudget().bytes); }

void requireMemory(double bytes, const std::string& what, const std::string& fix) {
    if (fitsMemoryBudget(bytes)) return;
    const MemoryBudget& b = memoryBudget();
    throwUserError(what + ": needs about " + formatBytes(bytes) + " of memory, more than the budget of " +
                   formatBytes(double(b.bytes)) + " (" + b.source + "); " + fix);
}

}  // namespace gbl
