// compare on the glTF sample models with material layers (issue 40, "Measured"): the layer
// attribute errors and the image errors per layer class reach report.json, report.csv,
// report.html and the console with plausible values; a layout that drops the clear coat (ue4)
// shows a coat error equal to the reference's coat amount (ClearcoatWicker's clearcoatFactor is
// 1 with no texture: 1 on every coated pixel); a scene without layers writes none of their keys
// or columns. Tiny frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "test_paths.h"

namespace fs = std::filesystem;
using Json = nlohmann::json;
using namespace gbl::test;

namespace {

const CliScratch scratch("gbl_compare_layers_test_");

const Json& runOf(const Json& report, const std::string& layout) {
    for (const Json& r : report["runs"])
        if (r["layout"] == layout) return r;
    static const Json none;
    ADD_FAILURE() << "no run of " << layout;
    return none;
}

std::string header(const fs::path& csv) {
    const std::string text = slurp(csv);
    return text.substr(0, text.find('\n'));
}

}  // namespace

TEST(CompareLayers, ClearcoatWickerMeasuresTheCoatAndUe4LosesIt) {
    const fs::path scene = sharedAssets() / "models/ClearcoatWicker/ClearcoatWicker.gltf";
    const RunResult r = runGbufferlab(
        scratch(), "compare --scene " + scene.string() + " --layouts ue4,reference --size 96x54 --views 1 --out cw");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    const Json report = scratch.json("cw/report.json");
    const Json& ue4 = runOf(report, "ue4");
    const Json& attrs = ue4["attribute_errors"];
    ASSERT_TRUE(attrs.contains("coat")) << attrs.dump();
    EXPECT_EQ(attrs["coat"]["over"], "coated");
    EXPECT_EQ(attrs["coat"]["unit"], "absolute");
    EXPECT_GT(attrs["coat"]["all"]["count"].get<double>(), 500.0);
    EXPECT_NEAR(attrs["coat"]["all"]["mean"].get<double>(), 1.0, 1e-6);  // the reference's coat amount
    EXPECT_NEAR(attrs["coat"]["all"]["max"].get<double>(), 1.0, 1e-6);
    EXPECT_NEAR(attrs["coat_roughness"]["all"]["mean"].get<double>(), 0.1, 1e-6);  // clearcoatRoughnessFactor
    // The coat normal map against the base normal: some degrees, under 90.
    const double coatNormal = attrs["coat_normal"]["all"]["mean"];
    EXPECT_GT(coatNormal, 0.5);
    EXPECT_LT(coatNormal, 90.0);
    EXPECT_FALSE(attrs.contains("sheen_color"));  // no pixel carries a sheen: absent, not 0
    EXPECT_FALSE(attrs.contains("anisotropy_strength"));
    const Json& classes = ue4["image_errors"]["by_class"];
    ASSERT_TRUE(classes.contains("coated"));
    EXPECT_GT(classes["coated"]["flip_mean"].get<double>(), 0.0);
    EXPECT_LT(classes["coated"]["flip_mean"].get<double>(), 1.0);
    EXPECT_EQ(classes["coated"]["pixels"], attrs["coat"]["all"]["count"]);
    EXPECT_FALSE(classes.contains("sheen"));
    // The reference against itself: every layer error 0.
    const Json& reference = runOf(report, "reference");
    EXPECT_EQ(reference["attribute_errors"]["coat"]["all"]["max"].get<double>(), 0.0);
    EXPECT_EQ(reference["attribute_errors"]["coat_normal"]["all"]["max"].get<double>(), 0.0);
    // Ranked within the class.
    ASSERT_TRUE(report.contains("significance_by_class"));
    ASSERT_TRUE(report["significance_by_class"].contains("coated"));
    EXPECT_EQ(report["significance_by_class"]["coated"]["ranks"].size(), 2u);
    // The CSV's layer columns, the HTML section, the console's table.
    const std::string csvHeader = header(scratch() / "cw/report.csv");
    EXPECT_NE(csvHeader.find(",coat_all_mean_abs,"), std::string::npos) << csvHeader;
    EXPECT_NE(csvHeader.find(",image_coated_flip_mean,"), std::string::npos);
    EXPECT_NE(slurp(scratch() / "cw/report.html").find("id=\"layers\""), std::string::npos);
    EXPECT_NE(r.out.find("Material layers"), std::string::npos) << r.out;
}

