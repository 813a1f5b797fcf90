#include "progress.h"

#include <unistd.h>

namespace gbl {

Progress::Progress(int totalSteps, FILE* out)
    : total_(totalSteps), out_(out), terminal_(isatty(fileno(out)) != 0), start_(std::chrono::steady_clock::now()) {}

void Progress::begin(const std::string& what) {
    stepStart_ = std::chrono::steady_clock::now();
    std::fprintf(out_, "[%d/%d] %s ...%s", done_ + 1, total_, what.c_str(), terminal_ ? "" : "\n");
    std::fflush(out_);
}

void Progress::end(const std::string& result) {
    ++done_;
    const auto now = std::chrono::steady_clock::now();
    const double step = std::chrono::duration<double>(now - stepStart_).count();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (terminal_) {
        const double eta = elapsed / done_ * (total_ - done_);
        std::fprintf(out_, " %s (%.1f s, ETA %.0f s)\n", result.c_str(), step, eta);
    } else {
        std::fprintf(out_, "  %s\n", result.c_str());
    }
    std::fflush(out_);
}

}  // namespace gbl
