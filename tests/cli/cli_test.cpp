// The gbufferlab binary on bad input: one clear line naming the file or flag, a non-zero
// exit, no output directory or partial file, never a crash. Runs the real executable.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {

struct RunResult {
    int exitCode;
    std::string out;
    std::string err;
};

fs::path scratch() {
    static fs::path dir = [] {
        fs::path d = fs::temp_directory_path() / ("gbl_cli_test_" + std::to_string(::getpid()));
        fs::remove_all(d);
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

RunResult run(const std::string& args, const std::string& envPrefix = "") {
    const fs::path out = scratch() / "stdout.txt", err = scratch() / "stderr.txt";
    const std::string cmd = "cd " + scratch().string() + " && " + envPrefix + " " + GBL_BINARY + " " + args + " >" +
                            out.string() + " 2>" + err.string();
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), slurp(out), slurp(err)};
}

size_t lineCount(const std::string& s) {
    size_t n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

// A user error: exit 1, exactly one line on stderr containing every `needle`.
void expectOneLineError(const RunResult& r, std::initializer_list<std::string> needles) {
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    for (const auto& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "missing '" << n << "' in: " << r.err;
}

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

TEST(Cli, RenderWritesExrAndPng) {
    const RunResult r = run("render --out ok --size 96x54");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::file_size(scratch() / "ok" / "reference.exr") > 96 * 54);
    const std::string png = slurp(scratch() / "ok" / "reference.png");
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(Cli, CompareReportsEveryRunAndTimesItsStages) {
    RunResult r = run("compare --out cmp --size 96x64 --layouts ue4,crysis3-thin");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json report = nlohmann::json::parse(slurp(scratch() / "cmp" / "report.json"));
    ASSERT_EQ(report["runs"].size(), 2u);
    for (const auto& run : report["runs"]) {
        EXPECT_TRUE(run["image_errors"].contains("flip_mean")) << run["layout"];
        EXPECT_FALSE(run["image_errors"].contains("hdr_flip_mean")) << "HDR-FLIP is opt-in";
    }
    // The stages are exclusive: they add up to the total, and the frames' own GPU time is known.
    const nlohmann::json t = nlohmann::json::parse(slurp(scratch() / "cmp" / "timings.json"));
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

    r = run("compare --out cmp-hdr --size 96x64 --layouts crysis3-thin --hdr-flip");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json hdr = nlohmann::json::parse(slurp(scratch() / "cmp-hdr" / "report.json"));
    const auto& errors = hdr["runs"][0]["image_errors"];
    ASSERT_TRUE(errors.contains("hdr_flip_mean"));
    EXPECT_GT(errors["hdr_flip_mean"].get<double>(), 0.0);  // crysis3-thin loses visible colour
    EXPECT_GE(errors["hdr_flip_exposures"].get<int>(), 2);

    r = run("compare --out cmp-both --size 96x64 --hdr-flip --no-hdr-flip");
    expectOneLineError(r, {"--hdr-flip", "--no-hdr-flip"});
    EXPECT_FALSE(fs::exists(scratch() / "cmp-both"));
}

TEST(Cli, UnknownFlagsAndCommandsAreExplained) {
    RunResult r = run("render --sise 64x64");
    expectOneLineError(r, {"--sise", "--size"});
    r = run("rendr");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("unknown command 'rendr'"), std::string::npos);
    r = run("render --help");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("--scene"), std::string::npos);
}

}  // namespace
