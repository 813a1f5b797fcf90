#pragma once
// gbufferlab search: the front judged on every metric (search/search_metrics.h). Which front
// layouts become files (and are confirmed by full renders), the published layout each is set
// beside, the confirmation's every metric and FLIP significance read back from compare's
// report.json, and the report's section on them.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "search_report.h"

namespace gbl {

// The published layout a found layout of `bytes` B/px is set beside: the best by the objective
// (fast score) among the published layouts within the smallest published budget that is at least
// `bytes` (the same budget, or the next larger one). nullptr when every published layout is smaller.
const SearchRow* comparatorFor(int bytes, const std::vector<SearchRow>& rows);

// Writes the chosen front layouts as <dir>/found-<bytes>b.toml (per byte count, the first in the
// objective's order) and <dir>/found-<bytes>b-allround.toml (the first that is no worse than its
// comparator on any metric, when that is another), each with a header comment: how it was found,
// every fast metric, the trade against its comparator and the engine constraints; beside each its
// `layouts export` in HLSL and GLSL (found-<bytes>b.hlsl, .glsl; with best-fit normals also the
// table, found-<bytes>b.hlsl.bestfit.u32). Returns their rows.
std::vector<SearchRow> writeFront(const search::SearchResult& result, const std::filesystem::path& dir,
                                  const std::string& commandLine, const std::string& objective, uint64_t seed,
                                  const std::vector<std::string>& constraints, const std::vector<SearchRow>& published);

// compare's report.json (one scene or a scene suite): every metric of each row's full renders
// into `full` (means over scenes; occlusion the fast evaluation's where the report predates its
// occlusion error), and for each found row the p-value of the FLIP sign-flip test against its comparator.
void readFullMetrics(const std::filesystem::path& reportJson, std::vector<SearchRow>& rows);

// The markdown section "Every metric" of search-report.md, and the closing note's lines on it.
std::string metricsSection(const SearchSummary& s);
std::string metricsNote(const SearchSummary& s);
// Adds the constraints, the front and each layout's metrics, verdict and trade to search.json.
void addMetricsJson(nlohmann::json& j, const SearchSummary& s);

}  // namespace gbl
