#pragma once
// What compare prints: the summary table, and where the time went (also written as
// timings.json for bench/).
#include <filesystem>
#include <string>

#include "report_model.h"
#include "stage_clock.h"

namespace gbl::compare {

// "52.3 dB", or "inf" for identical images.
std::string formatPsnr(double db);

// The table, then "G-buffer or visibility buffer?" and the verdict when the runs have them.
void printTable(const ReportModel& model);

// The verdict per byte budget (budget_verdict.h): its basis, then one line per budget, the same
// sentences report.html and report.json hold.
void printVerdict(const ReportModel& model);

// Where the time went, stage by stage (stage_clock.h), against the GPU passes' own time (the
// timestamp queries of every frame rendered): printed, and written as timings.json for bench/.
void reportStageTimes(const std::filesystem::path& outDir, const StageTimes& t, double gpuPassMs, bool cpuDevice);

}  // namespace gbl::compare
