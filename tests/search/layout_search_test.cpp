// The search: deterministic for a seed (whatever the thread count), resumable from its journal to
// the same result as an uninterrupted run, its front a true Pareto front, its rank correlation right.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "error.h"
#include "layout.h"
#include "layout_search.h"
#include "search_journal.h"
#include "search_test_scene.h"

namespace gbl::search {
namespace {

namespace fs = std::filesystem;

const FastEvaluator& evaluator() {
    static const FastEvaluator e({test::syntheticView(40, 28, 0.0f), test::syntheticView(40, 28, 1.2f)},
                                 test::syntheticLights(), test::syntheticIbl(), Objective::Flip);
    return e;
}

EvaluateFn evaluateFn() {
    return [](const std::string& text) { return evaluator().evaluate(parseLayout(text, "candidate.toml")); };
}

fs::path scratch(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("gbl-search-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

SearchOptions options(int candidates, uint64_t seed = 5) {
    SearchOptions o;
    o.budgetBytes = 12;
    o.seed = seed;
    o.candidates = candidates;
    o.batch = 4;
    o.threads = 2;
    o.journalKey = "test";
    return o;
}

void expectSameRun(const SearchResult& a, const SearchResult& b) {
    ASSERT_EQ(a.evaluated.size(), b.evaluated.size());
    for (size_t i = 0; i < a.evaluated.size(); ++i) {
        EXPECT_EQ(a.evaluated[i].body, b.evaluated[i].body) << i;
        // Bit-identical scores, not merely close.
        EXPECT_EQ(std::memcmp(&a.evaluated[i].eval.error, &b.evaluated[i].eval.error, sizeof(double)), 0) << i;
        EXPECT_EQ(a.evaluated[i].eval.psnr, b.evaluated[i].eval.psnr) << i;
    }
    EXPECT_EQ(a.front, b.front);
}

TEST(LayoutSearch, SameSeedSameFrontWhateverTheThreads) {
    SearchOptions o1 = options(24), o2 = options(24);
    o1.threads = 1;
    o2.threads = 2;
    const SearchResult a = runSearch(evaluateFn(), o1), b = runSearch(evaluateFn(), o2);
    expectSameRun(a, b);
    EXPECT_FALSE(a.front.empty());
    EXPECT_EQ(a.rejectedByValidation, 0);
    for (const Candidate& c : a.evaluated) EXPECT_LE(c.bytes, 12);
    // Another seed explores elsewhere.
    const SearchResult c = runSearch(evaluateFn(), options(24, 6));
    EXPECT_NE(a.evaluated.front().body, c.evaluated.front().body);
}

TEST(LayoutSearch, InterruptedThenResumedEqualsUninterrupted) {
    const fs::path dirA = scratch("a"), dirB = scratch("b");
    SearchOptions whole = options(20);
    whole.journalPath = (dirA / "journal.tsv").string();
    const SearchResult uninterrupted = runSearch(evaluateFn(), whole);

    // Interrupted: the evaluation fails after 9 candidates (mid-batch), as a signal would stop it.
    SearchOptions part = options(20);
    part.journalPath = (dirB / "journal.tsv").string();
    std::atomic<int> calls{0};
    const EvaluateFn failing = [&](const std::string& text) {
        if (++calls > 9) throw std::runtime_error("interrupted");
        return evaluateFn()(text);
    };
    EXPECT_THROW(runSearch(failing, part), std::runtime_error);
    // A torn last line, as a crash mid-write leaves.
    { std::ofstream(part.journalPath, std::ios::app) << "9\t00ab"; }
    const size_t journaled = Journal(part.journalPath, "test").entries().size();
    EXPECT_GE(journaled, 4u);
    EXPECT_LT(journaled, 20u);

    std::atomic<int> evaluatedAfterResume{0};
    const EvaluateFn counting = [&](const std::string& text) {
        ++evaluatedAfterResume;
        return evaluateFn()(text);
    };
    const SearchResult resumed = runSearch(counting, part);
    EXPECT_EQ(resumed.resumed, int(journaled));
    EXPECT_EQ(evaluatedAfterResume.load(), 20 - int(journaled));
    expectSameRun(uninterrupted, resumed);
    // The journals end byte-identical.
    std::ifstream a(whole.journalPath), b(part.journalPath);
    const std::string ja((std::istreambuf_iterator<char>(a)), {}), jb((std::istreambuf_iterator<char>(b)), {});
    EXPECT_EQ(ja, jb);
    fs::remove_all(dirA);
    fs::remove_all(dirB);
}

TEST(LayoutSearch, AJournalOfOtherArgumentsIsRefusedWithItsFileName) {
    const fs::path dir = scratch("key");
    SearchOptions o = options(4);
    o.journalPath = (dir / "journal.tsv").string();
    runSearch(evaluateFn(), o);
    o.journalKey = "other";
    try {
        runSearch(evaluateFn(), o);
        FAIL() << "expected a UserError";
    } catch (const UserError& e) {
        EXPECT_NE(std::string(e.what()).find("journal.tsv:1:"), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
    fs::remove_all(dir);
}

// Each way a journal can fail to be this search's is said as what it is: an empty or CRLF file
// was reported as "a search with other arguments".
TEST(LayoutSearch, AJournalsProblemIsNamedForWhatItIs) {
    const fs::path dir = scratch("journal-text");
    const std::string key = "budget=12 scene=built-in size=32x18 seed=1";
    const std::pair<std::string, std::string> cases[] = {
        {"", "the journal is empty"},
        {"gbufferlab-search-journal 2\tbudget=12 scene=built-in size=32x18 seed=1\r\n", "Windows line endings (CRLF)"},
        {"gbufferlab-search-journal 2\tbudget=12", "first line is cut off"},
        {"hello\n", "not a gbufferlab search journal"},
        {"gbufferlab-search-journal 1\tbudget=12 scene=built-in size=32x18 seed=1\n", "older gbufferlab"},
        {"gbufferlab-search-journal 2\tbudget=16 scene=built-in size=32x18 seed=1\n", "budget=16, not budget=12"},
        {"gbufferlab-search-journal 2\tbudget=12 scene=built-in size=64x36 seed=1\n", "size=64x36, not size=32x18"},
    };
    for (const auto& [text, needle] : cases) {
        SCOPED_TRACE(needle);
        const fs::path path = dir / "journal.tsv";
        { std::ofstream(path, std::ios::binary | std::ios::trunc) << text; }
        try {
            Journal journal(path, key);
            FAIL() << "expected a UserError";
        } catch (const UserError& e) {
            const std::string m = e.what();
            EXPECT_EQ(m.rfind(path.string() + ":1: ", 0), 0u) << m;
            EXPECT_NE(m.find(needle), std::string::npos) << m;
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
            if (needle.find(", not ") == std::string::npos) {
                EXPECT_EQ(m.find("other arguments"), std::string::npos) << m;
            }
        }
        std::ifstream in(path, std::ios::binary);
        EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()), text)
            << "a refused journal is left as it was";
    }
    fs::remove_all(dir);
}

// A resumed search trusted any number its journal held: a line whose score or FLIP was nan, inf
// or negative stood in for an evaluation, and the resumed front picked the tampered candidate.
// Every numeric column of a line, tampered, is now "malformed" with file:line, as a bad index or
// hash is; the untampered journal resumes to the uninterrupted front.
TEST(LayoutSearch, AJournalLineWithANumberNoEvaluationGivesIsMalformed) {
    const fs::path dir = scratch("tampered");
    SearchOptions o = options(8);
    o.journalKey = "budget=12 objective=flip seed=5";
    o.journalPath = (dir / "journal.tsv").string();
    const SearchResult whole = runSearch(evaluateFn(), o);
    std::ifstream in(o.journalPath, std::ios::binary);
    const std::string journal((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t lineStart = journal.find('\n') + 1;  // the first candidate's line: line 2
    const size_t lineEnd = journal.find('\n', lineStart);
    std::vector<std::string> columns;
    {
        std::istringstream line(journal.substr(lineStart, lineEnd - lineStart));
        for (std::string c; std::getline(line, c, '\t');) columns.push_back(c);
    }
    ASSERT_EQ(columns.size(), 14u);
    // A line as written resumes (the journal of this very search).
    EXPECT_EQ(Journal(o.journalPath, o.journalKey).entries().size(), 8u);
    const char* names[] = {"index", "hash", "bytes", "score", "flip", "psnr", "attributes", "normal",
                           "base colour", "diffuse colour", "specular colour", "roughness", "metallic", "occlusion"};
    std::vector<std::pair<size_t, std::string>> tampers;
    for (size_t c = 0; c < 14; ++c)
        for (const std::string bad : {"nan", "inf", "-inf", "-0x1p-4", "-1", "1e999", "", "0x1p+10", "1.5"})
            tampers.push_back({c, bad});
    tampers.push_back({4, "0x1.8p+0"});   // FLIP 1.5: FLIP is at most 1
    tampers.push_back({7, "0x1.7p+7"});   // a normal error of 184 degrees
    tampers.push_back({3, columns[4] == "0x0p+0" ? "0x1p-4" : "0x0p+0"});  // a score that is not the FLIP
    tampers.push_back({1, "-000000000000001"});  // 16 characters, not 16 hex digits
    for (const auto& [column, bad] : tampers) {
        std::vector<std::string> tampered = columns;
        if (tampered[column] == bad) continue;  // the value as written
        // Values some column may legitimately hold: skip them where they are valid.
        if (column >= 5 && column != 7 && (bad == "0x1p+10" || bad == "1.5")) continue;  // errors >= 0, unbounded
        if (column == 7 && bad == "1.5") continue;                                          // 1.5 degrees
        if (column == 2 && bad == "1.5") {}                                                 // bytes: whole only
        tampered[column] = bad;
        std::string line;
        for (size_t k = 0; k < tampered.size(); ++k) line += (k ? "\t" : "") + tampered[k];
        const std::string text = journal.substr(0, lineStart) + line + journal.substr(lineEnd);
        { std::ofstream(o.journalPath, std::ios::binary | std::ios::trunc) << text; }
        SCOPED_TRACE(std::string(names[column]) + " = '" + bad + "'");
        try {
            Journal journalRead(o.journalPath, o.journalKey);
            ADD_FAILURE() << "accepted";
        } catch (const UserError& e) {
            const std::string m = e.what();
            EXPECT_EQ(m.rfind(o.journalPath + ":2: malformed journal line", 0), 0u) << m;
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        }
    }
    // Untampered again: the resumed search is the uninterrupted one.
    { std::ofstream(o.journalPath, std::ios::binary | std::ios::trunc) << journal; }
    const SearchResult resumed = runSearch(evaluateFn(), o);
    EXPECT_EQ(resumed.resumed, 8);
    expectSameRun(whole, resumed);
    fs::remove_all(dir);
}

// The Pareto front over every metric against a brute force: search_constraints_test.cpp.

TEST(LayoutSearch, SpearmanAgainstHandComputedValues) {
    EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {10, 20, 30, 40}), 1.0);
    EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0);
    // Ranks (1,2,3,4,5) vs (2,1,4,3,5): d^2 sum 4, rho = 1 - 6*4/(5*24) = 0.8.
    EXPECT_NEAR(spearman({1, 2, 3, 4, 5}, {0.2, 0.1, 0.4, 0.3, 0.5}), 0.8, 1e-12);
}

}  // namespace
}  // namespace gbl::search
