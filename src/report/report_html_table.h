#pragma once
// The report page's layouts table: one row per run, its columns in groups (cost, attribute error,
// image error), sortable by the page's script. Secondary columns (the normal angle's p99) and,
// with several views, each value's spread over them are folded by default so the table fits a
// 1600-pixel window; a checkbox above it shows them, without the script. Internal to the report
// library (report_html.cpp).
#include <string>
#include <vector>

#include "report_model.h"

namespace gbl {

// `ids` are the runs' section ids, parallel to model.runs.
void writeLayoutsTable(std::string& out, const ReportModel& model, const std::vector<std::string>& ids);

}  // namespace gbl
