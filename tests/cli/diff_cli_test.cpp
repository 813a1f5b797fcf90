// `gbufferlab diff` (src/measure/image_diff.h, src/cli/cmd_diff.cpp) on files, run as the real executable:
// its RMSE / PSNR / max against an independent computation here, its FLIP against the library's,
// bad input as one clear line naming the file, and -- the point of it -- the numbers in
// report.json recomputed from the files `compare` writes (render.png, render.exr).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

#include "flip.h"
#include "image_io.h"

namespace fs = std::filesystem;

namespace {

using namespace gbl::test;

const CliScratch scratch("gbl_diff_test_");

RunResult run(const std::string& args, const std::string& envPrefix = "") { return scratch.run(args, envPrefix); }

gbl::Image8 pattern8(int w, int h, int channels, int seed) {
    gbl::Image8 img{w, h, channels, std::vector<unsigned char>(size_t(w) * h * channels)};
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = (unsigned char)((i * 37 + seed * (i % 7)) % 256);
    return img;
}

gbl::Image patternHdr(int w, int h, int seed) {
    gbl::Image img(w, h, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        img.pixels[i] = float(std::exp2(double((i * 13 + seed * (i % 5)) % 40) / 4.0 - 4.0));
    return img;
}

double num(const nlohmann::json& j) { return j.is_string() ? INFINITY : j.get<double>(); }

}  // namespace

// LDR: RMSE, PSNR (peak 1) and max over the RGB values / 255, computed here; FLIP = flipLdr.
TEST(Diff, LdrNumbersAreIndependentlyRight) {
    const gbl::Image8 a = pattern8(40, 30, 3, 1), b = pattern8(40, 30, 3, 3);
    gbl::writePng((scratch() / "a.png").string(), a);
    gbl::writePng((scratch() / "b.png").string(), b);
    const RunResult r = run("diff a.png b.png --json --out map.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    double se = 0.0, mx = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        const double d = (double(b.pixels[i]) - double(a.pixels[i])) / 255.0;
        se += d * d;
        mx = std::max(mx, std::abs(d));
    }
    const double rmse = std::sqrt(se / double(a.pixels.size()));
    EXPECT_NEAR(j["rmse"].get<double>(), rmse, 1e-6 * rmse);
    EXPECT_NEAR(j["psnr_db"].get<double>(), -20.0 * std::log10(rmse), 1e-5);
    EXPECT_NEAR(j["max_abs"].get<double>(), mx, 1e-6);
    gbl::Image fa(40, 30, 3), fb(40, 30, 3);
    for (size_t i = 0; i < a.pixels.size(); ++i) fa.pixels[i] = float(a.pixels[i]) / 255.0f, fb.pixels[i] = float(b.pixels[i]) / 255.0f;
    EXPECT_DOUBLE_EQ(j["flip_mean"].get<double>(), gbl::flipStats(gbl::flipLdr(fa, fb)).mean);
    EXPECT_EQ(j["kind"], "ldr");
    const gbl::Image8 map = gbl::readImage8((scratch() / "map.png").string());
    EXPECT_EQ(map.width, 40);
    EXPECT_EQ(map.height, 30);
    // Identical images: PSNR "inf", FLIP 0.
    const RunResult same = run("diff a.png a.png --json");
    ASSERT_EQ(same.exitCode, 0) << same.err;
    const auto js = nlohmann::json::parse(same.out);
    EXPECT_EQ(js["psnr_db"], "inf");
    EXPECT_EQ(js["flip_mean"].get<double>(), 0.0);
}

// HDR: PSNR with the reference's maximum as peak; HDR-FLIP with the given exposures equals
// flipHdr with that range; the map as a 1-channel float EXR.
TEST(Diff, HdrNumbersAndExposureFlags) {
    const gbl::Image a = patternHdr(32, 24, 1), b = patternHdr(32, 24, 2);
    gbl::writeExr((scratch() / "a.exr").string(), a);
    gbl::writeExr((scratch() / "b.exr").string(), b);
    const RunResult r = run("diff a.exr b.exr --json --start-exposure -2.5 --stop-exposure 1.5 --out map.exr");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    double se = 0.0, peak = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        se += double(b.pixels[i] - a.pixels[i]) * double(b.pixels[i] - a.pixels[i]);
        peak = std::max(peak, double(a.pixels[i]));
    }
    const double mse = se / double(a.pixels.size());
    EXPECT_NEAR(j["psnr_db"].get<double>(), 10.0 * std::log10(peak * peak / mse), 1e-6);
    EXPECT_NEAR(j["rmse"].get<double>(), std::sqrt(mse), 1e-6 * std::sqrt(mse));
    EXPECT_EQ(j["num_exposures"].get<int>(), 4);  // max(2, ceil(1.5 - -2.5)), as NVIDIA's tool
    const gbl::HdrFlipResult h = gbl::flipHdr(a, b, gbl::flipPixelsPerDegree(), {-2.5f, 1.5f, 4});
    EXPECT_DOUBLE_EQ(j["flip_mean"].get<double>(), gbl::flipStats(h.flip).mean);
    const gbl::Image map = gbl::readExrChannels((scratch() / "map.exr").string(), {"Y"});
    EXPECT_EQ(map.pixels, h.flip.pixels);
}

