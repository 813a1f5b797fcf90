#pragma once
// Progress for long work: on a terminal, per-step lines with elapsed time and an ETA from the
// mean step time so far; when not a terminal (CI, pipes), plain lines without timing noise.
#include <chrono>
#include <cstdio>
#include <string>

namespace gbl {

class Progress {
public:
    Progress(int totalSteps, FILE* out);
    // Announces step `index` (1-based) before it starts.
    void begin(const std::string& what);
    // Reports the end of the current step with a short result ("PSNR 41.2 dB").
    void end(const std::string& result);

private:
    int total_;
    int done_ = 0;
    FILE* out_;
    bool terminal_;
    std::chrono::steady_clock::time_point start_, stepStart_;
};

}  // namespace gbl
