// The headline of a comparison over several scenes (suite_verdict.h): the verdict per byte budget
// across the scenes, and how far the scenes agree in words, with the layouts that move most. Six
// layouts on three scenes whose taus were worked out by hand: the built-in scene against the two
// assets 0.33 and 0.20, the assets with each other 0.87.
#include <gtest/gtest.h>

#include <map>

#include <nlohmann/json.hpp>

#include "report_html.h"
#include "report_sample.h"
#include "suite_report.h"
#include "suite_verdict.h"

namespace gbl {
namespace {

using Flips = std::map<std::string, double>;

SuiteScene sceneOf(const std::string& name, bool builtin, const Flips& flips) {
    SuiteScene s;
    s.name = name;
    s.builtin = builtin;
    s.scene = builtin ? "built-in default scene" : name + ".gltf";
    ReportModel m;
    m.run.iblModes = {"split-sum"};
    const std::map<std::string, int> bytes = {{"a", 8}, {"b", 12}, {"c", 16}, {"d", 20}, {"e", 24}, {"f", 32}};
    for (const auto& [layout, flip] : flips) m.runs.push_back(test::sampleRun(layout, "split-sum", bytes.at(layout), flip, 40.0));
    s.report = m;
    return s;
}

// Ranks: builtin b d e a c f; helmet a b c d e f; bottle a b c d f e.
SuiteModel threeScenes() {
    SuiteModel m;
    m.run.iblModes = {"split-sum"};
    m.scenes.push_back(sceneOf("builtin", true, {{"a", .04}, {"b", .01}, {"c", .05}, {"d", .02}, {"e", .03}, {"f", .06}}));
    m.scenes.push_back(sceneOf("helmet", false, {{"a", .01}, {"b", .02}, {"c", .03}, {"d", .04}, {"e", .05}, {"f", .06}}));
    m.scenes.push_back(sceneOf("bottle", false, {{"a", .011}, {"b", .021}, {"c", .031}, {"d", .041}, {"e", .061}, {"f", .051}}));
    summariseSuite(m);
    return m;
}

TEST(SuiteVerdict, TheSceneApartIsNamedWithItsTausAndWhatTheyMean) {
    const SuiteModel m = threeScenes();
    ASSERT_EQ(m.agreement.size(), 3u);
    const auto w = suiteAgreementWords(m);
    ASSERT_TRUE(w.has_value());
    EXPECT_EQ(w->iblMode, "split-sum");
    EXPECT_NEAR(w->meanTau, (1.0 / 3 + 0.2 + 13.0 / 15) / 3, 1e-12);
    EXPECT_EQ(w->sentence,
              "The built-in scene agrees with the assets at tau 0.33 (helmet) and 0.20 (bottle): rankings depend on "
              "content. The assets agree with each other at tau 0.87: the ranking holds across them. The verdict "
              "across the scenes is their mean: read the ranking of the scene nearest your content beside it.");
    // Spreads a 3, e 3, d 2, c 2, b 1, f 1; among equals the summary's order (by mean rank).
    ASSERT_EQ(w->moves.size(), size_t(kMovesListed));
    EXPECT_EQ(w->moves[0].layout, "a");
    EXPECT_EQ(w->moves[0].spread, 3);
    EXPECT_EQ(w->moves[1].layout, "e");
    EXPECT_EQ(w->moves[2].layout, "d");
    EXPECT_EQ(w->moves[3].layout, "c");
    EXPECT_EQ(w->movesSentence,
              "Largest moves (rank by FLIP among 6 layouts): a 1st on helmet and bottle, 4th on the built-in scene; "
              "e 3rd on the built-in scene, 5th on helmet, 6th on bottle; d 2nd on the built-in scene, 4th on "
              "helmet and bottle; c 3rd on helmet and bottle, 5th on the built-in scene.");
}

TEST(SuiteVerdict, ScenesThatAgreeOrTwoScenesReadSo) {
    SuiteModel m = threeScenes();
    // The built-in scene ranked as helmet: every tau 0.87 or 1, no scene apart.
    m.scenes[0] = sceneOf("builtin", true, {{"a", .01}, {"b", .02}, {"c", .03}, {"d", .04}, {"e", .05}, {"f", .06}});
    summariseSuite(m);
    EXPECT_EQ(suiteAgreementWords(m)->sentence,
              "The 3 scenes agree at tau 0.87-1.00 (mean 0.91): the ranking holds across them.");
    m.scenes.pop_back();  // builtin and helmet, ranked alike
    summariseSuite(m);
    EXPECT_EQ(suiteAgreementWords(m)->sentence, "The built-in scene and helmet agree at tau 1.00: the ranking holds across them.");
    EXPECT_TRUE(suiteAgreementWords(m)->movesSentence.empty());
    m.scenes.pop_back();  // one scene: nothing to agree on, no verdict across scenes
    summariseSuite(m);
    EXPECT_FALSE(suiteAgreementWords(m).has_value());
    EXPECT_FALSE(suiteBudgetVerdict(m).has_value());
    EXPECT_EQ(agreementMeaning(0.5), "the rankings agree in broad lines but swap some layouts");
    EXPECT_EQ(ordinal(11), "11th");
    EXPECT_EQ(ordinal(22), "22nd");
    EXPECT_EQ(ordinal(103), "103rd");
}

// Per budget, the lowest FLIP averaged over the scenes among the layouts measured on every scene:
// means a 0.0203, b 0.0170, d 0.0337, c 0.0370, e 0.0470, f 0.0570.
TEST(SuiteVerdict, TheVerdictAcrossTheScenesAveragesTheirFlip) {
    SuiteModel m = threeScenes();
    const auto v = suiteBudgetVerdict(m);
    ASSERT_TRUE(v.has_value());
    EXPECT_EQ(v->scenes, 3);
    ASSERT_EQ(v->lines.size(), 6u);
    EXPECT_EQ(v->lines[0].sentence, "Up to 8 B/px: a (8 B/px) has the lowest mean FLIP over 3 scenes, 0.0203.");
    EXPECT_EQ(v->lines[1].sentence, "Up to 12 B/px: b (12 B/px) has the lowest mean FLIP over 3 scenes, 0.0170.");
    EXPECT_EQ(v->lines[5].best->layout, "b");
    // b failed on one scene: no longer in the verdict (measured on every scene or not at all).
    m.scenes[2].report->runs[1].status = RunStatus::Failed;
    summariseSuite(m);
    EXPECT_EQ(suiteBudgetVerdict(m)->lines[5].best->layout, "a");
    EXPECT_EQ(suiteBudgetVerdict(m)->lines[1].best->layout, "a");
}

// report.json and report.html of the top folder carry the same sentences.
TEST(SuiteVerdict, ReportJsonAndHtmlCarryTheHeadline) {
    const SuiteModel m = threeScenes();
    const nlohmann::ordered_json j = suiteToJson(m);
    ASSERT_TRUE(j.contains("verdict"));
    EXPECT_EQ(j["verdict"]["scenes"], 3);
    EXPECT_FALSE(j["verdict"].contains("views"));
    EXPECT_EQ(j["verdict"]["budgets"][0]["sentence"], suiteBudgetVerdict(m)->lines[0].sentence);
    const auto& words = j["rank_agreement"]["in_words"];
    EXPECT_EQ(words["sentence"], suiteAgreementWords(m)->sentence);
    EXPECT_EQ(words["moves_sentence"], suiteAgreementWords(m)->movesSentence);
    EXPECT_EQ(words["largest_moves"][0]["layout"], "a");
    EXPECT_EQ(words["largest_moves"][0]["rank_per_scene"]["builtin"], 4);
    EXPECT_EQ(words["largest_moves"][0]["spread"], 3);
    const std::string html = suiteHtml(m);
    EXPECT_NE(html.find("Verdict across the scenes"), std::string::npos);
    EXPECT_NE(html.find(htmlEscape(suiteAgreementWords(m)->sentence)), std::string::npos);
    EXPECT_NE(html.find(htmlEscape(suiteBudgetVerdict(m)->lines[1].sentence)), std::string::npos);
}

}  // namespace
}  // namespace gbl