TEST(Diff, BadInputIsOneLineNamingTheFile) {
    gbl::writePng((scratch() / "rgb.png").string(), pattern8(16, 16, 3, 1));
    gbl::writePng((scratch() / "rgba.png").string(), pattern8(16, 16, 4, 1));
    gbl::writePng((scratch() / "small.png").string(), pattern8(8, 16, 3, 1));
    gbl::writeExr((scratch() / "rgb.exr").string(), patternHdr(16, 16, 1));
    { std::ofstream(scratch() / "garbage.png") << "not a png"; }
    { std::ofstream(scratch() / "existing.png") << "user data"; }
    expectOneLineError(run("diff rgb.png small.png"), {"small.png", "8x16", "16x16"});
    expectOneLineError(run("diff rgb.png rgba.png"), {"rgba.png", "channels"});
    expectOneLineError(run("diff rgb.png rgb.exr"), {"rgb.exr", "like with like"});
    expectOneLineError(run("diff rgb.png garbage.png"), {"garbage.png"});
    expectOneLineError(run("diff rgb.png missing.png"), {"missing.png"});
    expectOneLineError(run("diff rgb.png rgb.tiff"), {"rgb.tiff"});
    expectOneLineError(run("diff rgb.png"), {"two images"});
    expectOneLineError(run("diff rgb.png rgb.png --start-exposure 1 --stop-exposure 2"), {"exposure"});
    expectOneLineError(run("diff rgb.exr rgb.exr --start-exposure 1"), {"--stop-exposure"});
    // Never overwrite the user's file without --force; no map from a failed diff.
    expectOneLineError(run("diff rgb.png rgb.png --out existing.png"), {"existing.png", "--force"});
    EXPECT_EQ(slurp(scratch() / "existing.png"), "user data");
    expectOneLineError(run("diff rgb.png small.png --out nomap.png"), {"small.png"});
    EXPECT_FALSE(fs::exists(scratch() / "nomap.png"));
}

