#pragma once
// GBL_HOST_PROFILE=1: named host-side scopes timed (wall) and summed per name; the table (calls,
// total and mean milliseconds) goes to stderr at exit. For finding where a command's host time
// goes where no profiler runs (a lent GPU machine has no perf). Off, a scope costs one branch.
#include <chrono>

namespace gbl {

bool hostProfileOn();
void hostProfileAdd(const char* name, double seconds);

class HostScope {
public:
    explicit HostScope(const char* name) : name_(hostProfileOn() ? name : nullptr) {
        if (name_) start_ = std::chrono::steady_clock::now();
    }
    ~HostScope() {
        if (name_) hostProfileAdd(name_, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
    }
    HostScope(const HostScope&) = delete;
    HostScope& operator=(const HostScope&) = delete;

private:
    const char* name_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace gbl
