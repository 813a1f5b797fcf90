// The comparison and the search as library calls (app/compare_api.h, app/search_api.h): run in
// this process, no command line, no process spawned; tiny sizes, for a 2-core CI.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "compare_api.h"
#include "search_api.h"

namespace gbl {
namespace {

namespace fs = std::filesystem;

// This process's scratch folder, removed when the tests end.
const fs::path& scratchRoot() {
    static const struct Root {
        fs::path path = fs::temp_directory_path() / ("gbl_app_api_test_" + std::to_string(::getpid()));
        ~Root() {
            std::error_code ec;
            fs::remove_all(path, ec);
        }
    } root;
    return root.path;
}

fs::path scratch(const std::string& name) {
    const fs::path dir = scratchRoot() / name;
    fs::remove_all(dir);
    fs::create_directories(dir.parent_path());
    return dir;
}

nlohmann::json readJson(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return nlohmann::json::parse(text.str());
}

// What a run told its caller.
struct RecordingSink : ProgressSink {
    int total = 0;
    std::vector<std::string> begun, ended, notes, statuses, errors;
    void started(int totalSteps) override { total = totalSteps; }
    void stepBegin(int, int, const std::string& what) override { begun.push_back(what); }
    void stepEnd(int, int, const std::string& result) override { ended.push_back(result); }
    void note(const std::string& line) override { notes.push_back(line); }
    void status(const std::string& line) override { statuses.push_back(line); }
    void error(const std::string& line) override { errors.push_back(line); }
};

// The reference layout itself and a lossy one, at 64x36, one view, split-sum.
compare::CompareOptions tinyComparison(const fs::path& out) {
    compare::CompareOptions o;
    o.layoutsSpec = "reference,crysis3-thin";
    o.width = 64;
    o.height = 36;
    o.viewCount = 1;
    o.outDir = out;
    return o;
}

const RunReport& runOf(const ReportModel& model, const std::string& layout) {
    for (const RunReport& r : model.runs)
        if (r.layout == layout) return r;
    throw std::runtime_error("no run of " + layout);
}

TEST(AppApi, ComparisonReturnsTheReportItWrote) {
    const fs::path out = scratch("compare");
    RecordingSink sink;
    std::vector<app::CompareResult> reports;
    app::RunControl control;
    control.progress = &sink;
    control.onReport = [&](const app::CompareResult& r) { reports.push_back(r); };
    const app::CompareResult result = app::runComparison(tinyComparison(out), control);

    EXPECT_EQ(result.exitStatus, 0);
    EXPECT_FALSE(result.interrupted());
    ASSERT_TRUE(result.report.has_value());
    EXPECT_FALSE(result.suite.has_value());
    ASSERT_EQ(result.report->runs.size(), 2u);
    // The reference against itself loses nothing; Crysis 3's thin G-buffer (specular luminance
    // only, 12 B/px) does.
    const RunReport& self = runOf(*result.report, "reference");
    const RunReport& thin = runOf(*result.report, "crysis3-thin");
    ASSERT_EQ(self.status, RunStatus::Ok);
    ASSERT_EQ(thin.status, RunStatus::Ok);
    ASSERT_TRUE(self.image && thin.image);
    EXPECT_EQ(self.image->flipMean, 0.0);
    EXPECT_GT(thin.image->flipMean, 0.0);
    EXPECT_LT(thin.bytesPerPixel.total, self.bytesPerPixel.total);
    EXPECT_FALSE(result.report->interruption.has_value());

    // The files are the model's: report.json holds the same numbers; the folder is complete.
    const nlohmann::json json = readJson(out / "report.json");
    ASSERT_EQ(json.at("runs").size(), 2u);
    for (const nlohmann::json& run : json.at("runs"))
        EXPECT_EQ(run.at("image_errors").at("flip_mean").get<double>(),
                  runOf(*result.report, run.at("layout").get<std::string>()).image->flipMean);
    EXPECT_FALSE(fs::exists(out / "INCOMPLETE"));
    EXPECT_TRUE(fs::exists(out / "timings.json"));
    ASSERT_TRUE(result.timings.has_value());
    EXPECT_GT(result.timings->stages.totalMs, 0.0);

    // Progress: one step per reference and run, each begun and ended; one report heard.
    EXPECT_EQ(sink.total, 3);
    EXPECT_EQ(sink.begun.size(), 3u);
    EXPECT_EQ(sink.ended.size(), 3u);
    EXPECT_TRUE(sink.errors.empty());
    ASSERT_EQ(reports.size(), 1u);
    EXPECT_EQ(reports[0].report->runs.size(), 2u);
}

TEST(AppApi, ComparisonCancelledBeforeItStartsWritesNothing) {
    const fs::path out = scratch("compare-cancelled-early");
    CancelToken cancel;
    cancel.cancel(SIGINT);
    app::RunControl control;
    control.cancel = &cancel;
    const app::CompareResult result = app::runComparison(tinyComparison(out), control);
    EXPECT_TRUE(result.interrupted());
    EXPECT_EQ(result.interruptedBy, SIGINT);
    EXPECT_EQ(result.exitStatus, 128 + SIGINT);
    EXPECT_FALSE(result.report.has_value());
    EXPECT_FALSE(fs::exists(out));
}

// Asked to stop as the second layout's run begins: the report of the runs that finished (the
// first layout's), the folder left marked INCOMPLETE, as SIGINT leaves it on the command line.
TEST(AppApi, ComparisonCancelledMidwayWritesThePartialReport) {
    const fs::path out = scratch("compare-cancelled");
    CancelToken cancel;
    struct CancellingSink : RecordingSink {
        CancelToken* token = nullptr;
        void stepBegin(int step, int steps, const std::string& what) override {
            RecordingSink::stepBegin(step, steps, what);
            if (step == 3) token->cancel(SIGTERM);  // 1: the reference; 2, 3: the layouts
        }
    } sink;
    sink.token = &cancel;
    bool reported = false;
    app::RunControl control;
    control.progress = &sink;
    control.cancel = &cancel;
    control.onReport = [&](const app::CompareResult&) { reported = true; };
    const app::CompareResult result = app::runComparison(tinyComparison(out), control);

    EXPECT_EQ(result.interruptedBy, SIGTERM);
    EXPECT_EQ(result.exitStatus, 128 + SIGTERM);
    EXPECT_FALSE(reported);  // a partial report is no finished one
    EXPECT_EQ(sink.begun.size(), 3u);  // the run begun goes on; none starts after it
    ASSERT_TRUE(result.report.has_value());
    ASSERT_TRUE(result.report->interruption.has_value());
    EXPECT_EQ(result.report->interruption->signal, "SIGTERM");
    EXPECT_EQ(result.report->interruption->runsFinished, 1);
    EXPECT_EQ(result.report->interruption->runsPlanned, 2);
    ASSERT_EQ(result.report->interruption->notRun.size(), 1u);
    EXPECT_EQ(result.report->runs.size(), 1u);
    EXPECT_TRUE(fs::exists(out / "INCOMPLETE"));
    const nlohmann::json json = readJson(out / "report.json");
    EXPECT_EQ(json.at("runs").size(), 1u);
    EXPECT_TRUE(json.contains("interruption"));
}

app::SearchOptions tinySearch(const fs::path& out) {
    app::SearchOptions o;
    o.budget = 12;
    o.width = 64;
    o.height = 36;
    o.viewCount = 1;
    o.candidates = 16;
    o.seed = 1;
    o.confirm = false;
    o.outDir = out;
    return o;
}

TEST(AppApi, SearchReturnsItsFront) {
    const fs::path out = scratch("search");
    RecordingSink sink;
    app::RunControl control;
    control.progress = &sink;
    const app::SearchResult result = app::runSearch(tinySearch(out), control);

    EXPECT_EQ(result.exitStatus, 0);
    EXPECT_FALSE(result.interrupted());
    EXPECT_FALSE(result.confirmation.has_value());
    EXPECT_EQ(result.summary.candidates, 16);
    // The front: non-empty, within the budget, by bytes ascending.
    const std::vector<search::Candidate>& front = result.summary.front;
    ASSERT_FALSE(front.empty());
    for (size_t i = 0; i < front.size(); ++i) {
        EXPECT_LE(front[i].bytes, 12);
        if (i > 0) {
            EXPECT_LE(front[i - 1].bytes, front[i].bytes);
        }
    }
    // Its chosen layouts written as files, beside the published layouts.
    ASSERT_GT(result.layoutsWritten(), 0);
    for (const SearchRow& row : result.summary.rows) {
        if (!row.found) continue;
        EXPECT_TRUE(fs::exists(row.file)) << row.file;
        EXPECT_LE(row.bytes, 12);
    }
    EXPECT_TRUE(fs::exists(out / "search-report.md"));
    EXPECT_TRUE(fs::exists(out / "search-journal.tsv"));
    EXPECT_FALSE(result.closingNote.empty());
    EXPECT_FALSE(sink.notes.empty());     // "search: rendering the reference ..."
    EXPECT_FALSE(sink.statuses.empty());  // "search: 8/16 candidates ..."
}

TEST(AppApi, SearchCancelledBeforeItStartsWritesNothing) {
    const fs::path out = scratch("search-cancelled");
    CancelToken cancel;
    cancel.cancel(SIGINT);
    app::RunControl control;
    control.cancel = &cancel;
    const app::SearchResult result = app::runSearch(tinySearch(out), control);
    EXPECT_EQ(result.interruptedBy, SIGINT);
    EXPECT_EQ(result.exitStatus, 128 + SIGINT);
    EXPECT_TRUE(result.summary.front.empty());
    EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace gbl
