#include "cli_runner.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>

namespace gbl::test {

namespace fs = std::filesystem;

int shellExitCode(const std::string& command) {
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

RunResult runGbufferlab(const fs::path& folder, const std::string& args, const std::string& envPrefix) {
    const fs::path out = folder / "stdout.txt", err = folder / "stderr.txt";
    const std::string cmd = "cd " + folder.string() + " && " + envPrefix + " " + GBL_BINARY + " " + args + " >" +
                            out.string() + " 2>" + err.string();
    const int code = shellExitCode(cmd);
    return {code, readFile(out), readFile(err)};
}

size_t lineCount(const std::string& s) {
    size_t n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

void expectOneLineError(const RunResult& r, std::initializer_list<std::string> needles) {
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    for (const auto& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "missing '" << n << "' in: " << r.err;
}

namespace {

void collectNumbers(const nlohmann::json& j, const std::string& at, const std::function<bool(const std::string&)>& skip,
                    std::vector<std::pair<std::string, double>>& out) {
    if (j.is_object()) {
        for (auto it = j.begin(); it != j.end(); ++it) {
            if (skip(it.key())) continue;
            collectNumbers(it.value(), at + "/" + it.key(), skip, out);
        }
    } else if (j.is_array()) {
        for (size_t i = 0; i < j.size(); ++i) collectNumbers(j[i], at + "/" + std::to_string(i), skip, out);
    } else if (j.is_number()) {
        out.emplace_back(at, j.get<double>());
    }
}

}  // namespace

std::vector<std::pair<std::string, double>> jsonNumbers(const nlohmann::json& j,
                                                        const std::function<bool(const std::string&)>& skip) {
    std::vector<std::pair<std::string, double>> out;
    collectNumbers(j, "", skip, out);
    return out;
}

std::vector<std::pair<std::string, double>> CliScratch::reportNumbers(const std::string& dir,
                                                                      std::initializer_list<std::string> skipKeys) const {
    const std::vector<std::string> skipped(skipKeys);
    return jsonNumbers(json(dir + "/report.json"), [&](const std::string& k) {
        return k.find("ms") != std::string::npos || std::find(skipped.begin(), skipped.end(), k) != skipped.end();
    });
}

std::vector<fs::path> imageFilesUnder(const fs::path& dir) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        const fs::path rel = fs::relative(entry.path(), dir);
        if (rel.extension() == ".png" || rel.extension() == ".exr") files.push_back(rel);
    }
    return files;
}

}  // namespace gbl::test
