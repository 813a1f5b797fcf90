#pragma once
// The one memory budget every command checks an input-sized allocation against, before making
// it: a header that claims 40000x40000 pixels, a --size, a --ppd that widens FLIP's filters.
// Past the budget the command stops with one line naming the input and the fix, in well under
// a second and without having touched the memory, where the allocation would have been killed
// by the kernel (exit 137) or swapped the machine to a halt.
//
// The budget: 3/4 of the machine's memory, where the machine's memory is the physical memory
// (sysconf) or the cgroup's limit when that is lower (a container). The quarter left is for the
// system, the page cache and the estimates' error. GBL_MEMORY_BUDGET sets it instead: bytes,
// or a number with K, M, G or T (binary units: 8G = 8 GiB); never more than the machine's memory.
#include <cstdint>
#include <string>

namespace gbl {

struct MemoryBudget {
    uint64_t bytes = 0;         // what one command may allocate
    uint64_t machineBytes = 0;  // physical memory, or the cgroup's limit when lower
    std::string source;         // how `bytes` was set, as messages quote it
};

// Read once per process (the environment and the machine do not change under it). A malformed
// GBL_MEMORY_BUDGET is a UserError naming the variable.
const MemoryBudget& memoryBudget();

// "1.5 GiB", "820 MiB", "12 KiB", "17 B": sizes in messages.
std::string formatBytes(double bytes);

// Throws a UserError "<what>: needs about X of memory, more than the budget of Y (<source>);
// <fix>" when `bytes` exceeds the budget. `bytes` is a double so that an estimate computed from
// hostile dimensions cannot wrap around to a small number.
void requireMemory(double bytes, const std::string& what, const std::string& fix);

// Whether `bytes` fits the budget (for callers that choose another way, e.g. bands, instead).
bool fitsMemoryBudget(double bytes);

// Parses a GBL_MEMORY_BUDGET value ("8G", "512M", "8GiB", "1073741824"); 0 when malformed.
uint64_t parseByteCount(const std::string& text);

// The budget from a GBL_MEMORY_BUDGET value (null or empty: unset) and the machine's memory:
// what memoryBudget() computes, for tests.
MemoryBudget makeMemoryBudget(const char* environmentValue, uint64_t machineBytes);

}  // namespace gbl
