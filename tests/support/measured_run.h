#pragma once
// Runs the real gbufferlab executable (GBL_BINARY) as a direct child and measures it: its own
// peak resident memory (wait4's rusage, so no other process counts) and its wall time. For the
// tests that hold a refusal to "one line, exit 1, under 200 MB, within a second".
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cli_runner.h"
#include "sanitizers.h"

namespace gbl::test {

struct MeasuredRun {
    RunResult result;
    double peakMiB = 0.0;  // the child's maximum resident set size
    double seconds = 0.0;  // wall time from fork to exit
};

// `gbufferlab args...` in `folder`, with `env` (NAME, value) added to the environment.
inline MeasuredRun runMeasured(const std::filesystem::path& folder, const std::vector<std::string>& args,
                               const std::vector<std::pair<std::string, std::string>>& env = {}) {
    const std::filesystem::path outPath = folder / "stdout.txt", errPath = folder / "stderr.txt";
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = ::fork();
    if (pid == 0) {
        if (::chdir(folder.c_str()) != 0) ::_exit(126);
        for (const auto& [name, value] : env) ::setenv(name.c_str(), value.c_str(), 1);
        const int out = ::open(outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out < 0 || err < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0) ::_exit(126);
        std::vector<char*> argv;
        std::string binary = GBL_BINARY;
        argv.push_back(binary.data());
        std::vector<std::string> copies = args;
        for (std::string& a : copies) argv.push_back(a.data());
        argv.push_back(nullptr);
        ::execv(binary.c_str(), argv.data());
        ::_exit(127);
    }
    MeasuredRun m;
    int status = 0;
    rusage usage{};
    if (pid < 0 || ::wait4(pid, &status, 0, &usage) != pid) {
        m.result.exitCode = -1;
        return m;
    }
    m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    m.peakMiB = double(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
    m.result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    m.result.out = slurp(outPath);
    m.result.err = slurp(errPath);
    return m;
}

// Whether the tests run under AddressSanitizer, whose shadow memory makes a process's resident
// size no measure of what the program allocated.
constexpr bool kSanitized =
#if GBL_ASAN
    true;
#else
    false;
#endif

// A refusal: one line naming every needle, exit 1, under `maxMiB` and within `maxSeconds`.
inline void expectBoundedRefusal(const MeasuredRun& m, std::initializer_list<std::string> needles,
                                 double maxMiB = 200.0, double maxSeconds = 1.0) {
    expectOneLineError(m.result, needles);
    if (!kSanitized) {
        EXPECT_LT(m.peakMiB, maxMiB) << m.result.err;
        EXPECT_LT(m.seconds, maxSeconds) << m.result.err;
    }
}

}  // namespace gbl::test
