// render --brdf / --no-ibl / --viewer-job and crossdiff from outside, as the real executable:
// refusals in one line, the job file in tools/gltf-viewer/README.md's contract, the coverage mask,
// and crossdiff's figures on images whose difference is known.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cli_runner.h"
#include "image.h"
#include "image_io.h"
#include "test_paths.h"

namespace fs = std::filesystem;

namespace {

using namespace gbl::test;

const CliScratch scratch("gbl_viewer_job_test_");

std::string waterBottle() { return (sharedAssets() / "models/WaterBottle/WaterBottle.gltf").string(); }

}  // namespace

TEST(ViewerJob, RefusesAnUnknownBrdfAndAJobWithoutAScene) {
    expectOneLineError(scratch.run("render --brdf cook --out x1"), {"--brdf cook", "ue4, gltf"});
    expectOneLineError(scratch.run("render --viewer-job j.json --out x2"), {"--viewer-job j.json", "--scene"});
    EXPECT_FALSE(fs::exists(scratch() / "x1"));
    EXPECT_FALSE(fs::exists(scratch() / "x2"));
}

// The job holds what the render used: the framed camera as a camera-to-world matrix (column-major,
// its translation the camera's position, its -Z axis pointing at the model), the scene's lights
// in KHR_lights_punctual units, no IBL with --no-ibl; the mask covers the bottle and not the corners.
TEST(ViewerJob, JobAndMaskDescribeTheRender) {
    const RunResult r = scratch.run("render --scene " + waterBottle() +
                                    " --size 64x48 --brdf gltf --no-ibl --viewer-job wb.json --out wb");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json job = scratch.json("wb.json");
    EXPECT_EQ(job["width"], 64);
    EXPECT_EQ(job["height"], 48);
    EXPECT_TRUE(job["ibl"].is_null());
    EXPECT_EQ(job["output"], "viewer.pfm");
    EXPECT_TRUE(fs::path(std::string(job["gltf"])).is_absolute());
    const auto& m = job["camera"]["camera_to_world"];
    ASSERT_EQ(m.size(), 16u);
    EXPECT_DOUBLE_EQ(double(m[15]), 1.0);
    // -Z of the camera (column 2, negated) points from the camera towards the origin, where the model is.
    const double px = m[12], py = m[13], pz = m[14], zx = m[8], zy = m[9], zz = m[10];
    const double toOrigin = -(px * -zx + py * -zy + pz * -zz) / std::sqrt(px * px + py * py + pz * pz);
    EXPECT_GT(toOrigin, 0.9);
    ASSERT_EQ(job["lights"].size(), 1u);  // WaterBottle has none: the default sun
    EXPECT_EQ(job["lights"][0]["type"], "directional");
    EXPECT_GT(double(job["camera"]["zfar"]), double(job["camera"]["znear"]));
    const std::string pgm = scratch.read("wb/reference.mask.pgm");
    const std::string header = "P5\n64 48\n255\n";
    ASSERT_EQ(pgm.size(), header.size() + 64 * 48);
    EXPECT_EQ(pgm.substr(0, header.size()), header);
    EXPECT_EQ(uint8_t(pgm[header.size()]), 0);                      // a corner: background
    EXPECT_EQ(uint8_t(pgm[header.size() + 24 * 64 + 32]), 255);     // the middle: the bottle
}

// Two 8x8 images, reference 1 everywhere, test 1.01 in one pixel, both masks covering all but one
// pixel (which differs by 100): relative RMSE = sqrt(0.01^2 / 63) / 1, max relative 0.01 at that
// pixel, one pixel beyond 1e-3, none beyond 0.02; the uncovered pixel is not measured.
TEST(Crossdiff, FiguresOfAKnownDifference) {
    gbl::Image ref(8, 8, 3, 1.0f), test(8, 8, 3, 1.0f);
    for (int c = 0; c < 3; ++c) test.at(3, 2, c) = 1.01f, test.at(0, 0, c) = 100.0f;
    gbl::writeExr((scratch() / "ref.exr").string(), ref);
    gbl::writeExr((scratch() / "test.exr").string(), test);
    std::string mask = "P5\n8 8\n255\n" + std::string(64, char(255));
    mask[std::string("P5\n8 8\n255\n").size()] = 0;
    { std::ofstream(scratch() / "m.pgm", std::ios::binary) << mask; }
    const RunResult r = scratch.run("crossdiff ref.exr m.pgm test.exr m.pgm --box 2 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["covered_pixels"], 63);
    EXPECT_NEAR(double(j["relative_rmse"]), std::sqrt(0.01 * 0.01 / 63.0), 1e-6);
    EXPECT_NEAR(double(j["max_relative"]), 0.01, 1e-6);
    EXPECT_EQ(j["worst_pixel"][0], 3);
    EXPECT_EQ(j["worst_pixel"][1], 2);
    EXPECT_EQ(j["beyond_tolerance_pixels"], 1);
    const RunResult r2 = scratch.run("crossdiff ref.exr m.pgm test.exr m.pgm --tolerance 0.02 --json");
    EXPECT_EQ(nlohmann::json::parse(r2.out)["beyond_tolerance_pixels"], 0);
    expectOneLineError(scratch.run("crossdiff ref.exr m.pgm test.exr"), {"REFERENCE REFERENCE_MASK TEST TEST_MASK"});
    { std::ofstream(scratch() / "small.pgm", std::ios::binary) << "P5\n4 4\n255\n" << std::string(16, char(255)); }
    expectOneLineError(scratch.run("crossdiff ref.exr small.pgm test.exr m.pgm"), {"small.pgm", "4x4", "8x8"});
}
