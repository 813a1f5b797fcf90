// `gbufferlab search` from outside: bad arguments are one-line errors before any work; a small
// search writes a front whose files pass `layouts check`, the same bytes on a second run with the
// same seed, and a rerun into the same folder resumes from the journal to the same front.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "cli_runner.h"

namespace gbl::test {
namespace {

namespace fs = std::filesystem;

TEST(SearchCli, BadArgumentsAreOneLineErrors) {
    const fs::path dir = scratchFolder("gbl-search-cli-args-");
    expectOneLineError(runGbufferlab(dir, "search"), {"--budget", "required"});
    expectOneLineError(runGbufferlab(dir, "search --budget 0"), {"--budget"});
    expectOneLineError(runGbufferlab(dir, "search --budget twelve"), {"--budget"});
    expectOneLineError(runGbufferlab(dir, "search --budget 12 --objective ssim"), {"--objective", "ssim", "flip"});
    expectOneLineError(runGbufferlab(dir, "search --budget 12 --size 480"), {"--size"});
    expectOneLineError(runGbufferlab(dir, "search --budget 12 --views 0"), {"--views"});
    expectOneLineError(runGbufferlab(dir, "search --budget 12 --candidates -3"), {"--candidates"});
    expectOneLineError(runGbufferlab(dir, "search --budget 12 extra"), {"extra"});
    expectOneLineError(runGbufferlab(dir, "search --budget 12 --min-bits occlusion=x"), {"--min-bits", "occlusion=x"});
    expectOneLineError(runGbufferlab(dir, "search --budget 12 --min-bits albedo=4"), {"--min-bits", "albedo"});
    expectOneLineError(runGbufferlab(dir, "search --budget 12 --min-bits occlusion=9"), {"--min-bits", "to 8"});
    fs::create_directories(dir / "full");
    { std::ofstream(dir / "full" / "x.txt") << "x"; }
    expectOneLineError(runGbufferlab(dir, "search --budget 12 --out full"), {"full"});
    fs::remove_all(dir);
}

std::map<std::string, std::string> frontFiles(const fs::path& dir) {
    std::map<std::string, std::string> m;
    for (const auto& e : fs::directory_iterator(dir)) m[e.path().filename().string()] = slurp(e.path());
    return m;
}

TEST(SearchCli, SmallSearchIsDeterministicResumableAndItsFrontPassesCheck) {
    const fs::path dir = scratchFolder("gbl-search-cli-run-");
    const std::string args = "search --budget 12 --size 96x54 --views 1 --candidates 12 --seed 3 --no-confirm --threads 2";
    const RunResult a = runGbufferlab(dir, args + " --out a");
    ASSERT_EQ(a.exitCode, 0) << a.err << a.out;
    EXPECT_NE(a.err.find("ETA"), std::string::npos) << a.err;  // the progress line
    EXPECT_NE(a.out.find("closing note"), std::string::npos) << a.out;
    const RunResult b = runGbufferlab(dir, args + " --out b");
    ASSERT_EQ(b.exitCode, 0) << b.err;
    const auto fa = frontFiles(dir / "a" / "front"), fb = frontFiles(dir / "b" / "front");
    ASSERT_FALSE(fa.empty());
    EXPECT_EQ(fa, fb);  // same seed, same bytes
    const std::string report = slurp(dir / "a" / "search-report.md");
    for (const auto& [name, text] : fa) {
        if (fs::path(name).extension() != ".toml") continue;
        EXPECT_NE(text.find("seed 3"), std::string::npos) << name;
        const RunResult check = runGbufferlab(dir, "layouts check a/front/" + name);
        EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
        // Its engine code beside it (layouts export), linked from the report.
        const std::string stem = fs::path(name).stem().string();
        for (const std::string ext : {".hlsl", ".glsl"}) {
            ASSERT_TRUE(fa.count(stem + ext)) << stem + ext;
            EXPECT_NE(fa.at(stem + ext).find("gbl_" + stem.substr(0, 5) + "_"), std::string::npos) << stem + ext;
            EXPECT_NE(report.find("(front/" + stem + ext + ")"), std::string::npos) << report;
        }
    }
    // A rerun into the same folder replays the journal: nothing is evaluated again.
    const RunResult c = runGbufferlab(dir, args + " --out a");
    ASSERT_EQ(c.exitCode, 0) << c.err;
    EXPECT_NE(c.out.find("resuming"), std::string::npos) << c.out;
    EXPECT_NE(c.err.find("12/12 candidates (12 from the journal)"), std::string::npos) << c.err;
    EXPECT_EQ(frontFiles(dir / "a" / "front"), fa);
    // Another budget is another search: its journal refuses the folder.
    const RunResult d = runGbufferlab(dir, "search --budget 16 --size 96x54 --views 1 --candidates 4 --no-confirm --out a");
    expectOneLineError(d, {"search-journal.tsv", "budget=12, not budget=16"});
    fs::remove_all(dir);
}

}  // namespace
}  // namespace gbl::test
