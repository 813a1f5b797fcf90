// search over several scenes reads its confirmation from compare's report of several scenes
// (schema gbufferlab-scene-suite): each scene's full-render FLIP per layout, and their mean only
// when the layout ran on every scene; the front report then lists both per scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

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
