// Views with nothing to measure (compare.md, "Views with nothing to measure"), run as the real
// executable on tiny frames: an exposure that clips the reference to black gave "PSNR inf, FLIP
// 0.0000" and a verdict of ties; a camera that sees no geometry did too, and counted in the means.
// Such a view is marked not measured with its reason in every file and left out of the means; a
// comparison with no view measured exits non-zero.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace fs = std::filesystem;
using Json = nlohmann::json;
using namespace gbl::test;

namespace {

const CliScratch scratch("gbl_nothing_measured_test_");

RunResult run(const std::string& args) { return scratch.run(args); }

}  // namespace

TEST(NothingMeasured, AReferenceClippedToBlackIsNoPerfectScore) {
    const RunResult r = run("compare --scene builtin --size 64x36 --views 1 --layouts ue4,crysis3-thin --exposure 1e-30 --out black");
    EXPECT_EQ(r.exitCode, 4) << r.err;
    EXPECT_NE(r.err.find("no view had anything to measure"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("NOT MEASURED"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("view 0 not measured: the reference tone-maps to all black at exposure 1e-30"),
              std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("inf"), std::string::npos) << r.out;
    const Json report = scratch.json("black/report.json");
    ASSERT_TRUE(report["run"].contains("view_not_measured")) << report["run"].dump();
    EXPECT_NE(report["run"]["view_not_measured"][0].get<std::string>().find("all black"), std::string::npos);
    ASSERT_EQ(report["runs"].size(), 2u);
    for (const Json& run : report["runs"]) {
        EXPECT_EQ(run["status"], "not-measured");
        EXPECT_FALSE(run.contains("image_errors")) << run.dump();
        EXPECT_NE(run.value("not_measured", "").find("view 0: "), std::string::npos);
    }
    EXPECT_FALSE(report.contains("verdict")) << report.value("verdict", Json()).dump();
    const std::string csv = scratch.read("black/report.csv");
    EXPECT_NE(csv.find("not-measured"), std::string::npos);
    EXPECT_NE(csv.find("all black"), std::string::npos);
    EXPECT_NE(scratch.read("black/report.html").find("not measured"), std::string::npos);
    EXPECT_FALSE(fs::exists(scratch() / "black/INCOMPLETE"));
}

TEST(NothingMeasured, ACameraThatSeesNoGeometryIsLeftOutOfTheMeans) {
    // Two cameras on the built-in scene: one at the spheres, one straight up at the sky.
    std::ofstream(scratch() / "two-views.toml") << R"([[scene]]
gltf = "builtin"
[[scene.camera]]
position = [0.0, 1.0, 4.0]
target = [0.0, 0.5, 0.0]
[[scene.camera]]
position = [0.0, 1.0, 4.0]
target = [0.0, 50.0, 4.0]
up = [0.0, 0.0, -1.0]
)";
    const RunResult r = run("compare --scene two-views.toml --size 64x36 --layouts ue4,crysis3-thin --out sky");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Json report = scratch.json("sky/scenes/builtin/report.json");
    ASSERT_TRUE(report["run"].contains("view_not_measured")) << report["run"].dump();
    EXPECT_EQ(report["run"]["view_not_measured"][0], "");
    EXPECT_NE(report["run"]["view_not_measured"][1].get<std::string>().find("coverage 0"), std::string::npos)
        << report["run"]["view_not_measured"].dump();
    for (const Json& run : report["runs"]) {
        EXPECT_EQ(run["status"], "ok");
        EXPECT_NE(run.value("not_measured", "").find("view 1: "), std::string::npos);
        // The mean is view 0's alone: the sky view adds no PSNR inf, no FLIP 0.
        ASSERT_EQ(run["views"].size(), 2u);
        EXPECT_FALSE(run["views"][1].contains("image_errors"));
        EXPECT_EQ(run["image_errors"]["flip_mean"], run["views"][0]["image_errors"]["flip_mean"]);
        EXPECT_EQ(run["image_errors"]["psnr_tonemapped_db"], run["views"][0]["image_errors"]["psnr_tonemapped_db"]);
        EXPECT_EQ(run["view_spread"]["image_errors"]["flip_mean"]["views"], 1);
    }
    EXPECT_EQ(report["verdict"]["views"], 1);
    EXPECT_NE(scratch.read("sky/scenes/builtin/report.csv").find("coverage 0"), std::string::npos);
    // The report agrees with itself: its means are over the one view measured, and it says so.
    EXPECT_NE(scratch.read("sky/scenes/builtin/report.html").find("Every metric is the mean over 1 of the 2 views"),
              std::string::npos);
    EXPECT_NE(r.out.find("Every metric is the mean over 1 of the 2 views"), std::string::npos) << r.out;
}