// report.json's image errors are what `gbufferlab diff` computes from the files compare wrote:
// LDR-FLIP, tone-mapped PSNR and RMSE from the PNGs; HDR-FLIP, linear PSNR and RMSE from the EXRs
// (with several views, the default: the first view's numbers, whose files compare writes).
// With --float32-exr (the metrics are computed on the 32-bit float renders), --eval cpu (the
// oracle) reproduces them exactly; --eval gpu within the tolerances
// src/evaluate/gpu_evaluator.h states (FLIP means 1e-4; an 8-bit value may be one step apart).
TEST(Diff, ReportNumbersAreReproducibleFromWrittenFiles) {
    std::map<std::string, nlohmann::json> reports;
    for (const std::string eval : {"cpu", "gpu"}) {
        SCOPED_TRACE("--eval " + eval);
        const bool exact = eval == "cpu";
        const std::string dir = "rep-" + eval + "/";
        const RunResult c = run("compare --scene builtin --size 96x54 --layouts crysis2-slim,ue4 --hdr-flip --float32-exr --eval " + eval +
                              (exact ? " --error-exr" : "") + " --out " + dir);
        ASSERT_EQ(c.exitCode, 0) << c.err;
        const auto& report = reports[eval] = nlohmann::json::parse(slurp(scratch() / dir / "report.json"));
        EXPECT_EQ(report["run"]["exr_precision"], "float32");
        const auto& refImage = report["reference"]["images"][0];
        EXPECT_EQ(gbl::readExrPixelType((scratch() / dir / refImage["render_exr"].get<std::string>()).string()),
                  gbl::ExrPixelType::Float32);
        ASSERT_FALSE(refImage["render_exr"].get<std::string>().empty());
        auto same = [&](double a, double b, double tolerance, const std::string& what) {
            if (exact) EXPECT_DOUBLE_EQ(a, b) << what;
            else EXPECT_NEAR(a, b, tolerance) << what;
        };
        for (const auto& runJson : report["runs"]) {
            // Several views (the default): the files are the first view's, so are these numbers; the
            // run's own image_errors are the mean over the views.
            ASSERT_TRUE(runJson.contains("views")) << runJson["layout"];
            const auto& e = runJson["views"][0]["image_errors"];
            const std::string layout = runJson["layout"];
            RunResult d = run("diff " + dir + refImage["render"].get<std::string>() + " " + dir +
                              runJson["images"]["render"].get<std::string>() + " --json");
            ASSERT_EQ(d.exitCode, 0) << d.err;
            auto j = nlohmann::json::parse(d.out);
            same(num(j["flip_mean"]), num(e["flip_mean"]), 1e-4, layout + " flip");
            same(num(j["psnr_db"]), num(e["psnr_tonemapped_db"]), 0.01, layout + " psnr");
            EXPECT_NEAR(num(j["rmse"]), num(e["rmse_tonemapped"]), exact ? 1e-12 : 1e-3 * num(e["rmse_tonemapped"]));
            d = run("diff " + dir + refImage["render_exr"].get<std::string>() + " " + dir +
                    runJson["images"]["render_exr"].get<std::string>() + " --json");
            ASSERT_EQ(d.exitCode, 0) << d.err;
            j = nlohmann::json::parse(d.out);
            same(num(j["flip_mean"]), num(e["hdr_flip_mean"]), 1e-4, layout + " hdr flip");
            EXPECT_EQ(j["num_exposures"].get<int>(), e["hdr_flip_exposures"].get<int>());
            same(num(j["psnr_db"]), num(e["psnr_linear_db"]), 1e-6, layout + " psnr linear");
            EXPECT_NEAR(num(j["rmse"]), num(e["rmse_linear"]), 1e-9 * num(e["rmse_linear"]));
        }
        // The GPU's float maps stay on the device: no errors.exr; the oracle writes one (--error-exr).
        const std::string errorsExr = report["runs"][0]["images"]["errors_exr"];
        EXPECT_EQ(errorsExr.empty(), !exact);
    }
    // The later views have no files, so against the oracle directly: each view's reference sets
    // the relative luminance error's floor and HDR-FLIP's exposures (once, view 0's were kept on
    // the GPU: 5 exposures fewer and HDR-FLIP 9e-4 off in view 2 at 480x270).
    const auto& cpuRuns = reports["cpu"]["runs"];
    const auto& gpuRuns = reports["gpu"]["runs"];
    ASSERT_EQ(cpuRuns.size(), gpuRuns.size());
    for (size_t r = 0; r < cpuRuns.size(); ++r)
        for (size_t v = 0; v < cpuRuns[r]["views"].size(); ++v) {
            SCOPED_TRACE(cpuRuns[r]["layout"].get<std::string>() + ", view " + std::to_string(v));
            const auto& c = cpuRuns[r]["views"][v]["image_errors"];
            const auto& g = gpuRuns[r]["views"][v]["image_errors"];
            EXPECT_EQ(g["hdr_flip_exposures"].get<int>(), c["hdr_flip_exposures"].get<int>());
            EXPECT_NEAR(num(g["hdr_flip_mean"]), num(c["hdr_flip_mean"]), 1e-4);
            EXPECT_NEAR(num(g["flip_mean"]), num(c["flip_mean"]), 1e-4);
            const double relCpu = num(c["by_class"]["covered"]["rel_luminance_mean"]);
            EXPECT_NEAR(num(g["by_class"]["covered"]["rel_luminance_mean"]), relCpu, 1e-6 * relCpu);
            // The attributes too, as gpu_evaluator_test holds one render (float angles and
            // CIEDE2000 against the oracle's double: means within 1e-4 relative).
            const auto& ca = cpuRuns[r]["views"][v]["attribute_errors"];
            const auto& ga = gpuRuns[r]["views"][v]["attribute_errors"];
            ASSERT_EQ(ga.size(), ca.size());
            for (const auto& [name, attribute] : ca.items()) {
                EXPECT_EQ(ga[name]["all"]["count"], attribute["all"]["count"]) << name;
                const double mean = num(attribute["all"]["mean"]);
                EXPECT_NEAR(num(ga[name]["all"]["mean"]), mean, 1e-4 * mean + 1e-9) << name;
            }
        }
    const RunResult bad = run("compare --scene builtin --size 32x32 --layouts ue4 --eval fpga --out rep-bad");
    expectOneLineError(bad, {"--eval fpga", "auto, gpu or cpu"});
    EXPECT_FALSE(fs::exists(scratch() / "rep-bad"));
}

