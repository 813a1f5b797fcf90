// compare in bands against compare on whole frames, through the real executable: every number of
// report.json (times, the command line and notes aside) and every image file must be the same,
// for layouts that stress a band's edges (crysis3-thin's checkerboard chroma, crysis2-slim's light
// pre-pass, a visibility buffer), over two views; whole frames with the GPU's deferred 8-bit images
// give the same too; and the flag's bad uses fail with one line.
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

const CliScratch scratch("gbl_compare_bands_test_");

RunResult run(const std::string& args) { return scratch.run(args); }

// Every number of a report.json, but for times and other facts of the run itself.
std::vector<std::pair<std::string, double>> reportNumbers(const std::string& dir) {
    return scratch.reportNumbers(dir, {"times", "pass_times", "run", "date"});
}

TEST(CompareBandsCli, BandsGiveTheWholeFramesNumbersAndImages) {
    const std::string common =
        "compare --scene builtin --size 200x120 --layouts crysis3-thin,crysis2-slim,visibility-32 --views 2 --eval gpu --hdr-flip ";
    const RunResult whole = run(common + "--band-rows 0 --out whole");
    ASSERT_EQ(whole.exitCode, 0) << whole.err;
    const RunResult bands = run(common + "--band-rows 24 --out bands");  // 120 = 5 x 24
    ASSERT_EQ(bands.exitCode, 0) << bands.err;
    const RunResult odd = run(common + "--band-rows 56 --out odd");  // 56 + 56 + 8 rows
    ASSERT_EQ(odd.exitCode, 0) << odd.err;
    // Whole frames the way a GPU runs them: each run's 8-bit images unpacked by the writer's job
    // (GpuErrorImages::unpack) while later runs evaluate into new buffers. The same files.
    const RunResult deferred =
        scratch.run(common + "--band-rows 0 --out deferred", "GBL_EVAL_DEFER_IMAGES=1 GBL_HOST_PROFILE=1");
    ASSERT_EQ(deferred.exitCode, 0) << deferred.err;
    EXPECT_NE(deferred.err.find("job: unpack the 8-bit images"), std::string::npos) << "no image was deferred";
    EXPECT_EQ(whole.err.find("job: unpack the 8-bit images"), std::string::npos);

    const std::vector<std::pair<std::string, double>> expected = reportNumbers("whole");
    ASSERT_GT(expected.size(), 200u);
    for (const char* dir : {"bands", "odd", "deferred"}) {
        const std::vector<std::pair<std::string, double>> got = reportNumbers(dir);
        ASSERT_EQ(got.size(), expected.size()) << dir;
        size_t differ = 0;
        for (size_t i = 0; i < got.size(); ++i) {
            ASSERT_EQ(got[i].first, expected[i].first);
            const double e = expected[i].second, g = got[i].second;
            // Sums over bands add in another order: 1e-9 relative; every other number is exact.
            if (std::abs(g - e) > 1e-9 * std::max(1.0, std::abs(e))) {
                ++differ;
                ADD_FAILURE() << dir << " " << got[i].first << ": " << g << " vs " << e;
            }
        }
        EXPECT_EQ(differ, 0u) << dir;
        // Every image the whole-frame run wrote, byte for byte (PNGs, render.exr, crops).
        size_t files = 0;
        for (const fs::path& rel : imageFilesUnder(scratch / "whole")) {
            ++files;
            ASSERT_TRUE(fs::exists(scratch / dir / rel)) << dir << "/" << rel;
            EXPECT_EQ(slurp(scratch / "whole" / rel), slurp(scratch / dir / rel)) << dir << "/" << rel << " differs";
        }
        EXPECT_GT(files, 20u);
    }
}

TEST(CompareBandsCli, BadUsesAreOneLine) {
    expectOneLineError(run("compare --scene builtin --size 64x48 --layouts ue4 --band-rows 12 --out e1"), {"--band-rows", "multiple of 8"});
    expectOneLineError(run("compare --scene builtin --size 64x48 --layouts ue4 --band-rows 16 --eval cpu --out e2"),
                       {"--band-rows", "--eval cpu"});
    expectOneLineError(run("compare --scene builtin --size 64x48 --layouts ue4 --band-rows 16 --ibl ground-truth,split-sum --out e3"),
                       {"--band-rows", "ground-truth"});
    expectOneLineError(run("compare --scene builtin --size 64x48 --layouts ue4 --band-rows many --out e4"), {"--band-rows"});
    for (const char* d : {"e1", "e2", "e3", "e4"}) EXPECT_FALSE(fs::exists(scratch / d)) << d;
}

}  // namespace
