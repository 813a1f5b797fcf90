// compare over several scenes (compare_suite.h): every layout on every scene, each scene's full
// report in scenes/<name>/, the summary across them (mean error, ranks, tied ranks, rank
// agreement) in the top report; the numbers of a scene the same as its single-scene comparison
// (shared pipelines and IBL change nothing); the engine-style exposure recorded and equal to the
// reference's metered again here; a scene that cannot be loaded fails alone (exit 4); a suite that
// names a missing file or a scene twice is refused before anything is rendered. Small frames.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "auto_exposure.h"
#include "cli_runner.h"
#include "image_io.h"
#include "test_paths.h"

namespace fs = std::filesystem;
using Json = nlohmann::json;
using namespace gbl::test;

namespace {

const CliScratch scratch("gbl_compare_scenes_test_");

const Json* runOf(const Json& report, const std::string& layout) {
    for (const Json& r : report["runs"])
        if (r["layout"] == layout) return &r;
    return nullptr;
}

}  // namespace

// The default, no --scene: the built-in scene and the bundled assets (scenes/default-suite.toml)
// as a suite, at whatever --size and --views say; its report leads with the verdict across the
// scenes and their rank agreement in words. Tiny frames, two layouts.
TEST(CompareScenes, WithoutASceneTheBundledSuiteAndItsHeadline) {
    const RunResult r = runGbufferlab(scratch(), "compare --size 64x36 --views 1 --layouts ue4,ue5-nostatic --out default");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("Across 3 scenes"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\nAgreement. "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\nVerdict across the scenes. "), std::string::npos) << r.out;
    const Json top = scratch.json("default/report.json");
    EXPECT_EQ(top["schema"], "gbufferlab-scene-suite");
    EXPECT_EQ(top["run"]["width"], 64);
    ASSERT_EQ(top["scenes"].size(), 3u);
    const char* names[] = {"builtin", "FlightHelmet", "WaterBottle"};
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(top["scenes"][i]["name"], names[i]);
        EXPECT_EQ(top["scenes"][i]["status"], "ok");
        EXPECT_TRUE(fs::exists(scratch() / "default/scenes" / names[i] / "report.html")) << names[i];
    }
    EXPECT_EQ(top["verdict"]["scenes"], 3);
    EXPECT_EQ(top["verdict"]["budgets"].size(), 6u);
    const std::string words = top["rank_agreement"]["in_words"]["sentence"];
    EXPECT_NE(words.find(" agree"), std::string::npos) << words;
    EXPECT_NE(words.find(" at tau "), std::string::npos) << words;
    EXPECT_NE(r.out.find(words), std::string::npos);  // the console prints the same sentence
    EXPECT_EQ(top["rank_agreement"]["pairs"].size(), 3u);
    const std::string html = slurp(scratch() / "default/report.html");
    EXPECT_NE(html.find("Verdict across the scenes"), std::string::npos);
}

