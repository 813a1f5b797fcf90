// The gbufferlab binary on bad input: one clear line naming the file or flag, a non-zero
// exit, no output directory or partial file, never a crash. Runs the real executable.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <map>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "color_map.h"
#include "ibl_figure.h"
#include "image_io.h"

namespace fs = std::filesystem;

namespace {

using namespace gbl::test;

const CliScratch scratch("gbl_cli_test_");

RunResult run(const std::string& args, const std::string& envPrefix = "") { return scratch.run(args, envPrefix); }

TEST(Cli, MissingVulkanDriverIsOneClearLine) {
    const RunResult r = run("render --out nodriver --size 64x64",
                            "VK_DRIVER_FILES=/nonexistent/none.json VK_ICD_FILENAMES=/nonexistent/none.json");
    expectOneLineError(r, {"no Vulkan driver found", "mesa-vulkan-drivers"});
    EXPECT_EQ(r.err.find("VK_ERROR"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(scratch() / "nodriver"));
}

TEST(Cli, BadSizesNameTheFlag) {
    for (const std::string size : {"0x0", "abc", "100000x10", "640", "-5x10", "64x"}) {
        const RunResult r = run("render --out badsize --size " + size);
        expectOneLineError(r, {"--size"});
        EXPECT_FALSE(fs::exists(scratch() / "badsize")) << size;
    }
}

TEST(Cli, MissingAndMalformedSceneNameTheFile) {
    RunResult r = run("render --out s1 --size 32x32 --scene does_not_exist.gltf");
    expectOneLineError(r, {"does_not_exist.gltf"});
    { std::ofstream(scratch() / "garbage.gltf") << "{ this is not json"; }
    r = run("render --out s2 --size 32x32 --scene garbage.gltf");
    expectOneLineError(r, {"garbage.gltf"});
    { std::ofstream(scratch() / "garbage.glb") << "glTF\x02\x00\x00\x00 truncated"; }
    r = run("render --out s3 --size 32x32 --scene garbage.glb");
    expectOneLineError(r, {"garbage.glb"});
    EXPECT_FALSE(fs::exists(scratch() / "s1"));
    EXPECT_FALSE(fs::exists(scratch() / "s2"));
    EXPECT_FALSE(fs::exists(scratch() / "s3"));
}

TEST(Cli, MissingAndMalformedEnvironmentNameTheFile) {
    RunResult r = run("render --out e1 --size 32x32 --env nothing.hdr");
    expectOneLineError(r, {"nothing.hdr"});
    { std::ofstream(scratch() / "bad.exr") << "not an exr file at all"; }
    r = run("render --out e2 --size 32x32 --env bad.exr");
    expectOneLineError(r, {"bad.exr"});
    { std::ofstream(scratch() / "sky.png") << "x"; }
    r = run("render --out e3 --size 32x32 --env sky.png");
    expectOneLineError(r, {"sky.png"});
    EXPECT_FALSE(fs::exists(scratch() / "e1"));
    EXPECT_FALSE(fs::exists(scratch() / "e2"));
}

TEST(Cli, NonEmptyOutputNeedsForceAndIsNotTouchedWithout) {
    fs::create_directories(scratch() / "full");
    { std::ofstream(scratch() / "full" / "reference.png") << "the user's file"; }
    RunResult r = run("render --out full --size 32x32");
    expectOneLineError(r, {"--out", "--force"});
    EXPECT_EQ(slurp(scratch() / "full" / "reference.png"), "the user's file");
    r = run("render --out full --size 32x32 --force");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(slurp(scratch() / "full" / "reference.png"), "the user's file");
    // Written whole: no temporary files left behind.
    for (const auto& e : fs::directory_iterator(scratch() / "full"))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

// render --band-rows: the frame rendered 7 rows at a time (renderer.h RenderSettings::bandRows)
// is written as the same files, byte for byte, as the whole frame.
TEST(Cli, RenderInBandsWritesTheSameFiles) {
    RunResult r = run("render --out whole --size 96x54");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = run("render --out bands --size 96x54 --band-rows 7");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* file : {"reference.exr", "reference.png"})
        EXPECT_EQ(slurp(scratch() / "whole" / file), slurp(scratch() / "bands" / file)) << file;
    for (const std::string rows : {"0", "-3", "abc", "99999999"}) {
        r = run("render --out badband --size 32x32 --band-rows " + rows);
        expectOneLineError(r, {"--band-rows"});
        EXPECT_FALSE(fs::exists(scratch() / "badband")) << rows;
    }
    r = run("render --out badband --size 32x32 --band-rows 8 --ibl ground-truth");
    expectOneLineError(r, {"--band-rows", "ground-truth"});
    EXPECT_FALSE(fs::exists(scratch() / "badband"));
}

TEST(Cli, RenderWritesExrAndPng) {
    const RunResult r = run("render --out ok --size 96x54");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::file_size(scratch() / "ok" / "reference.exr") > 96 * 54);
    const std::string png = slurp(scratch() / "ok" / "reference.png");
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(Cli, CompareReportsEveryRunAndTimesItsStages) {
    RunResult r = run("compare --scene builtin --out cmp --size 96x64 --layouts ue4,crysis3-thin");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json report = scratch.json("cmp/report.json");
    ASSERT_EQ(report["runs"].size(), 2u);
    for (const auto& run : report["runs"]) {
        EXPECT_TRUE(run["image_errors"].contains("flip_mean")) << run["layout"];
        EXPECT_FALSE(run["image_errors"].contains("hdr_flip_mean")) << "HDR-FLIP is opt-in";
    }
    // After the table, the verdict: report.json's sentences, one line per budget, in order.
    ASSERT_TRUE(report.contains("verdict"));
    ASSERT_EQ(report["verdict"]["budgets"].size(), 6u);
    size_t at = r.out.find("\ncrysis3-thin ");  // the table's last row
    ASSERT_NE(at, std::string::npos) << r.out;
    at = r.out.find("\nVerdict. " + report["verdict"]["basis"].get<std::string>() + "\n", at);
    EXPECT_NE(at, std::string::npos) << r.out;
    for (const auto& budget : report["verdict"]["budgets"]) {
        at = r.out.find("\n  " + budget["sentence"].get<std::string>() + "\n", at);
        EXPECT_NE(at, std::string::npos) << budget["sentence"] << "\n" << r.out;
    }
    // The stages are exclusive: they add up to the total, and the frames' own GPU time is known.
    const nlohmann::json t = scratch.json("cmp/timings.json");
    double sum = 0.0;
    for (const auto& [stage, ms] : t["stages_ms"].items()) {
        EXPECT_GE(ms.get<double>(), 0.0) << stage;
        sum += ms.get<double>();
    }
    EXPECT_EQ(t["stages_ms"].size(), 8u);
    EXPECT_NEAR(sum, t["total_ms"].get<double>(), 1e-6 * sum);
    EXPECT_GT(t["gpu_pass_ms"].get<double>(), 0.0);
    EXPECT_GT(t["stages_ms"]["rendering"].get<double>(), 0.0);
    EXPECT_NE(r.out.find("time by stage"), std::string::npos) << r.out;
    // lavapipe (compare's default device) renders on the host's cores: the ratio says so.
    EXPECT_EQ(t["gpu_passes_share_host_cores"], true);
    EXPECT_NE(r.out.find("on this CPU device the passes share the cores"), std::string::npos) << r.out;

    r = run("compare --scene builtin --out cmp-hdr --size 96x64 --layouts crysis3-thin --hdr-flip");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json hdr = scratch.json("cmp-hdr/report.json");
    const auto& errors = hdr["runs"][0]["image_errors"];
    ASSERT_TRUE(errors.contains("hdr_flip_mean"));
    EXPECT_GT(errors["hdr_flip_mean"].get<double>(), 0.0);  // crysis3-thin loses visible colour
    EXPECT_GE(errors["hdr_flip_exposures"].get<int>(), 2);

    r = run("compare --scene builtin --out cmp-both --size 96x64 --hdr-flip --no-hdr-flip");
    expectOneLineError(r, {"--hdr-flip", "--no-hdr-flip"});
    EXPECT_FALSE(fs::exists(scratch() / "cmp-both"));
}

// The seed's figure: one row per IBL mode (ground truth first), one column per ball of the grid,
// and under each row the numbers report.json holds, drawn in the bitmap font; per-class image
// errors add up to the covered pixels' and the ground truth reports its noise beside each run.
// compare --views N: every metric is the mean of its per-view values, with a spread >= 0; the
// views are different cameras, so their errors differ. Bad counts are one line naming the flag.
// ToyCar's glass (KHR_materials_transmission) is drawn forward by deferred engines: compare says
// how many pixels it leaves out of every metric, per view, in the report's notes and on the
// console, and measures the rest.
TEST(Cli, CompareCountsAndExcludesForwardDrawnPixels) {
    const fs::path toyCar = fs::path(GBL_SHARED_DIR) / "assets" / "models" / "ToyCar" / "ToyCar.gltf";
    if (!fs::exists(toyCar)) GTEST_SKIP() << "missing input " << toyCar.string();
    RunResult r = run("compare --scene " + toyCar.string() + " --out toycar --size 96x64 --views 1 --layouts ue4");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json report = nlohmann::json::parse(slurp(scratch() / "toycar" / "report.json"));
    std::string note;
    for (const auto& n : report["run"]["notes"])
        if (n.get<std::string>().find("forward") != std::string::npos) note = n.get<std::string>();
    EXPECT_NE(note.find("% of pixels forward, excluded from every metric"), std::string::npos) << note;
    EXPECT_NE(note.find("KHR_materials_transmission"), std::string::npos) << note;
    const double percent = std::stod(note);
    EXPECT_GT(percent, 0.1) << note;
    EXPECT_LT(percent, 20.0) << note;
    EXPECT_NE((r.out + r.err).find("% of pixels forward, excluded"), std::string::npos);
    ASSERT_EQ(report["runs"].size(), 1u);
    EXPECT_TRUE(report["runs"][0]["image_errors"].contains("flip_mean"));
}

TEST(Cli, CompareViewsReportTheMeanOverViewsAndItsSpread) {
    for (const std::string bad : {"0", "abc", "-1", "2x", "17"}) {
        const RunResult b = run("compare --scene builtin --out badviews --size 32x32 --layouts ue4 --views " + bad);
        expectOneLineError(b, {"--views"});
        EXPECT_FALSE(fs::exists(scratch() / "badviews")) << bad;
    }
    const RunResult r = run("compare --scene builtin --out views2 --size 96x64 --layouts ue4,crysis3-thin --views 2");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json report = scratch.json("views2/report.json");
    ASSERT_EQ(report["run"]["views"].size(), 2u);
    ASSERT_EQ(report["runs"].size(), 2u);
    const auto num = [](const nlohmann::json& j) {
        return j.is_string() ? (j == "inf" ? INFINITY : -INFINITY) : j.get<double>();
    };
    for (const auto& run : report["runs"]) {
        SCOPED_TRACE(run["layout"].get<std::string>());
        ASSERT_EQ(run["views"].size(), 2u);
        const nlohmann::json& v0 = run["views"][0];
        const nlohmann::json& v1 = run["views"][1];
        const std::vector<nlohmann::json::json_pointer> metrics = {
            nlohmann::json::json_pointer("/image_errors/psnr_tonemapped_db"),
            nlohmann::json::json_pointer("/image_errors/flip_mean"),
            nlohmann::json::json_pointer("/image_errors/rmse_linear"),
            nlohmann::json::json_pointer("/attribute_errors/normal/all/mean")};
        for (const auto& m : metrics) {
            SCOPED_TRACE(m.to_string());
            const double a = num(v0.at(m)), b = num(v1.at(m)), mean = num(run.at(m));
            EXPECT_NEAR(mean, 0.5 * (a + b), 1e-9 * std::max(1.0, std::abs(mean)));
            const nlohmann::json& spread = run["view_spread"].at(m);
            EXPECT_GE(num(spread["std"]), 0.0);
            EXPECT_NEAR(num(spread["std"]), 0.5 * std::abs(a - b), 1e-9 * std::max(1.0, std::abs(a - b)));
            EXPECT_EQ(num(spread["min"]), std::min(a, b));
            EXPECT_EQ(num(spread["max"]), std::max(a, b));
            EXPECT_EQ(spread["views"], 2);
        }
        // Different cameras, different errors.
        EXPECT_NE(v0["image_errors"]["flip_mean"], v1["image_errors"]["flip_mean"]);
        EXPECT_NE(v0["image_errors"]["rmse_linear"], v1["image_errors"]["rmse_linear"]);
    }
    // The CSV has each metric's spread, the console table its rows.
    const std::string csv = slurp(scratch() / "views2" / "report.csv");
    const std::string header = csv.substr(0, csv.find('\n'));
    for (const char* column : {",views,", ",psnr_tonemapped_db_view_min,", ",psnr_tonemapped_db_view_max,",
                               ",flip_mean_view_std,", ",normal_all_mean_deg_view_std,"})
        EXPECT_NE(header.find(column), std::string::npos) << column;
    EXPECT_NE(r.out.find("mean over 2 views"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("spread"), std::string::npos) << r.out;
    const std::string html = slurp(scratch() / "views2" / "report.html");
    EXPECT_NE(html.find("mean over 2 views"), std::string::npos);
    EXPECT_NE(html.find("class=\"spread\""), std::string::npos);
}

TEST(Cli, CompareDrawsTheSeedsIblFigureWithTheReportsNumbers) {
    const RunResult r = run("compare --scene builtin --out fig --size 160x90 --layouts ue4 --ibl bo2,ground-truth,split-sum "
                            "--gt-noise 0.05 --gt-batch-samples 16");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json report = scratch.json("fig/report.json");
    ASSERT_TRUE(report.contains("ibl_figure"));
    const auto& fig = report["ibl_figure"];
    ASSERT_EQ(fig["rows"].size(), 3u);
    EXPECT_EQ(fig["rows"][0]["ibl_mode"], "ground-truth");
    EXPECT_EQ(fig["rows"][1]["ibl_mode"], "split-sum");
    EXPECT_EQ(fig["rows"][2]["ibl_mode"], "bo2");
    ASSERT_EQ(fig["columns"].size(), 12u);
    for (size_t c = 0; c < 12; ++c)
        EXPECT_EQ(fig["columns"][c].get<std::string>().rfind(c < 6 ? "metal r=" : "dielectric r=", 0), 0u) << c;

    // Numbers: each row's equal its lighting run's per-class errors (ground truth: its noise), of
    // the first view (the figure is drawn from it; the run's own numbers are means over views).
    std::map<std::string, nlohmann::json> lighting;
    for (const auto& run : report["runs"]) {
        ASSERT_TRUE(run.contains("views"));
        for (const auto& view : run["views"]) {
            const auto& classes = view["image_errors"]["by_class"];
            if (!classes.contains("metal") || !classes.contains("dielectric")) continue;  // not in sight
            const double n = classes["covered"]["pixels"].get<double>();
            const double nm = classes["metal"]["pixels"].get<double>(), nd = classes["dielectric"]["pixels"].get<double>();
            EXPECT_EQ(n, nm + nd);
            const double sum = classes["metal"]["rel_luminance_mean"].get<double>() * nm +
                               classes["dielectric"]["rel_luminance_mean"].get<double>() * nd;
            EXPECT_NEAR(classes["covered"]["rel_luminance_mean"].get<double>() * n, sum, 1e-9 * std::max(sum, 1.0));
        }
        const auto& classes = run["views"][0]["image_errors"]["by_class"];
        if (run["layout"].get<std::string>().rfind("reference (", 0) == 0) {
            lighting[run["ibl_mode"].get<std::string>()] = run["views"][0];
            ASSERT_TRUE(run.contains("ground_truth"));  // the reference's convergence, beside the comparison
            EXPECT_TRUE(classes["metal"].contains("reference_noise"));
        }
    }
    ASSERT_EQ(lighting.size(), 2u);
    const auto& noiseSource = lighting.at("split-sum")["image_errors"]["by_class"];
    EXPECT_EQ(fig["rows"][0]["metal_noise"], noiseSource["metal"]["reference_noise"]);
    EXPECT_EQ(fig["rows"][0]["dielectric_noise"], noiseSource["dielectric"]["reference_noise"]);
    for (size_t i = 1; i < 3; ++i) {
        const auto& row = fig["rows"][i];
        const auto& classes = lighting.at(row["ibl_mode"].get<std::string>())["image_errors"]["by_class"];
        EXPECT_EQ(row["metal_error"], classes["metal"]["rel_luminance_mean"]);
        EXPECT_EQ(row["dielectric_error"], classes["dielectric"]["rel_luminance_mean"]);
    }

    // The PNG: its size is that of 3 rows x 12 tiles, and each caption band holds exactly the
    // caption made from the row's JSON numbers.
    const gbl::Image8 png = gbl::readImage8((scratch() / "fig" / fig["png"].get<std::string>()).string());
    const int band = gbl::iblFigureCaptionBandHeight();
    const int rowsHeight = png.height - gbl::kIblFigureTitleHeight - gbl::kIblFigureMargin;
    ASSERT_EQ(rowsHeight % 3, 0);
    const int tile = rowsHeight / 3 - band;
    ASSERT_GE(tile, 64);
    EXPECT_EQ(png.width, 2 * gbl::kIblFigureMargin + 12 * tile + 11 * gbl::kIblFigureTileGap + gbl::kIblFigureGroupGap);
    for (int i = 0; i < 3; ++i) {
        const auto& row = fig["rows"][size_t(i)];
        gbl::IblFigureRow fromJson;
        fromJson.iblMode = row["ibl_mode"];
        if (row.contains("metal_error")) fromJson.metalError = row["metal_error"].get<double>();
        if (row.contains("dielectric_error")) fromJson.dielectricError = row["dielectric_error"].get<double>();
        if (row.contains("metal_noise")) fromJson.metalNoise = row["metal_noise"].get<double>();
        if (row.contains("dielectric_noise")) fromJson.dielectricNoise = row["dielectric_noise"].get<double>();
        const std::string caption = gbl::iblFigureCaption(fromJson);
        EXPECT_EQ(row["caption"], caption);
        gbl::Image8 expected;
        expected.width = png.width;
        expected.height = band;
        expected.channels = 3;
        expected.pixels.assign(size_t(png.width) * band * 3, 0);
        gbl::fillRect(expected, 0, 0, png.width, band, gbl::kIblFigureBackground);
        gbl::drawText(expected, gbl::kIblFigureMargin, gbl::kIblFigureCaptionPad, caption, gbl::kIblFigureText,
                      gbl::kIblFigureTextScale);
        const int top = gbl::kIblFigureTitleHeight + i * (tile + band) + tile;
        size_t differing = 0;
        for (int y = 0; y < band; ++y)
            for (int x = 0; x < png.width; ++x)
                for (int c = 0; c < 3; ++c)
                    differing += png.pixels[(size_t(top + y) * png.width + x) * size_t(png.channels) + c] !=
                                 expected.pixels[(size_t(y) * png.width + x) * 3 + c];
        EXPECT_EQ(differing, 0u) << "caption of row " << i << ": " << caption;
    }
    // Each tile shows its ball only: the corners (outside the ball, where the default scene's
    // surroundings would show) are the backdrop, the centre is not.
    auto pixelIs = [&](int x, int y, gbl::Rgb8 c) {
        const unsigned char* p = &png.pixels[(size_t(y) * png.width + x) * size_t(png.channels)];
        return p[0] == c.r && p[1] == c.g && p[2] == c.b;
    };
    for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 12; ++c) {
            const int x0 = gbl::kIblFigureMargin + c * (tile + gbl::kIblFigureTileGap) + (c >= 6 ? gbl::kIblFigureGroupGap : 0);
            const int y0 = gbl::kIblFigureTitleHeight + i * (tile + band);
            for (auto [dx, dy] : {std::pair{1, 1}, std::pair{tile - 2, 1}, std::pair{1, tile - 2}, std::pair{tile - 2, tile - 2}})
                EXPECT_TRUE(pixelIs(x0 + dx, y0 + dy, gbl::kIblFigureTileBackdrop)) << "row " << i << " column " << c;
            EXPECT_FALSE(pixelIs(x0 + tile / 2, y0 + tile / 2, gbl::kIblFigureTileBackdrop)) << "row " << i << " column " << c;
        }
    EXPECT_NE(slurp(scratch() / "fig" / "report.html").find(fig["png"].get<std::string>()), std::string::npos);
}

TEST(Cli, UnknownFlagsAndCommandsAreExplained) {
    RunResult r = run("render --sise 64x64");
    expectOneLineError(r, {"--sise", "--size"});
    r = run("rendr");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("unknown command 'rendr'"), std::string::npos);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    r = run("render --help");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("--scene"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Failures are loud (issue 13): exit codes, special files, strict flags, interruption, locking.

// gbufferlab started in the background in scratch(), stdout/stderr to <name>.out/.err.
struct Background {
    pid_t pid = -1;
    std::string name;
    Background(const std::string& runName, const std::vector<std::string>& args) : name(runName) {
        pid = ::fork();
        if (pid == 0) {
            if (::chdir(scratch().c_str()) != 0) ::_exit(120);
            const int out = ::open((name + ".out").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            const int err = ::open((name + ".err").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            ::dup2(out, 1);
            ::dup2(err, 2);
            std::vector<char*> argv{const_cast<char*>(GBL_BINARY)};
            for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
            argv.push_back(nullptr);
            ::execv(GBL_BINARY, argv.data());
            ::_exit(121);
        }
    }
    int wait() {
        int status = 0;
        ::waitpid(pid, &status, 0);
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    std::string err() const { return slurp(scratch() / (name + ".err")); }
};

// Waits up to `seconds` for `pred`; false on time-out.
template <class Pred>
bool waitFor(Pred&& pred, double seconds) {
    for (int i = 0; i < int(seconds * 50); ++i) {
        if (pred()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
}

std::vector<std::string> temporariesUnder(const fs::path& dir) {
    std::vector<std::string> found;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.path().filename().string().find(".tmp") != std::string::npos) found.push_back(e.path().string());
    return found;
}

TEST(Cli, CompareExitsNonZeroWhenARunFailsAndStillReportsIt) {
    // A file named "runs" where compare makes its runs/ folder: every layout's images fail to write.
    fs::create_directories(scratch() / "cmp-fail");
    { std::ofstream(scratch() / "cmp-fail" / "runs") << "in the way"; }
    const RunResult r = run("compare --scene builtin --out cmp-fail --force --size 64x32 --layouts crysis3-thin,ue4");
    EXPECT_EQ(r.exitCode, 4) << r.err;
    EXPECT_NE(r.err.find("2 of 2 runs failed"), std::string::npos) << r.err;
    const nlohmann::json report = scratch.json("cmp-fail/report.json");
    ASSERT_EQ(report["runs"].size(), 2u);
    for (const auto& run : report["runs"]) {
        EXPECT_EQ(run["status"], "failed");
        EXPECT_NE(run["error"].get<std::string>().find("runs"), std::string::npos) << run["error"];
    }
    EXPECT_FALSE(fs::exists(scratch() / "cmp-fail" / "INCOMPLETE"));
}

TEST(Cli, DirectoriesAndFifosWhereFilesBelongAreOneLine) {
    fs::create_directories(scratch() / "adir.toml");
    RunResult r = run("layouts check adir.toml");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE((r.out + r.err).find("adir.toml: is a directory, not a file; give the path of a file\n"),
              std::string::npos) << r.out << r.err;
    EXPECT_EQ((r.out + r.err).find("bad_alloc"), std::string::npos);
    fs::remove(scratch() / "fifo.toml");
    ASSERT_EQ(::mkfifo((scratch() / "fifo.toml").c_str(), 0600), 0);
    r = run("layouts check fifo.toml", "timeout 60");  // a read would block forever
    EXPECT_NE(r.exitCode, 124) << "hung on a FIFO";
    EXPECT_NE((r.out + r.err).find("is not a regular file"), std::string::npos) << r.out << r.err;
    r = run("compare --scene builtin --out fifo-out --size 32x32 --layouts ./fifo.toml", "timeout 60");
    expectOneLineError(r, {"fifo.toml", "is not a regular file"});
    fs::remove(scratch() / "fifo.hdr");
    ASSERT_EQ(::mkfifo((scratch() / "fifo.hdr").c_str(), 0600), 0);
    r = run("render --out fifo-env --size 32x32 --env fifo.hdr", "timeout 60");
    expectOneLineError(r, {"fifo.hdr", "is not a regular file"});
    fs::create_directories(scratch() / "scene-dir.gltf");
    r = run("render --out dir-scene --size 32x32 --scene scene-dir.gltf");
    expectOneLineError(r, {"scene-dir.gltf", "is a directory"});
    EXPECT_FALSE(fs::exists(scratch() / "fifo-out"));
    EXPECT_FALSE(fs::exists(scratch() / "fifo-env"));
}

TEST(Cli, FlagsAreStrict) {
    RunResult r = run("render --out --force --size 32x32");
    expectOneLineError(r, {"--out needs a value", "followed by the flag --force"});
    EXPECT_FALSE(fs::exists(scratch() / "--force"));
    r = run("render --size 64x64 --size 32x32 --out twice");
    expectOneLineError(r, {"--size is given twice"});
    for (const std::string bad : {"--layouts ,", "--layouts ''", "--layouts all,ue4", "--layouts ue4,,ryse",
                                  "--ibl ,split-sum"}) {
        r = run("compare --scene builtin --out strict --size 32x32 " + bad);
        expectOneLineError(r, {bad.substr(0, bad.find(' '))});
        EXPECT_FALSE(fs::exists(scratch() / "strict")) << bad;
    }
    r = run("\"$(printf 'bad\\ncommand')\"");  // a newline in the command name
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("unknown command 'bad\\ncommand'"), std::string::npos) << r.err;
}

// SIGINT / SIGTERM mid-compare: exit 130 / 143, no temporary left, the folder marked INCOMPLETE
// with a report of the runs that finished.
TEST(Cli, InterruptedCompareLeavesAMarkedFolderWithAReportOfFinishedRuns) {
    for (const int signal : {SIGINT, SIGTERM}) {
        const std::string name = signal == SIGINT ? "int" : "term";
        const fs::path out = scratch() / ("interrupted-" + name);
        // 640x360: each run takes long enough (hundreds of ms on lavapipe) that the signal lands
        // mid-compare even on a loaded machine, not after the last run.
        Background b(name, {"compare", "--scene", "builtin", "--out", out.string(), "--size", "640x360", "--layouts", "all"});
        // Wait for the second layout's run folder: at least one run has finished by then.
        size_t started = 0;
        waitFor([&] {
            std::error_code ec;
            started = 0;
            if (fs::exists(out / "runs", ec))
                for ([[maybe_unused]] const auto& e : fs::directory_iterator(out / "runs", ec)) ++started;
            return started >= 2;
        }, 120);
        ASSERT_GE(started, 2u) << b.err();
        ::kill(b.pid, signal);
        const int code = b.wait();
        EXPECT_EQ(code, 128 + signal) << b.err();
        EXPECT_TRUE(temporariesUnder(out).empty()) << temporariesUnder(out)[0];
        const std::string marker = slurp(out / "INCOMPLETE");
        EXPECT_NE(marker.find(std::string("interrupted by ") + (signal == SIGINT ? "SIGINT" : "SIGTERM")),
                  std::string::npos) << marker;
        const nlohmann::json report = nlohmann::json::parse(slurp(out / "report.json"));
        EXPECT_GE(report["runs"].size(), 1u);
        EXPECT_LT(report["runs"].size(), 6u);
        EXPECT_NE(report["run"]["notes"].dump().find("INCOMPLETE"), std::string::npos);
        EXPECT_TRUE(fs::exists(out / "report.html"));
        // It says so to programs, and its verdict speaks only of the layouts that ran: it named no
        // signal and claimed "no layout fits 12 B/px" of 12 B/px layouts that never ran.
        const std::string signalText = signal == SIGINT ? "SIGINT" : "SIGTERM";
        EXPECT_EQ(report.value("status", ""), "interrupted");
        ASSERT_TRUE(report.contains("interruption")) << "no interruption in report.json";
        EXPECT_EQ(report["interruption"]["signal"], signalText);
        EXPECT_GE(report["interruption"]["not_run"].size(), 1u);
        EXPECT_NE(slurp(out / "report.csv").find(",interrupted by " + signalText + "\n"), std::string::npos);
        if (report.contains("verdict"))
            for (const auto& b : report["verdict"]["budgets"])
                EXPECT_EQ(b["sentence"].get<std::string>().find("no layout fits"), std::string::npos) << b["sentence"];
        // The images are written in the background; the runs the report lists had theirs
        // queued, and the interruption writes them before the report.
        for (const auto& r : report["runs"])
            for (const char* key : {"render", "render_exr", "errors_exr"})
                if (r["status"] == "ok") {
                    EXPECT_TRUE(fs::exists(out / r["images"][key].get<std::string>())) << r["images"][key];
                }
    }
}

// A suite interrupted by a signal wrote no top report and left INCOMPLETE without the signal,
// though docs/compare.md promised it: the top report of the scenes that finished is written, says
// it is interrupted and which scenes did not finish, and INCOMPLETE names the signal.
TEST(Cli, InterruptedSuiteWritesTheTopReportOfTheScenesThatFinished) {
    // Two scenes: the built-in one under its sky, one view; then under a small grey environment of
    // its own, 16 cameras: long enough for the signal to land in it.
    gbl::Image grey(64, 32, 3);
    for (float& v : grey.pixels) v = 0.5f;
    gbl::writeExr((scratch() / "grey.exr").string(), grey);
    {
        std::ofstream suite(scratch() / "suite-int.toml");
        suite << "[[scene]]\ngltf = \"builtin\"\nname = \"sky\"\n[[scene]]\ngltf = \"builtin\"\nname = \"grey\"\n"
                 "environment = \"grey.exr\"\n";
        for (int c = 0; c < 16; ++c)
            suite << "[[scene.camera]]\nposition = [" << std::sin(c * 0.39) * 4.0 << ", 1.5, " << std::cos(c * 0.39) * 4.0
                  << "]\ntarget = [0.0, 0.5, 0.0]\n";
    }
    const fs::path out = scratch() / "suite-interrupted";
    Background b("suite-int", {"compare", "--scene", "suite-int.toml", "--out", out.string(), "--size", "96x54",
                               "--views", "1", "--layouts", "ue4,crysis3-thin,ryse,niagara"});
    // The second scene has begun (its folder exists): the first one has finished.
    ASSERT_TRUE(waitFor([&] { return fs::exists(out / "scenes/grey"); }, 300)) << b.err();
    ::kill(b.pid, SIGINT);
    EXPECT_EQ(b.wait(), 130) << b.err();
    const std::string marker = slurp(out / "INCOMPLETE");
    EXPECT_NE(marker.find("interrupted by SIGINT"), std::string::npos) << marker;
    ASSERT_TRUE(fs::exists(out / "report.json"));
    const nlohmann::json top = nlohmann::json::parse(slurp(out / "report.json"));
    EXPECT_EQ(top["schema"], "gbufferlab-scene-suite");
    EXPECT_EQ(top.value("status", ""), "interrupted");
    ASSERT_TRUE(top.contains("interruption")) << "no interruption in report.json";
    EXPECT_EQ(top["interruption"]["signal"], "SIGINT");
    EXPECT_EQ(top["interruption"]["scenes_planned"], 2);
    ASSERT_EQ(top["scenes"].size(), 1u);
    EXPECT_EQ(top["scenes"][0]["name"], "sky");
    EXPECT_EQ(top["interruption"]["not_finished"], nlohmann::json::array({"grey"}));
    EXPECT_NE(slurp(out / "report.html").find("interrupted by SIGINT"), std::string::npos);
    EXPECT_TRUE(temporariesUnder(out).empty());
}

// Two runs into one --out: the second is refused (even with --force) while the first runs, and
// the first's report is its own.
TEST(Cli, SecondRunIntoTheSameOutputIsRefused) {
    const fs::path out = scratch() / "locked";
    // Large enough that the first is still running while the second and the render are tried.
    Background first("first", {"compare", "--scene", "builtin", "--out", out.string(), "--size", "640x360", "--layouts", "ue4,ryse"});
    ASSERT_TRUE(waitFor([&] { return fs::exists(out / "INCOMPLETE"); }, 120)) << first.err();
    const RunResult second = run("compare --scene builtin --out locked --force --size 64x32 --layouts crysis3-thin");
    expectOneLineError(second, {"--out", "another gbufferlab run is writing into this directory"});
    const RunResult render = run("render --out locked --force --size 32x32");
    expectOneLineError(render, {"another gbufferlab run"});
    EXPECT_EQ(first.wait(), 0) << first.err();
    const nlohmann::json report = nlohmann::json::parse(slurp(out / "report.json"));
    ASSERT_EQ(report["runs"].size(), 2u);
    EXPECT_EQ(report["runs"][0]["layout"], "ue4");
    EXPECT_FALSE(fs::exists(out / "reference.exr")) << "the refused render wrote into the folder";
}

// glTF URIs outside the scene's folder are refused unless --allow-outside-scene.
TEST(Cli, SceneUrisOutsideTheSceneFolderNeedAFlag) {
    const fs::path box = "/usr/share/assimp/models/glTF2/BoxTextured-glTF";
    if (!fs::exists(box / "BoxTextured.gltf")) GTEST_SKIP() << "assimp-testmodels not installed";
    fs::create_directories(scratch() / "scene");
    fs::copy_file(box / "BoxTextured0.bin", scratch() / "outside.bin", fs::copy_options::overwrite_existing);
    fs::copy_file(box / "CesiumLogoFlat.png", scratch() / "scene" / "CesiumLogoFlat.png",
                  fs::copy_options::overwrite_existing);
    std::string text = slurp(box / "BoxTextured.gltf");
    text.replace(text.find("BoxTextured0.bin"), 16, "../outside.bin");
    { std::ofstream(scratch() / "scene" / "box.gltf") << text; }
    RunResult r = run("render --out outside1 --size 32x32 --scene scene/box.gltf");
    expectOneLineError(r, {"box.gltf", "../outside.bin'", "outside the scene's folder", "--allow-outside-scene"});
    EXPECT_FALSE(fs::exists(scratch() / "outside1"));
    r = run("render --out outside2 --size 32x32 --scene scene/box.gltf --allow-outside-scene");
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

}  // namespace
