#pragma once
// report.json: the whole ReportModel, schema in docs/report-schema.md. Keys keep the model's
// order. Non-finite numbers, which JSON cannot hold, are written as the strings "inf" / "-inf"
// (a PSNR of identical images) and null (NaN).
#include <filesystem>

#include <nlohmann/json.hpp>

#include "budget_verdict.h"
#include "report_model.h"

namespace gbl {

constexpr int kReportSchemaVersion = 1;

nlohmann::ordered_json reportToJson(const ReportModel& model);
// The inverse. Throws UserError naming the field ("runs[2].image_errors.flip_mean: ...") when
// the document does not follow the schema, or has another schema version.
ReportModel reportFromJson(const nlohmann::ordered_json& json);

// nlohmann's conversion hooks (found by ADL): `json j = model;` and `j.get<ReportModel>()`.
void to_json(nlohmann::ordered_json& json, const ReportModel& model);
void from_json(const nlohmann::ordered_json& json, ReportModel& model);

// A verdict per byte budget as report.json's "verdict" holds it (one scene's, or across several).
nlohmann::ordered_json budgetVerdictToJson(const BudgetVerdict& verdict);

// Writes report.json (indented) atomically.
void writeReportJson(const std::filesystem::path& path, const ReportModel& model);
// Reads one back; a UserError names the file.
ReportModel readReportJson(const std::filesystem::path& path);

}  // namespace gbl