TEST(CompareScenes, EveryLayoutOnEveryScene) {
    const fs::path avocado = sharedAssets() / "models/Avocado/Avocado.gltf";
    const fs::path studio = sharedAssets() / "envmaps/studio_small_03_1k.hdr";
    GBL_REQUIRE_FILE(avocado);
    GBL_REQUIRE_FILE(studio);
    const std::string common = " --layouts ue4,crysis3-thin --size 160x90 --views 2 --float32-exr";
    const RunResult r = scratch.run("compare --scene builtin --scene " + avocado.string() + " --env " +
                                                     studio.string() + common + " --out two");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("Across 2 scenes"), std::string::npos) << r.out;
    const Json top = scratch.json("two/report.json");
    EXPECT_EQ(top["schema"], "gbufferlab-scene-suite");
    ASSERT_EQ(top["scenes"].size(), 2u);
    EXPECT_EQ(top["scenes"][0]["name"], "builtin");
    EXPECT_EQ(top["scenes"][1]["name"], "Avocado");
    EXPECT_FALSE(fs::exists(scratch() / "two/INCOMPLETE"));
    for (const char* name : {"builtin", "Avocado"}) {
        EXPECT_TRUE(fs::exists(scratch() / "two/scenes" / name / "report.html")) << name;
        EXPECT_TRUE(fs::exists(scratch() / "two/scenes" / name / "runs/ue4/split-sum/render.png")) << name;
    }
    // The summary is the scenes' numbers: per scene the run's flip_mean, their mean, the ranks.
    const Json& layouts = top["summary"]["layouts"];
    ASSERT_EQ(layouts.size(), 2u);
    for (const Json& row : layouts) {
        double sum = 0;
        int worst = 0;
        for (size_t s = 0; s < 2; ++s) {
            const Json* run = runOf(top["scenes"][s]["report"], row["layout"]);
            ASSERT_TRUE(run);
            EXPECT_EQ(row["per_scene"][s]["error"].get<double>(), (*run)["image_errors"]["flip_mean"].get<double>());
            sum += row["per_scene"][s]["error"].get<double>();
            worst = std::max(worst, row["per_scene"][s]["rank"].get<int>());
            EXPECT_FALSE(row["per_scene"][s]["tied_rank"].get<std::string>().empty());
        }
        EXPECT_DOUBLE_EQ(row["mean_error"].get<double>(), sum / 2);
        EXPECT_EQ(row["worst_rank"].get<int>(), worst);
    }
    // Two scenes, two layouts: one pair of scenes, tau +-1, a swap when it is -1.
    const Json& agreement = top["rank_agreement"]["pairs"];
    ASSERT_EQ(agreement.size(), 1u);
    const double tau = agreement[0]["kendall_tau"].get<double>();
    EXPECT_EQ(std::abs(tau), 1.0);
    EXPECT_EQ(agreement[0]["swapped_pairs"].size(), tau < 0 ? 1u : 0u);

    // Engine-style exposure: recorded per view, and the reference's file meters to it again.
    const Json& avocadoRun = top["scenes"][1]["report"]["run"];
    EXPECT_EQ(avocadoRun["exposure_method"], "ue4-histogram");
    ASSERT_EQ(avocadoRun["view_exposures"].size(), 2u);
    const gbl::Image reference = gbl::readExr((scratch() / "two/scenes/Avocado/reference-split-sum.exr").string());
    EXPECT_DOUBLE_EQ(avocadoRun["exposure"].get<double>(), double(float(gbl::meterExposure(reference).exposure)));
    // Framing: the 6 cm avocado, without a camera of its own, is in both views, at the scale of its
    // bounding sphere (which, fitted to a 16:9 frame's height, covers at most pi/4 x 9/16 = 44% of
    // it; the avocado's silhouette covered 13.5% and 9.8% here, 2026-11-28).
    ASSERT_EQ(avocadoRun["view_coverage"].size(), 2u);
    for (const Json& c : avocadoRun["view_coverage"]) {
        EXPECT_GT(c.get<double>(), 0.05) << avocadoRun.dump();
        EXPECT_LT(c.get<double>(), 0.45) << avocadoRun.dump();
    }

    // One scene alone: the same numbers as in the comparison of two.
    const RunResult alone =
        scratch.run("compare --scene " + avocado.string() + " --env " + studio.string() + common + " --out one");
    ASSERT_EQ(alone.exitCode, 0) << alone.err;
    const Json single = scratch.json("one/report.json");
    EXPECT_EQ(single["schema"], "gbufferlab-report");
    for (const char* layout : {"ue4", "crysis3-thin"})
        EXPECT_EQ((*runOf(single, layout))["image_errors"]["flip_mean"],
                  (*runOf(top["scenes"][1]["report"], layout))["image_errors"]["flip_mean"])
            << layout;
}

TEST(CompareScenes, ASceneThatCannotLoadFailsAlone) {
    fs::create_directories(scratch() / "broken");
    std::ofstream(scratch() / "broken/broken.gltf") << "{ \"asset\": { \"version\": \"2.0\" }, \"buffers\": [ { \"uri\": 7 } ] }";
    std::ofstream(scratch() / "suite.toml") << "[[scene]]\ngltf = \"broken/broken.gltf\"\n[[scene]]\ngltf = \"builtin\"\n";
    const RunResult r = scratch.run("compare --scene suite.toml --layouts ue4 --size 160x90 --views 1 "
                                                 "--exposure 1 --out failed");
    EXPECT_EQ(r.exitCode, 4) << r.out << r.err;
    EXPECT_NE(r.err.find("scene broken"), std::string::npos) << r.err;
    const Json top = scratch.json("failed/report.json");
    EXPECT_EQ(top["scenes"][0]["status"], "failed");
    EXPECT_FALSE(top["scenes"][0]["error"].get<std::string>().empty());
    EXPECT_EQ(top["scenes"][1]["status"], "ok");
    EXPECT_EQ(top["scenes"][1]["report"]["run"]["exposure_method"], "fixed");
    EXPECT_EQ(top["scenes"][1]["report"]["run"]["exposure"].get<double>(), 1.0);
    EXPECT_TRUE(top["summary"]["layouts"][0]["per_scene"][0]["error"].is_null());
    EXPECT_EQ(top["summary"]["layouts"][0]["scenes_measured"], 1);
}

TEST(CompareScenes, BadSuitesAreRefusedBeforeRendering) {
    std::ofstream(scratch() / "missing.toml") << "[[scene]]\ngltf = \"builtin\"\n[[scene]]\ngltf = \"nowhere.gltf\"\n";
    RunResult r = scratch.run("compare --scene missing.toml --layouts ue4 --size 32x32 --out refused");
    expectOneLineError(r, {"missing.toml:4:8:", "no such file"});
    r = scratch.run("compare --scene builtin --scene builtin --layouts ue4 --size 32x32 --out refused");
    expectOneLineError(r, {"given twice"});
    std::ofstream(scratch() / "empty.toml") << "# nothing\n";
    r = scratch.run("compare --scene empty.toml --layouts ue4 --size 32x32 --out refused");
    expectOneLineError(r, {"empty.toml:1:1:", "no scene"});
    EXPECT_FALSE(fs::exists(scratch() / "refused"));
}
