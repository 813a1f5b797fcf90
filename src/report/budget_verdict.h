#pragma once
// The report's conclusion in one line per byte budget (8, 12, 16, 24, 32 B/px and unlimited):
// the layout with the lowest mean FLIP among those that fit. Written at the top of report.html,
// into report.json ("verdict") and after compare's console table, from this one function, so
// the three cannot disagree.
//
// What "fits" means is stated in BudgetVerdict::basis and here: a run counts the table's bytes
// per pixel (targets + depth + light buffers); a visibility buffer adds half of its resolve's
// modelled vertex fetches per pixel (src/measure/bandwidth.h, no cache reuse). Half, because the
// bandwidth model moves a stored byte twice (written by the geometry pass, read by the lighting
// pass) and a fetched byte once: the half is the G-buffer size that moves as many bytes. Without
// it a visibility buffer would read as its 8 B/px of ids and depth and win every budget.
//
// Ties: the lines rest on the mean FLIP alone and name every layout tied with the best, a tie
// being an exactly equal mean. They do not test whether the best is significantly better than the
// next: the table's tied ranks do (rank_significance.h, the paired sign-flip test on FLIP tiles),
// and the basis says so.
//
// An interrupted report (ReportModel::interruption) holds only the runs that finished: each line
// names the layouts that fit its budget but never ran, and "no layout fits" becomes "no layout
// that ran fits", so that no line claims what was never measured.
#include <optional>
#include <string>
#include <vector>

#include "report_model.h"

namespace gbl {

inline constexpr int kVerdictBudgets[] = {8, 12, 16, 24, 32};

struct VerdictEntry {
    std::string layout;
    int bytesPerPixel = 0;       // the table's: targets + depth + light buffers
    double countedBytes = 0;     // what the budget is held against (see above)
    bool visibilityBuffer = false;  // countedBytes includes modelled vertex fetches
    double flipMean = 0;         // LDR-FLIP, mean over the views
};

struct BudgetLine {
    std::optional<int> budget;  // bytes per pixel; nullopt: unlimited
    std::optional<VerdictEntry> best;  // nullopt: no measured layout fits
    std::vector<VerdictEntry> tiedWith;
    std::optional<VerdictEntry> smallest;  // when nothing fits: the layout of fewest counted bytes
    // An interrupted report: the layouts that fit the budget but never ran (flipMean unused).
    std::vector<VerdictEntry> notRun;
    std::string sentence;
};

struct BudgetVerdict {
    std::string iblMode;  // the first IBL mode with a measured layout run
    int views = 1;        // the FLIP means are over this many views
    int scenes = 0;       // across several scenes (suite_verdict.h): the FLIP means are over them; 0: one scene
    std::string basis;    // how the lines are decided, one paragraph
    std::string interruptedBy;  // "SIGINT" when the report is an interrupted one's, else 
    std::vector<BudgetLine> lines;  // kVerdictBudgets in order, then unlimited
};

// Bytes per pixel a run is held against a budget (see the file comment).
double verdictCountedBytes(const RunReport& run);

// nullopt when no layout run was measured (failed runs, the reference itself and the lighting
// comparisons never count).
std::optional<BudgetVerdict> budgetVerdict(const ReportModel& model);

// The lines of a verdict, kVerdictBudgets then unlimited, from the measured layouts (`entries`,
// any order) and those an interruption left unrun: each budget's best, the layouts tied with it
// and, when none fits, the smallest. `over` ends "has the lowest mean FLIP over ..." ("3 views",
// "3 scenes"); `interruptedBy` the signal of an interrupted report, else "".
std::vector<BudgetLine> verdictLines(std::vector<VerdictEntry> entries, std::vector<VerdictEntry> notRun,
                                     const std::string& over, const std::string& interruptedBy);

}  // namespace gbl
