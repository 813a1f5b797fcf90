#pragma once
// Runs the real gbufferlab executable (GBL_BINARY) from a scratch folder of the test process and
// captures what it printed: the harness of the tests that check the command line from outside.
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "temp_dir.h"

namespace gbl::test {

struct RunResult {
    int exitCode;
    std::string out;
    std::string err;
};

// The whole file as text ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) { return readFile(p); }

// `gbufferlab ARGS` in `folder`, with `envPrefix` (VAR=value ...) before it; exit code as the
// shell gives it (128 + signal for a signal).
RunResult runGbufferlab(const std::filesystem::path& folder, const std::string& args, const std::string& envPrefix = "");

// `command` run by the shell; its exit code as runGbufferlab gives it.
int shellExitCode(const std::string& command);

// The scratch folder of a test file that runs gbufferlab (ScratchDir: made on first use), the
// runs in it and the files they write there.
class CliScratch : public ScratchDir {
public:
    using ScratchDir::ScratchDir;
    RunResult run(const std::string& args, const std::string& envPrefix = "") const {
        return runGbufferlab((*this)(), args, envPrefix);
    }
    std::string read(const std::filesystem::path& name) const { return readFile(*this / name); }
    nlohmann::json json(const std::filesystem::path& name) const { return nlohmann::json::parse(read(name)); }
    // Every number of `dir`/report.json by its JSON pointer (jsonNumbers), but under the keys that
    // hold "ms" (times) and `skipKeys` (other facts of the run itself).
    std::vector<std::pair<std::string, double>> reportNumbers(const std::string& dir,
                                                              std::initializer_list<std::string> skipKeys) const;
};

size_t lineCount(const std::string& s);

// A user error: exit 1, exactly one line on stderr containing every `needle`.
void expectOneLineError(const RunResult& r, std::initializer_list<std::string> needles);

// Every number under `j` with its JSON pointer, in document order, leaving out the members whose
// key `skip` says (times and other facts of the run itself, which differ between runs).
std::vector<std::pair<std::string, double>> jsonNumbers(const nlohmann::json& j,
                                                        const std::function<bool(const std::string& key)>& skip);

// The image files (.png, .exr) under `dir`, as paths relative to it, in the order the folder walk
// gives them.
std::vector<std::filesystem::path> imageFilesUnder(const std::filesystem::path& dir);

}  // namespace gbl::test
