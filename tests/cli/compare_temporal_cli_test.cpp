// compare --temporal N through the real executable: --temporal 1 is a comparison without the flag
// (every number of report.json and every image file the same); --temporal N writes the resolve's
// numbers beside frame 0's, with UE's Halton offsets; bad values are one line each, before anything
// is written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace fs = std::filesystem;
using namespace gbl::test;

namespace {

const CliScratch scratch("gbl_compare_temporal_test_");

RunResult run(const std::string& args) { return scratch.run(args); }

const std::string kCommon = "compare --scene builtin --size 96x54 --layouts niagara,crysis3-thin --views 1 ";

TEST(CompareTemporalCli, TemporalOneIsTheComparisonWithoutTheFlagBitForBit) {
    const RunResult plain = run(kCommon + "--out plain");
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    const RunResult one = run(kCommon + "--temporal 1 --out one");
    ASSERT_EQ(one.exitCode, 0) << one.err;
    // Every number of report.json, but for times and the facts of the run itself.
    const std::vector<std::pair<std::string, double>> a = scratch.reportNumbers("plain", {"run", "date"}),
                                                      b = scratch.reportNumbers("one", {"run", "date"});
    ASSERT_GT(a.size(), 100u);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i].first, b[i].first);
        EXPECT_EQ(a[i].second, b[i].second) << a[i].first;  // exactly: the same code path
    }
    const nlohmann::json j = scratch.json("one/report.json");
    EXPECT_FALSE(j["run"].contains("temporal"));
    for (const auto& r : j["runs"]) EXPECT_FALSE(r.contains("single_frame"));
    size_t files = 0;
    for (const fs::path& rel : imageFilesUnder(scratch / "plain")) {
        ++files;
        EXPECT_EQ(slurp(scratch / "plain" / rel), slurp(scratch / "one" / rel)) << rel;
    }
    EXPECT_GT(files, 10u);
}

TEST(CompareTemporalCli, ResolvedAndSingleFrameSideBySide) {
    const RunResult t = run(kCommon + "--temporal 4 --out t4");
    ASSERT_EQ(t.exitCode, 0) << t.err;
    EXPECT_NE(t.out.find("FLIP 1f"), std::string::npos) << t.out;
    const nlohmann::json j = scratch.json("t4/report.json");
    const nlohmann::json& temporal = j["run"]["temporal"];
    EXPECT_EQ(temporal["frames"], 4);
    EXPECT_EQ(temporal["resolve"], "mean");
    // Halton(k + 1, 2) - 0.5, Halton(k + 1, 3) - 0.5 (published points 1/2, 1/4, 3/4, 1/8 and
    // 1/3, 2/3, 1/9, 4/9).
    const double hx[] = {0.5, 0.25, 0.75, 0.125}, hy[] = {1.0 / 3, 2.0 / 3, 1.0 / 9, 4.0 / 9};
    ASSERT_EQ(temporal["jitter"].size(), 4u);
    for (size_t k = 0; k < 4; ++k) {
        EXPECT_NEAR(temporal["jitter"][k][0].get<double>(), hx[k] - 0.5, 1e-7);
        EXPECT_NEAR(temporal["jitter"][k][1].get<double>(), hy[k] - 0.5, 1e-7);
    }
    // The plain comparison's runs (frame without jitter) differ from both the resolve and frame 0
    // (jittered by (0, -1/6)): the frames were really moved and resolved.
    const RunResult plain = run(kCommon + "--out plain4");
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    const nlohmann::json p = scratch.json("plain4/report.json");
    ASSERT_EQ(j["runs"].size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        const nlohmann::json& r = j["runs"][i];
        ASSERT_EQ(r["status"], "ok");
        ASSERT_TRUE(r.contains("single_frame")) << r["layout"];
        const double resolved = r["image_errors"]["flip_mean"], single = r["single_frame"]["image_errors"]["flip_mean"];
        const double still = p["runs"][i]["image_errors"]["flip_mean"];
        EXPECT_GT(resolved, 0.0);
        EXPECT_GT(single, 0.0);
        EXPECT_NE(resolved, single) << r["layout"];
        EXPECT_NE(single, still) << r["layout"];
        EXPECT_TRUE(r["single_frame"]["attribute_errors"]["normal"].contains("all"));
        EXPECT_TRUE(r["attribute_errors"]["normal"].contains("all"));
    }
    // report.html shows both; the CSV carries frame 0's columns.
    const std::string html = scratch.read("t4/report.html");
    EXPECT_NE(html.find("Single frame (frame 0)"), std::string::npos);
    EXPECT_NE(html.find("data-plot=\"flip-1f\""), std::string::npos);
    EXPECT_NE(scratch.read("t4/report.csv").find("single_frame_flip_mean"), std::string::npos);
}

TEST(CompareTemporalCli, BadValuesAreOneLine) {
    const std::string c = "compare --scene builtin --size 64x36 --layouts ue4 ";
    expectOneLineError(run(c + "--temporal 0 --out e1"), {"--temporal 0", "1 to 256"});
    expectOneLineError(run(c + "--temporal eight --out e2"), {"--temporal eight", "whole number"});
    expectOneLineError(run(c + "--temporal 100000 --out e3"), {"--temporal 100000", "1 to 256"});
    expectOneLineError(run(c + "--temporal -2 --out e4"), {"--temporal -2"});
    expectOneLineError(run(c + "--temporal 4 --eval gpu --out e5"), {"--temporal 4", "--eval"});
    expectOneLineError(run(c + "--temporal 4 --band-rows 16 --out e6"), {"--temporal 4", "--band-rows"});
    expectOneLineError(run(c + "--temporal 4 --ibl ground-truth --out e7"), {"--temporal 4", "ground-truth"});
    expectOneLineError(run(c + "--temporal 4 --resolve median --out e8"), {"--resolve", "mean or exp"});
    expectOneLineError(run(c + "--resolve exp --out e9"), {"--resolve exp", "--temporal"});
    for (const char* d : {"e1", "e2", "e3", "e4", "e5", "e6", "e7", "e8", "e9"})
        EXPECT_FALSE(fs::exists(scratch / d)) << d;
}

}  // namespace

// The memory refusal of --temporal at 16384^2 advised --band-rows, which --temporal refuses; a
// refusal advises only what the command accepts with the flags given (search has no bands at all).
TEST(CompareTemporalCli, AMemoryRefusalAdvisesOnlyWhatTheFlagsAllow) {
    const std::string budget = "GBL_MEMORY_BUDGET=4G";  // refused on any machine
    const RunResult r = scratch.run("compare --scene builtin --temporal 4 --size 16384x16384 --layouts ue4 --views 1 --out huge", budget);
    expectOneLineError(r, {"--size 16384x16384", "--temporal"});
    EXPECT_EQ(r.err.find("--band-rows 64"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(scratch / "huge"));
    const RunResult s = scratch.run("search --budget 12 --size 16384x16384 --views 1 --out huge-search", budget);
    expectOneLineError(s, {"--size 16384x16384"});
    EXPECT_EQ(s.err.find("--band-rows"), std::string::npos) << s.err;
    // Without --temporal, compare can still advise bands.
    const RunResult whole =
        scratch.run("compare --scene builtin --size 16384x16384 --layouts ue4 --views 1 --band-rows 0 --out huge-whole", budget);
    expectOneLineError(whole, {"--size 16384x16384", "--band-rows 64"});
}