// errors.exr (a float dump of every per-pixel error, 16 MB a 1080p run) only on request: a default
// run names and writes none, yet every number stays recomputable (the test above); --error-exr
// writes it, and is refused where no float maps exist (the device evaluator, bands).
TEST(Diff, ErrorExrIsWrittenOnlyOnRequest) {
    const RunResult c = run("compare --scene builtin --size 96x54 --layouts ue4 --views 1 --eval cpu --out noerrexr");
    ASSERT_EQ(c.exitCode, 0) << c.err;
    const auto report = scratch.json("noerrexr/report.json");
    EXPECT_EQ(report["runs"][0]["images"]["errors_exr"], "");
    for (const auto& entry : fs::recursive_directory_iterator(scratch() / "noerrexr"))
        EXPECT_NE(entry.path().filename(), "errors.exr") << entry.path();
    ASSERT_FALSE(report["runs"][0]["images"]["render_exr"].get<std::string>().empty());

    const RunResult w = run("compare --scene builtin --size 96x54 --layouts ue4 --views 1 --error-exr --out errexr");
    ASSERT_EQ(w.exitCode, 0) << w.err;
    const auto withExr = scratch.json("errexr/report.json");
    const std::string path = withExr["runs"][0]["images"]["errors_exr"];
    ASSERT_FALSE(path.empty());
    EXPECT_TRUE(fs::is_regular_file(scratch() / "errexr" / path)) << path;
    // The numbers do not depend on it.
    EXPECT_EQ(withExr["runs"][0]["image_errors"].dump(), report["runs"][0]["image_errors"].dump());

    expectOneLineError(run("compare --scene builtin --size 96x54 --layouts ue4 --error-exr --eval gpu --out errexr-gpu"),
                       {"--error-exr", "--eval cpu"});
    expectOneLineError(run("compare --scene builtin --size 96x54 --layouts ue4 --error-exr --band-rows 16 --out errexr-bands"),
                       {"--error-exr", "--band-rows 0"});
    EXPECT_FALSE(fs::exists(scratch() / "errexr-gpu"));
    EXPECT_FALSE(fs::exists(scratch() / "errexr-bands"));
}

