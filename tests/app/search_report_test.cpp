// search over several scenes reads its confirmation from compare's report of several scenes
// (schema gbufferlab-scene-suite): each scene's full-render FLIP per layout, and their mean only
// when the layout ran on every scene; the front report then lists both per scene.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "search_front.h"
#include "search_report.h"

namespace fs = std::filesystem;
using namespace gbl;

TEST(SearchReport, ReadsEachScenesConfirmation) {
    const fs::path dir = fs::temp_directory_path() / ("gbl_search_report_test_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    auto run = [](const char* layout, double flip, const char* status = "ok") {
        return nlohmann::json{{"layout", layout}, {"ibl_mode", "split-sum"}, {"status", status},
                              {"image_errors", {{"flip_mean", flip}}}};
    };
    const nlohmann::json report = {
        {"schema", "gbufferlab-scene-suite"},
        {"scenes",
         {{{"name", "builtin"}, {"report", {{"runs", {run("found-9b", 0.02), run("ue4", 0.013)}}}}},
          {{"name", "helmet"}, {"report", {{"runs", {run("found-9b", 0.004), run("ue4", 0.0, "failed")}}}}},
          {{"name", "broken"}, {"report", nullptr}}}}};
    std::ofstream(dir / "report.json") << report.dump();
    std::vector<SearchRow> rows(2);
    rows[0].name = "found-9b";
    rows[1].name = "ue4";
    readConfirmation(dir / "report.json", rows);
    ASSERT_EQ(rows[0].fullFlipPerScene.size(), 3u);
    EXPECT_EQ(*rows[0].fullFlipPerScene[0], 0.02);
    EXPECT_EQ(*rows[0].fullFlipPerScene[1], 0.004);
    EXPECT_FALSE(rows[0].fullFlipPerScene[2]);
    EXPECT_FALSE(rows[0].fullFlip) << "a scene without its run: no mean";
    EXPECT_EQ(*rows[1].fullFlipPerScene[0], 0.013);
    EXPECT_FALSE(rows[1].fullFlipPerScene[1]) << "a failed run has no FLIP";

    // Two scenes, both measured: the mean, and the front report's per-scene table.
    const nlohmann::json two = {{"schema", "gbufferlab-scene-suite"},
                                {"scenes",
                                 {{{"name", "a"}, {"report", {{"runs", {run("found-9b", 0.02)}}}}},
                                  {{"name", "b"}, {"report", {{"runs", {run("found-9b", 0.004)}}}}}}}};
    std::ofstream(dir / "two.json") << two.dump();
    std::vector<SearchRow> one(1);
    one[0].name = "found-9b";
    one[0].found = true;
    one[0].fastPerScene.resize(2);
    one[0].fastPerScene[0].flip = 0.021;
    one[0].fastPerScene[1].flip = 0.005;
    readConfirmation(dir / "two.json", one);
    EXPECT_DOUBLE_EQ(*one[0].fullFlip, 0.012);
    SearchSummary summary;
    summary.sceneNames = {"a", "b"};
    summary.rows = one;
    writeSearchReport(summary, dir);
    std::ifstream in(dir / "search-report.md");
    const std::string md((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(md.find("| found-9b | 0 | 0.02100 / 0.02000 | 0.00500 / 0.00400 |"), std::string::npos) << md;
    fs::remove_all(dir);
}

// Every metric of the confirmation read back from compare's report.json (one scene), the FLIP
// significance of a found layout against its comparator from compare's pairs, and the verdict
// and trade the report and search.json then give.
TEST(SearchReport, ReadsEveryMetricAndTheFlipSignificance) {
    const fs::path dir = fs::temp_directory_path() / ("gbl_search_metrics_test_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    auto attr = [](double mean) { return nlohmann::json{{"unit", "x"}, {"all", {{"mean", mean}}}}; };
    auto run = [&](const char* layout, double flip, nlohmann::json psnr, double normal, double base, double ao) {
        return nlohmann::json{
            {"layout", layout},
            {"ibl_mode", "split-sum"},
            {"status", "ok"},
            {"image_errors", {{"flip_mean", flip}, {"psnr_tonemapped_db", psnr}}},
            {"attribute_errors",
             {{"normal", attr(normal)}, {"base_color", attr(base)}, {"diffuse_color", attr(base)},
              {"specular_color", attr(0.2)}, {"roughness", attr(0.001)}, {"metallic", attr(0.0)},
              {"occlusion", attr(ao)}}}};
    };
    const nlohmann::json report = {
        {"runs",
         {run("found-12b", 0.007, 44.2, 0.1, 0.5, 0.004), run("crysis3-thin", 0.01, 57.2, 0.2, 1.0, 0.0),
          run("ue4", 0.009, "inf", 0.05, 0.3, 0.1)}},
        {"significance",
         {{"pairs",
           {{{"better", "found-12b"}, {"worse", "crysis3-thin"}, {"ibl_mode", "split-sum"}, {"units", 432},
             {"p_value", 0.0002}, {"significant", true}},
            {{"better", "found-12b"}, {"worse", "ue4"}, {"ibl_mode", "split-sum"}, {"units", 432},
             {"p_value", 0.3}, {"significant", false}}}}}}};
    std::ofstream(dir / "report.json") << report.dump();
    std::vector<SearchRow> rows(3);
    rows[0].name = "found-12b";
    rows[0].found = true;
    rows[0].bytes = 12;
    rows[0].comparator = "crysis3-thin";
    rows[0].fast.occlusion = 0.5;  // the full renders' occlusion (0.004) replaces the fast value
    rows[1].name = "crysis3-thin";
    rows[1].bytes = 12;
    rows[2].name = "ue4";
    rows[2].bytes = 25;
    readFullMetrics(dir / "report.json", rows);
    ASSERT_TRUE(rows[0].full && rows[1].full && rows[2].full);
    EXPECT_EQ(rows[0].full->flip, 0.007);
    EXPECT_EQ(rows[0].full->psnr, 44.2);
    EXPECT_EQ(rows[0].full->normalDeg, 0.1);
    EXPECT_EQ(rows[0].full->baseColorDe, 0.5);
    EXPECT_EQ(rows[0].full->specularColorDe, 0.2);
    EXPECT_EQ(rows[0].full->occlusion, 0.004);
    EXPECT_EQ(rows[2].full->occlusion, 0.1);
    EXPECT_TRUE(std::isinf(rows[2].full->psnr));
    ASSERT_TRUE(rows[0].flipPValue);
    EXPECT_EQ(*rows[0].flipPValue, 0.0002) << "the pair with its comparator, not with ue4";
    EXPECT_EQ(rows[0].flipUnits, 432);
    EXPECT_FALSE(rows[1].flipPValue);

    SearchSummary summary;
    summary.objective = "flip";
    summary.rows = rows;
    const std::string note = writeSearchReport(summary, dir);
    // FLIP -30 %, PSNR -13 dB (the example), normal and colours halved, occlusion from 0.
    EXPECT_NE(note.find("found-12b vs crysis3-thin (12 B/px): trade (FLIP -30 %, PSNR -13.0 dB, normal -50 %, "
                        "base ΔE -50 %, diffuse ΔE -50 %, occlusion +0.0040); FLIP difference p = 0.0002 [full renders]"),
              std::string::npos)
        << note;
    EXPECT_NE(note.find("at 12 B/px: no found layout is no worse than crysis3-thin (12 B/px) on every metric"),
              std::string::npos)
        << note;
    std::ifstream in(dir / "search.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["layouts"][0]["verdict"], "trade");
    EXPECT_EQ(j["layouts"][0]["flip_p_value"], 0.0002);
    EXPECT_EQ(j["layouts"][2]["full_metrics"]["psnr_db"], "inf");

    // Comparators: the best published by the objective within the same or the next larger budget.
    std::vector<SearchRow> published(4);
    const std::pair<const char*, int> pub[] = {{"crysis3-thin", 12}, {"niagara", 12}, {"ryse", 16}, {"compact", 16}};
    const double score[] = {0.04, 0.1, 0.012, 0.010};
    for (size_t i = 0; i < 4; ++i) {
        published[i].name = pub[i].first;
        published[i].bytes = pub[i].second;
        published[i].fast.error = score[i];
    }
    EXPECT_EQ(comparatorFor(8, published)->name, "crysis3-thin");
    EXPECT_EQ(comparatorFor(12, published)->name, "crysis3-thin");
    EXPECT_EQ(comparatorFor(13, published)->name, "compact");
    EXPECT_EQ(comparatorFor(16, published)->name, "compact");
    EXPECT_EQ(comparatorFor(17, published), nullptr);
    fs::remove_all(dir);
}
