#pragma once
// report.csv: one row per run (layout x IBL mode) with the HTML table's columns and every
// attribute metric, after a header row. RFC 4180 fields with "\n" line ends:
// fields with commas, quotes or line breaks quoted. Numbers are the shortest text that reads back
// to the same double; "inf" for an infinite PSNR; an empty field where a value is absent
// (a failed run, an attribute that does not apply). Columns: docs/report-schema.md.
#include <filesystem>
#include <string>
#include <vector>

#include "report_model.h"

namespace gbl {

// `layers`: with the material layers' columns (a report where some run measured them,
// ReportModel::hasLayerMetrics); without, the columns of every report before them.
std::vector<std::string> reportCsvHeader(bool layers = false);
std::string reportCsv(const ReportModel& model);  // header + rows
void writeReportCsv(const std::filesystem::path& path, const ReportModel& model);  // atomic

// One CSV field, quoted when it must be.
std::string csvField(const std::string& text);

}  // namespace gbl