// The default half-float EXRs: the report says so, the files are half, and the linear numbers
// recomputed from them stay within what half's rounding allows. Each value read back is within
// 2^-11 of the float one (relative, normal range) or 2^-25 (absolute, subnormal), so by the
// triangle inequality |RMSE(t' - r') - RMSE(t - r)| <= RMSE(t' - t) + RMSE(r' - r)
// <= 2^-11 (RMS(t) + RMS(r)) + 2^-24. PSNR = 20 log10(peak / RMSE) moves with the RMSE and the
// peak (the reference's maximum, also rounded). The PNG numbers do not depend on the EXRs: exact.
TEST(Diff, HalfExrsReproduceTheReportWithinHalfsRounding) {
    const RunResult c = run("compare --scene builtin --size 96x54 --layouts ue4 --views 1 --error-exr --out half");
    ASSERT_EQ(c.exitCode, 0) << c.err;
    const auto report = scratch.json("half/report.json");
    EXPECT_EQ(report["run"]["exr_precision"], "half");
    const std::string refExr = "half/" + report["reference"]["images"][0]["render_exr"].get<std::string>();
    const auto& runJson = report["runs"][0];
    const std::string testExr = "half/" + runJson["images"]["render_exr"].get<std::string>();
    const std::string errorsExr = "half/" + runJson["images"]["errors_exr"].get<std::string>();
    for (const std::string& f : {refExr, testExr, errorsExr})
        EXPECT_EQ(gbl::readExrPixelType((scratch() / f).string()), gbl::ExrPixelType::Half) << f;
    const auto& e = runJson["image_errors"];

    RunResult d = run("diff half/" + report["reference"]["images"][0]["render"].get<std::string>() + " half/" +
                      runJson["images"]["render"].get<std::string>() + " --json");
    ASSERT_EQ(d.exitCode, 0) << d.err;
    auto j = nlohmann::json::parse(d.out);
    EXPECT_DOUBLE_EQ(num(j["psnr_db"]), num(e["psnr_tonemapped_db"]));
    EXPECT_DOUBLE_EQ(num(j["flip_mean"]), num(e["flip_mean"]));

    d = run("diff " + refExr + " " + testExr + " --json");
    ASSERT_EQ(d.exitCode, 0) << d.err;
    j = nlohmann::json::parse(d.out);
    auto rms = [](const gbl::Image& image) {
        double sum = 0.0;
        for (float v : image.pixels) sum += double(v) * v;
        return std::sqrt(sum / double(image.pixels.size()));
    };
    const gbl::Image refHalf = gbl::readExr((scratch() / refExr).string());  // RGB, as diff reads them
    const gbl::Image testHalf = gbl::readExr((scratch() / testExr).string());
    // RMS of the float images, from the half ones: at most 2^-11 (relative) larger.
    const double slack = 1.0 + std::ldexp(1.0, -10);
    const double bound = std::ldexp(1.0, -11) * slack * (rms(refHalf) + rms(testHalf)) + std::ldexp(1.0, -24);
    const double rmseFloat = num(e["rmse_linear"]), rmseHalf = num(j["rmse"]);
    EXPECT_LE(std::fabs(rmseHalf - rmseFloat), bound) << "float " << rmseFloat << ", half " << rmseHalf;
    double peak = 0.0;
    for (float v : refHalf.pixels) peak = std::max(peak, double(v));
    const double peakLo = peak / (1.0 + std::ldexp(1.0, -11)), peakHi = peak / (1.0 - std::ldexp(1.0, -11));
    const double psnrFloat = num(e["psnr_linear_db"]);
    EXPECT_GE(psnrFloat, 20.0 * std::log10(peakLo / (rmseHalf + bound)) - 1e-9);
    if (rmseHalf > bound) {
        EXPECT_LE(psnrFloat, 20.0 * std::log10(peakHi / (rmseHalf - bound)) + 1e-9);
    }
    // The bound is not vacuous here: the run's error is well above half's rounding.
    EXPECT_LT(bound, 0.2 * rmseFloat);
}
