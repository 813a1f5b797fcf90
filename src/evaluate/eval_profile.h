#pragma once
// GBL_EVAL_PROFILE=1: the evaluation passes timed one by one. Each dispatch (and histogram clear)
// is then submitted on its own and waited for, timed on the host around the submission, so the
// times hold on any driver (lavapipe's timestamp queries do not bracket its compute work); the
// order of the commands, and so every result, is unchanged. The summary (calls, total and mean
// milliseconds, share) goes to stderr when the evaluator is destroyed. Off unless the variable is
// set to something other than 0; the per-dispatch submissions cost a little on a real GPU.
#include <cstdint>
#include <string>
#include <vector>

namespace gbl::evaluate {

class EvalProfile {
public:
    // Kinds: the names of what is timed (EvalDevice's passes, rows and columns apart).
    explicit EvalProfile(std::vector<std::string> kinds, std::string device);
    ~EvalProfile();
    EvalProfile(const EvalProfile&) = delete;
    EvalProfile& operator=(const EvalProfile&) = delete;

    static bool wanted();
    void add(uint32_t kind, double seconds);
    std::string summary() const;

private:
    std::vector<std::string> kinds_;
    std::string device_;
    std::vector<double> ms_;
    std::vector<uint64_t> calls_;
};

}  // namespace gbl::evaluate
