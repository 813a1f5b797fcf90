#include "progress.h"

#include <unistd.h>

namespace gbl {

Progress::Progress(int totalSteps, ProgressSink* sink) : total_(totalSteps), sink_(sink) {
    if (sink_) sink_->started(total_);
}

void Progress::begin(const std::string& what) {
    if (sink_) sink_->stepBegin(done_ + 1, total_, what);
}

void Progress::end(const std::string& result) {
    ++done_;
    if (sink_) sink_->stepEnd(done_, total_, result);
}

ConsoleProgress::ConsoleProgress(FILE* steps, FILE* notes)
    : out_(steps), notes_(notes), terminal_(isatty(fileno(steps)) != 0), start_(std::chrono::steady_clock::now()) {}

void ConsoleProgress::started(int) { start_ = std::chrono::steady_clock::now(); }

void ConsoleProgress::stepBegin(int step, int total, const std::string& what) {
    stepStart_ = std::chrono::steady_clock::now();
    std::fprintf(out_, "[%d/%d] %s ...%s", step, total, what.c_str(), terminal_ ? "" : "\n");
    std::fflush(out_);
}

void ConsoleProgress::stepEnd(int step, int total, const std::string& result) {
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double stepSeconds = std::chrono::duration<double>(now - stepStart_).count();
    if (terminal_) {
        const double eta = elapsed / step * (total - step);
        std::fprintf(out_, " %s (%.1f s, ETA %.0f s)\n", result.c_str(), stepSeconds, eta);
    } else {
        std::fprintf(out_, "  %s\n", result.c_str());
    }
    std::fflush(out_);
}

void ConsoleProgress::note(const std::string& line) {
    std::fprintf(notes_, "%s\n", line.c_str());
    std::fflush(notes_);
}

void ConsoleProgress::status(const std::string& line) { std::fprintf(out_, "%s\n", line.c_str()); }

void ConsoleProgress::error(const std::string& line) { std::fprintf(out_, "gbufferlab: error: %s\n", line.c_str()); }

}  // namespace gbl
