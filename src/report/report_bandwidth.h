#pragma once
// The report's "bandwidth as GPUs pay it" section (docs/bandwidth.md): each layout's nominal
// against effective bytes per pixel and 1080p60 traffic per GPU class, its targets' compression,
// its tile-memory fit per family, and the verdict per budget with each class's effective bytes.
// report.json, report.csv, report.html and compare's console print from these functions.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "report_model.h"

namespace gbl {

// runs[i].effective_bandwidth
nlohmann::ordered_json effectiveBandwidthJson(const EffectiveBandwidth& e);
// The report-level section "bandwidth_as_paid": the classes and what each assumes, the tile
// families and their sources, the lighting model, the model's calibration note, and the verdicts.
nlohmann::ordered_json bandwidthAsPaidJson(const ReportModel& model);

// report.csv: the columns the effective bandwidth adds (empty fields where a run has none).
std::vector<std::string> effectiveCsvHeader();
std::vector<std::string> effectiveCsvFields(const RunReport& run);

// The budget lines held against one class's effective bytes (or "nominal": the table's bytes):
// the layout of lowest mean FLIP among the measured G-buffer layouts whose bytes fit.
struct EffectiveBudgetLine {
    std::optional<int> budget;  // nullopt: unlimited
    std::string best;           // "" when none fits
    double bytes = 0;           // the best's bytes under the class
    double flipMean = 0;
};
struct EffectiveVerdict {
    std::string gpuClass;  // "nominal", "desktop-dcc", "mali-afbc", "tile-subpass"
    std::vector<EffectiveBudgetLine> lines;
};
std::vector<EffectiveVerdict> effectiveVerdicts(const ReportModel& model);
// One sentence per budget whose best layout changes from the nominal one under a class.
std::vector<std::string> verdictChanges(const std::vector<EffectiveVerdict>& verdicts);

// report.html's section (an <h2 id="bandwidth-as-paid"> and its tables); "" without effective numbers.
std::string bandwidthSectionHtml(const ReportModel& model);

// The atlas's Bytes/px cell: the layout's effective bytes per class under the nominal ones ("" when
// it has none).
std::string atlasEffectiveBytesHtml(const ReportModel& model, const std::string& layout);

// The runs of the report's first IBL mode that have effective numbers, in report order.
std::vector<const RunReport*> effectiveRuns(const ReportModel& model);

}  // namespace gbl
