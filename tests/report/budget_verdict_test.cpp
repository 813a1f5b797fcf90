// The verdict per byte budget: which runs count, what a visibility buffer is held against, ties,
// budgets nothing fits, and that report.json carries the same sentences the function wrote.
#include <gtest/gtest.h>

#include "budget_verdict.h"
#include "report_json.h"
#include "report_sample.h"

namespace gbl {
namespace {

// A visibility run: `idBytes` of ids + depth per pixel, `vertexBytes` of modelled vertex fetches
// per pixel in every frame.
RunReport visibilityRun(const std::string& name, int idBytes, double vertexBytes, double flip) {
    RunReport r = test::sampleRun(name, "split-sum", idBytes, flip, 40.0);
    r.pipeline = "visibility-buffer";
    for (FrameTraffic& f : r.bandwidth) f.vertexFetchBytes = double(f.width) * f.height * vertexBytes;
    return r;
}

const BudgetLine& lineFor(const BudgetVerdict& v, std::optional<int> budget) {
    for (const BudgetLine& l : v.lines)
        if (l.budget == budget) return l;
    throw std::runtime_error("no line for that budget");
}

TEST(BudgetVerdict, OneLinePerBudgetBestByMeanFlipAmongThoseThatFit) {
    // split-sum: compact-octahedral 12 B (0.0561), ryse 16 B (0.0710), ue4 20 B (0.0213),
    // fat-naive 44 B (0.0: identical); the failed run and the "none" runs never count.
    const auto v = budgetVerdict(test::sampleReport());
    ASSERT_TRUE(v.has_value());
    EXPECT_EQ(v->iblMode, "split-sum");
    ASSERT_EQ(v->lines.size(), 6u);
    const std::optional<int> budgets[] = {8, 12, 16, 24, 32, std::nullopt};
    for (size_t i = 0; i < 6; ++i) EXPECT_EQ(v->lines[i].budget, budgets[i]);
    const BudgetLine& at8 = lineFor(*v, 8);
    EXPECT_FALSE(at8.best.has_value());
    ASSERT_TRUE(at8.smallest.has_value());
    EXPECT_EQ(at8.smallest->layout, "compact-octahedral");
    EXPECT_EQ(at8.sentence, "Up to 8 B/px: no layout fits; the smallest, compact-octahedral, counts 12 B/px.");
    EXPECT_EQ(lineFor(*v, 12).best->layout, "compact-octahedral");
    // ryse fits 16 but loses to compact-octahedral: more bytes never win on their own.
    EXPECT_EQ(lineFor(*v, 16).best->layout, "compact-octahedral");
    EXPECT_EQ(lineFor(*v, 24).best->layout, "ue4");
    EXPECT_EQ(lineFor(*v, 32).best->layout, "ue4");
    EXPECT_EQ(lineFor(*v, std::nullopt).best->layout, "fat-naive");
    EXPECT_EQ(lineFor(*v, 24).sentence,
              "Up to 24 B/px: ue4 (20 B/px) has the lowest mean FLIP over 1 view, 0.0213.");
    EXPECT_EQ(lineFor(*v, std::nullopt).sentence,
              "Unlimited: fat-naive (44 B/px) has the lowest mean FLIP over 1 view, 0.0000.");
    for (const BudgetLine& l : v->lines) EXPECT_TRUE(l.tiedWith.empty()) << l.sentence;
}

TEST(BudgetVerdict, TheReferenceLightingComparisonsAndOtherModesNeverCount) {
    ReportModel m = test::sampleReport();
    RunReport reference = test::sampleRun(m.reference.layout, "split-sum", 8, 0.0, INFINITY);
    RunReport lighting = test::sampleRun("reference (split-sum vs ground-truth)", "split-sum", 8, 0.0, INFINITY);
    m.runs.push_back(reference);
    m.runs.push_back(lighting);
    m.runs.push_back(test::sampleRun("tiny", "none", 8, 0.001, 50.0));  // a better run under the second mode
    const auto v = budgetVerdict(m);
    ASSERT_TRUE(v.has_value());
    EXPECT_FALSE(lineFor(*v, 8).best.has_value()) << lineFor(*v, 8).sentence;
    // With no measured run under the first mode, the verdict is the next mode's.
    ReportModel onlyNone = test::sampleReport();
    std::erase_if(onlyNone.runs, [](const RunReport& r) { return r.iblMode == "split-sum"; });
    const auto n = budgetVerdict(onlyNone);
    ASSERT_TRUE(n.has_value());
    EXPECT_EQ(n->iblMode, "none");
    EXPECT_EQ(lineFor(*n, 12).best->layout, "compact-octahedral");
    EXPECT_EQ(lineFor(*n, 24).best->layout, "ue4");
    ReportModel failed = test::sampleReport();
    for (RunReport& r : failed.runs) r.status = RunStatus::Failed;
    EXPECT_FALSE(budgetVerdict(failed).has_value());
}

TEST(BudgetVerdict, AVisibilityBufferCountsHalfItsModelledVertexFetches) {
    ReportModel m = test::sampleReport();
    m.runs.push_back(visibilityRun("visibility-32", 8, 156.0, 0.0100));
    const RunReport& vis = m.runs.back();
    EXPECT_DOUBLE_EQ(verdictCountedBytes(vis), 8.0 + 78.0);
    EXPECT_DOUBLE_EQ(verdictCountedBytes(m.runs[0]), 20.0);  // a G-buffer layout: the table's bytes
    const auto v = budgetVerdict(m);
    ASSERT_TRUE(v.has_value());
    // Its 8 B/px of ids would win every budget from 8 up; counted at 86 it fits none but unlimited.
    EXPECT_FALSE(lineFor(*v, 8).best.has_value()) << lineFor(*v, 8).sentence;
    for (int budget : kVerdictBudgets) {
        if (lineFor(*v, budget).best) {
            EXPECT_NE(lineFor(*v, budget).best->layout, "visibility-32") << budget;
        }
    }
    EXPECT_EQ(lineFor(*v, 24).best->layout, "ue4");
    EXPECT_EQ(lineFor(*v, std::nullopt).best->layout, "fat-naive");  // 0.0 beats 0.0100
    m.runs[2].image->flipMean = 0.5;  // fat-naive worse than the visibility buffer
    const auto w = budgetVerdict(m);
    const BudgetLine& unlimited = lineFor(*w, std::nullopt);
    ASSERT_TRUE(unlimited.best.has_value());
    EXPECT_EQ(unlimited.best->layout, "visibility-32");
    EXPECT_TRUE(unlimited.best->visibilityBuffer);
    EXPECT_EQ(unlimited.sentence,
              "Unlimited: visibility-32 (8 B/px of ids and depth, 86 counting its modelled vertex fetches) has the "
              "lowest mean FLIP over 1 view, 0.0100.");
    EXPECT_NE(w->basis.find("half of its resolve's modelled vertex fetches"), std::string::npos) << w->basis;
}

TEST(BudgetVerdict, EqualMeansAreTiesNamedInTheLine) {
    ReportModel m = test::sampleReport();
    m.runs.push_back(test::sampleRun("twin-b", "split-sum", 12, 0.0561, 33.25));
    m.runs.push_back(test::sampleRun("twin-a", "split-sum", 12, 0.0561, 33.25));
    const auto v = budgetVerdict(m);
    const BudgetLine& at12 = lineFor(*v, 12);
    ASSERT_TRUE(at12.best.has_value());
    // Equal bytes: by name, so the line reads the same in every run.
    EXPECT_EQ(at12.best->layout, "compact-octahedral");
    ASSERT_EQ(at12.tiedWith.size(), 2u);
    EXPECT_EQ(at12.tiedWith[0].layout, "twin-a");
    EXPECT_EQ(at12.tiedWith[1].layout, "twin-b");
    EXPECT_EQ(at12.sentence,
              "Up to 12 B/px: compact-octahedral (12 B/px) has the lowest mean FLIP over 1 view, 0.0561, tied with "
              "twin-a (12 B/px) and twin-b (12 B/px).");
    EXPECT_TRUE(lineFor(*v, 24).tiedWith.empty());  // ue4 is better than all three
}

TEST(BudgetVerdict, SaysHowManyViewsTheMeanIsOver) {
    ReportModel m = test::sampleReport();
    m.run.views = {"scene camera", "orbit 120", "orbit 240"};
    for (RunReport& r : m.runs)
        if (r.image) r.views.assign(3, ViewMetrics{r.attributes, r.image});
    const auto v = budgetVerdict(m);
    EXPECT_EQ(v->views, 3);
    EXPECT_NE(lineFor(*v, 12).sentence.find("lowest mean FLIP over 3 views, 0.0561"), std::string::npos)
        << lineFor(*v, 12).sentence;
}

TEST(BudgetVerdict, ReportJsonHoldsTheSameLines) {
    ReportModel m = test::sampleReport();
    m.runs.push_back(visibilityRun("visibility-32", 8, 156.0, 0.0100));
    const auto v = budgetVerdict(m);
    const nlohmann::ordered_json j = reportToJson(m);
    ASSERT_TRUE(j.contains("verdict"));
    const auto& verdict = j["verdict"];
    EXPECT_EQ(verdict["ibl_mode"], "split-sum");
    EXPECT_EQ(verdict["metric"], "flip_mean");
    EXPECT_EQ(verdict["views"], 1);
    EXPECT_EQ(verdict["basis"], v->basis);
    ASSERT_EQ(verdict["budgets"].size(), v->lines.size());
    for (size_t i = 0; i < v->lines.size(); ++i) EXPECT_EQ(verdict["budgets"][i]["sentence"], v->lines[i].sentence);
    EXPECT_EQ(verdict["budgets"][0]["budget_bytes_per_pixel"], 8);
    EXPECT_EQ(verdict["budgets"][5]["budget_bytes_per_pixel"], "inf");  // unlimited, as the schema writes +inf
    EXPECT_FALSE(verdict["budgets"][0].contains("best"));  // nothing fits 8
    EXPECT_EQ(verdict["budgets"][0]["smallest"]["layout"], "compact-octahedral");
    const auto& best24 = verdict["budgets"][3]["best"];
    EXPECT_EQ(best24["layout"], "ue4");
    EXPECT_EQ(best24["bytes_per_pixel"], 20);
    EXPECT_DOUBLE_EQ(best24["counted_bytes_per_pixel"].get<double>(), 20.0);
    EXPECT_DOUBLE_EQ(best24["flip_mean"].get<double>(), 0.0213);
    EXPECT_TRUE(verdict["budgets"][3]["tied_with"].empty());
    // Derived, not read back: a report read and written again holds it unchanged.
    EXPECT_EQ(reportToJson(reportFromJson(j))["verdict"], verdict);
    EXPECT_FALSE(reportToJson(ReportModel{}).contains("verdict"));
}

// The caption said "Differences are not tested for significance yet: a tie is an exactly equal
// mean" beside a Rank column that ties layouts by the sign-flip test: it now says what the lines
// rest on (the mean alone) and where significance is.
TEST(BudgetVerdict, TheBasisSaysWhatTheLinesRestOn) {
    const auto v = budgetVerdict(test::sampleReport());
    ASSERT_TRUE(v.has_value());
    EXPECT_EQ(v->basis.find("not tested for significance yet"), std::string::npos) << v->basis;
    EXPECT_NE(v->basis.find("mean FLIP alone"), std::string::npos) << v->basis;
    EXPECT_NE(v->basis.find("exactly equal mean"), std::string::npos) << v->basis;
    EXPECT_NE(v->basis.find("the Rank column does (the paired sign-flip test"), std::string::npos) << v->basis;
}

// After SIGINT the verdict claimed "no layout fits 12 B/px" when the 12 B/px layouts were asked
// for and never ran: the lines speak only of the layouts that ran and name those that did not.
TEST(BudgetVerdict, AnInterruptedReportNamesTheLayoutsThatDidNotRun) {
    ReportModel m = test::sampleReport();
    std::erase_if(m.runs, [](const RunReport& r) { return r.layout != "ue4" || r.iblMode != "split-sum"; });
    ReportInterruption i;
    i.signal = "SIGINT";
    i.runsFinished = 1;
    i.runsPlanned = 3;
    i.notRun = {{"niagara", "split-sum", 12, 12.0}, {"crysis3-thin", "split-sum", 12, 12.0}};
    m.interruption = i;
    const auto v = budgetVerdict(m);
    ASSERT_TRUE(v.has_value());
    EXPECT_EQ(v->interruptedBy, "SIGINT");
    EXPECT_EQ(lineFor(*v, 8).sentence, "Up to 8 B/px: no layout that ran fits; the smallest, ue4, counts 20 B/px.");
    EXPECT_EQ(lineFor(*v, 12).sentence,
              "Up to 12 B/px: no layout that ran fits; the smallest, ue4, counts 20 B/px; not run (interrupted by "
              "SIGINT): crysis3-thin (12 B/px), niagara (12 B/px).");
    EXPECT_EQ(lineFor(*v, 24).sentence,
              "Up to 24 B/px: ue4 (20 B/px) has the lowest mean FLIP over 1 view, 0.0213; not run (interrupted by "
              "SIGINT): crysis3-thin (12 B/px), niagara (12 B/px).");
    EXPECT_NE(v->basis.find("interrupted by SIGINT after 1 of 3 runs"), std::string::npos) << v->basis;
    for (const BudgetLine& l : v->lines) EXPECT_EQ(l.sentence.find("no layout fits"), std::string::npos) << l.sentence;
    // report.json says so to programs, and reads back to the same verdict.
    const nlohmann::ordered_json j = reportToJson(m);
    EXPECT_EQ(j["status"], "interrupted");
    EXPECT_EQ(j["interruption"]["signal"], "SIGINT");
    EXPECT_EQ(j["interruption"]["runs_finished"], 1);
    EXPECT_EQ(j["interruption"]["runs_planned"], 3);
    ASSERT_EQ(j["interruption"]["not_run"].size(), 2u);
    EXPECT_EQ(j["verdict"]["budgets"][1]["not_run"].size(), 2u);
    EXPECT_EQ(j["verdict"]["budgets"][0].contains("not_run"), false);
    const nlohmann::ordered_json back = reportToJson(reportFromJson(j));
    EXPECT_EQ(back["status"], j["status"]);
    EXPECT_EQ(back["interruption"], j["interruption"]);
    EXPECT_EQ(back["verdict"], j["verdict"]);
    EXPECT_EQ(reportToJson(test::sampleReport())["status"], "complete");
}

}  // namespace
}  // namespace gbl
