#pragma once
// Runs the real gbufferlab executable (GBL_BINARY) from a scratch folder of the test process and
// captures what it printed: the harness of the tests that check the command line from outside.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

namespace gbl::test {

struct RunResult {
    int exitCode;
    std::string out;
    std::string err;
};

// A fresh folder for this test process (its pid in the name), emptied on first use.
inline std::filesystem::path scratchFolder(const std::string& prefix) {
    std::filesystem::path d = std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()));
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
}

inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// `gbufferlab ARGS` in `folder`, with `envPrefix` (VAR=value ...) before it; exit code as the
// shell gives it (128 + signal for a signal).
inline RunResult runGbufferlab(const std::filesystem::path& folder, const std::string& args,
                               const std::string& envPrefix = "") {
    const std::filesystem::path out = folder / "stdout.txt", err = folder / "stderr.txt";
    const std::string cmd = "cd " + folder.string() + " && " + envPrefix + " " + GBL_BINARY + " " + args + " >" +
                            out.string() + " 2>" + err.string();
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), slurp(out), slurp(err)};
}

inline size_t lineCount(const std::string& s) {
    size_t n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

// A user error: exit 1, exactly one line on stderr containing every `needle`.
inline void expectOneLineError(const RunResult& r, std::initializer_list<std::string> needles) {
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    for (const auto& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "missing '" << n << "' in: " << r.err;
}

}  // namespace gbl::test
