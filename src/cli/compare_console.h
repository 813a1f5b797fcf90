#pragma once
// What compare prints: the summary table (of several scenes, the table across them), where the
// time went, the report's path and what failed.
#include "compare_api.h"
#include "compare_text.h"
#include "compare_timings.h"
#include "report_model.h"
#include "suite_report.h"

namespace gbl::compare {

// The table, then "G-buffer or visibility buffer?" and the verdict when the runs have them.
void printTable(const ReportModel& model);

// The verdict per byte budget (budget_verdict.h): its basis, then one line per budget, the same
// sentences report.html and report.json hold.
void printVerdict(const ReportModel& model);
// The effective bandwidth per GPU class (report_bandwidth.h), after the verdict.
void printBandwidthAsPaid(const ReportModel& model);

// Where the time went, stage by stage (stage_clock.h), against the GPU passes' own time (the
// timestamp queries of every frame rendered): what timings.json holds (compare_timings.h).
void printTimings(const CompareTimings& timings);

// Several scenes: each layout's mean error, tied, mean and worst rank across them, each scene's
// error, the rank agreement between scenes, the scenes that failed.
void printSuiteTable(const SuiteModel& model);

// A comparison's report as written (app::RunControl::onReport): its table (or the table across
// the scenes), where the time went, the report's path, then each error on stderr.
void printReport(const app::CompareResult& result);

}  // namespace gbl::compare
