#pragma once
// Progress for long work. The work counts its steps (Progress) and tells a sink; the sink decides
// what is shown. The console's (ConsoleProgress): on a terminal, per-step lines with elapsed time
// and an ETA from the mean step time so far; when not a terminal (CI, pipes), plain lines without
// timing noise.
#include <chrono>
#include <cstdio>
#include <string>

namespace gbl {

// Where progress goes (app/run_control.h passes one to a comparison or a search).
class ProgressSink {
public:
    virtual ~ProgressSink() = default;
    // A sequence of `totalSteps` counted steps begins.
    virtual void started(int totalSteps) = 0;
    // Step `step` (1-based) of `total` begins: `what` it does ("ue4 / split-sum [view 1]").
    virtual void stepBegin(int step, int total, const std::string& what) = 0;
    // ... and ends with a short result ("PSNR 41.2 dB, FLIP 0.0133").
    virtual void stepEnd(int step, int total, const std::string& result) = 0;
    // A line of news that is no step ("search: rendering the reference ...", "== scene 2 of 3 ==").
    virtual void note(const std::string& line) = 0;
    // A line of a long loop's progress ("search: 40/600 candidates, ...").
    virtual void status(const std::string& line) = 0;
    // Something failed and the work goes on without it ("scene helmet (--scene ...): ...").
    virtual void error(const std::string& line) = 0;
};

// Counts the steps of one sequence and tells `sink` (none: nobody).
class Progress {
public:
    Progress(int totalSteps, ProgressSink* sink);
    // Announces the next step before it starts.
    void begin(const std::string& what);
    // Reports the end of the current step with a short result ("PSNR 41.2 dB").
    void end(const std::string& result);

private:
    int total_;
    int done_ = 0;
    ProgressSink* sink_;
};

// gbufferlab's console: steps and status lines on `steps` (stderr), notes on `notes` (stdout),
// errors on `steps` after "gbufferlab: error: ".
class ConsoleProgress : public ProgressSink {
public:
    ConsoleProgress(FILE* steps, FILE* notes);
    void started(int totalSteps) override;
    void stepBegin(int step, int total, const std::string& what) override;
    void stepEnd(int step, int total, const std::string& result) override;
    void note(const std::string& line) override;
    void status(const std::string& line) override;
    void error(const std::string& line) override;

private:
    FILE* out_;
    FILE* notes_;
    bool terminal_;
    std::chrono::steady_clock::time_point start_, stepStart_;
};

}  // namespace gbl