TEST(CompareLayers, SheenAndAnisotropyModels) {
    struct Case {
        const char* model;
        const char* attribute;  // measured, with a plausible positive error for ue4
        const char* cls;
    } cases[] = {{"SheenChair", "sheen_color", "sheen"}, {"AnisotropyStrengthTest", "anisotropy_strength", "anisotropic"}};
    for (const Case& c : cases) {
        const fs::path scene = sharedAssets() / "models" / c.model / (std::string(c.model) + ".gltf");
        const RunResult r = runGbufferlab(scratch(), "compare --scene " + scene.string() +
                                                         " --layouts ue4 --size 96x54 --views 1 --out " + c.model);
        ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
        const Json report = scratch.json(fs::path(c.model) / "report.json");
        const Json& ue4 = runOf(report, "ue4");
        ASSERT_TRUE(ue4["attribute_errors"].contains(c.attribute)) << c.model;
        EXPECT_EQ(ue4["attribute_errors"][c.attribute]["over"], c.cls);
        const double mean = ue4["attribute_errors"][c.attribute]["all"]["mean"];
        EXPECT_GT(mean, 0.0) << c.model;
        EXPECT_TRUE(ue4["image_errors"]["by_class"].contains(c.cls)) << c.model;
        EXPECT_TRUE(ue4["image_errors"]["by_class"].contains("plain")) << c.model;  // the wood, the label
        EXPECT_FALSE(ue4["attribute_errors"].contains("coat")) << c.model;
    }
}

TEST(CompareLayers, ASceneWithoutLayersWritesNoneOfTheirKeys) {
    const RunResult r = runGbufferlab(scratch(), "compare --scene builtin --layouts ue4 --size 64x36 --views 1 --out plain");
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    const std::string json = slurp(scratch() / "plain/report.json");
    for (const char* key : {"\"coat", "\"sheen", "\"anisotropy", "\"coated\"", "\"plain\"", "\"over\"",
                            "significance_by_class"})
        EXPECT_EQ(json.find(key), std::string::npos) << key;
    const std::string csvHeader = header(scratch() / "plain/report.csv");
    EXPECT_EQ(csvHeader.find("coat"), std::string::npos);
    EXPECT_EQ(csvHeader.find("image_plain"), std::string::npos);
    EXPECT_EQ(slurp(scratch() / "plain/report.html").find("id=\"layers\""), std::string::npos);
    EXPECT_EQ(r.out.find("Material layers"), std::string::npos);
}

// The device evaluator, whole frames and in bands, measures the layers as the CPU path does
// (gpu_evaluator.h's tolerances: float angles 1e-4 relative, quantiles from histograms).
TEST(CompareLayers, DeviceEvaluatorWholeAndInBandsAgreesWithTheCpu) {
    const fs::path scene = sharedAssets() / "models/ClearcoatWicker/ClearcoatWicker.gltf";
    const std::string common = "compare --scene " + scene.string() + " --layouts ue4 --size 96x54 --views 1 ";
    for (const char* run : {"cpu", "gpu", "bands"}) {
        const std::string flags = std::string(run) == "cpu"   ? "--eval cpu"
                                  : std::string(run) == "gpu" ? "--eval gpu"
                                                              : "--eval gpu --band-rows 16";
        const RunResult r = runGbufferlab(scratch(), common + flags + " --out eval_" + run);
        ASSERT_EQ(r.exitCode, 0) << run << r.out << r.err;
    }
    const Json cpu = runOf(scratch.json("eval_cpu/report.json"), "ue4");
    for (const char* run : {"gpu", "bands"}) {
        const Json g = runOf(scratch.json(std::string("eval_") + run + "/report.json"), "ue4");
        for (const char* a : {"coat", "coat_roughness", "coat_normal"}) {
            const Json& ca = cpu["attribute_errors"][a]["all"];
            const Json& ga = g["attribute_errors"][a]["all"];
            EXPECT_EQ(ga["count"], ca["count"]) << run << " " << a;
            const double c = ca["mean"], v = ga["mean"];
            EXPECT_NEAR(v, c, 1e-4 * std::max(1.0, c)) << run << " " << a;
        }
        const Json& cc = cpu["image_errors"]["by_class"]["coated"];
        const Json& gc = g["image_errors"]["by_class"]["coated"];
        EXPECT_EQ(gc["pixels"], cc["pixels"]) << run;
        EXPECT_NEAR(gc["flip_mean"].get<double>(), cc["flip_mean"].get<double>(), 1e-4) << run;
        EXPECT_NEAR(gc["rmse_linear"].get<double>(), cc["rmse_linear"].get<double>(),
                    1e-9 * cc["rmse_linear"].get<double>())
            << run;
    }
}
