#pragma once
// report.html: one self-contained page (style and script inline; the images are files beside
// it, referenced by relative paths). A header with the run; a sortable table of the runs; error
// (FLIP mean, or PSNR) against bytes per pixel as inline SVG with each IBL mode's Pareto front;
// and per run its images side by side with the reference, its crops and its numbers.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "report_model.h"

namespace gbl {

std::string reportHtml(const ReportModel& model);
void writeReportHtml(const std::filesystem::path& path, const ReportModel& model);  // atomic

// Writes report.html, report.json and report.csv into `dir` (created when missing), each
// atomically.
void writeReport(const std::filesystem::path& dir, const ReportModel& model);

// ---- Pieces, exposed for tests ------------------------------------------------------------------

std::string htmlEscape(const std::string& text);  // & < > " '
// How the page writes an infinite value (a PSNR of identical images): U+221E in UTF-8.
inline constexpr const char* kInfinity = "\xE2\x88\x9E";
// A relative path for src= / href=: each byte outside [A-Za-z0-9-._~/] percent-encoded.
std::string urlPathEscape(const std::string& path);
// `digits` significant digits, plain decimal for 1e-4 <= |v| < 1e6 ("0.0123", "38.1", "1250"),
// else exponent ("1.2e-07"); "0" for 0; "∞" / "-∞"; "NaN".
std::string formatSignificant(double v, int digits);
// `decimals` after the point ("38.12"); "∞" / "-∞"; "NaN".
std::string formatFixed(double v, int decimals);

// The Pareto front of (x, y) points where a smaller x is better and a smaller y is better (or a
// larger one with higherIsBetter): the indices of the points no other point beats on both, in
// increasing x. Ties: of equal points the first; NaN points never belong.
std::vector<size_t> paretoFront(const std::vector<std::pair<double, double>>& points, bool higherIsBetter);

}  // namespace gbl
