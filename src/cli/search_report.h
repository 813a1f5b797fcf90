#pragma once
// gbufferlab search, the output: the Pareto front as layout files, the published layouts beside
// them, the confirmation by full GPU renders (the compare pipeline) and the closing note.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "layout_search.h"

namespace gbl {

struct SearchRow {
    std::string name;
    std::string file;       // the written .toml (found layouts), "" for published ones
    std::vector<std::string> exports;  // found layouts: "found-12b.hlsl", "found-12b.glsl" beside the .toml
    bool found = false;
    int bytes = 0;
    search::Evaluation fast;  // the fast (CPU) evaluation
    std::optional<double> fullFlip;  // compare's flip_mean (mean over views) of the full GPU render
    // Several scenes (search --scene A --scene B): each scene's fast evaluation and full-render FLIP
    // (SearchSummary::sceneNames order); `fast` and `fullFlip` are then their means.
    std::vector<search::Evaluation> fastPerScene;
    std::vector<std::optional<double>> fullFlipPerScene;
    std::string how;
};

struct SearchSummary {
    std::string commandLine;
    std::string objective;
    uint64_t seed = 0;
    int budget = 0;
    std::string size;
    int views = 0;
    int candidates = 0, resumed = 0;
    double perMinute = 0.0;
    double cpuSecondsPerCandidate = 0.0;
    int threads = 0;
    double reshadeFlip = 0.0;       // CPU re-shade of the reference against its GPU render (mean over views)
    double reshadeMeanRelative = 0.0;  // ... and its mean relative luminance error
    std::string counts;             // over budget / duplicates / ...
    std::vector<SearchRow> rows;    // found, then published
    std::vector<std::string> sceneNames;  // several scenes only
};

// Writes each front candidate as <dir>/found-<bytes>b.toml with a header comment (how it was
// found, what it scored), and beside it its `layouts export` in HLSL and GLSL (found-<bytes>b.hlsl,
// .glsl; with best-fit normals also the table, found-<bytes>b.hlsl.bestfit.u32), and returns their rows.
std::vector<SearchRow> writeFront(const search::SearchResult& result, const std::filesystem::path& dir,
                                  const std::string& commandLine, const std::string& objective, uint64_t seed);

// Reads compare's report.json: each layout's flip_mean (split-sum) into the rows; a report of
// several scenes (schema gbufferlab-scene-suite): each scene's into fullFlipPerScene and their
// mean, over the scenes where it ran, into fullFlip.
void readConfirmation(const std::filesystem::path& reportJson, std::vector<SearchRow>& rows);

// search-report.md and search.json in `dir`; returns the closing note (also printed).
std::string writeSearchReport(const SearchSummary& summary, const std::filesystem::path& dir);

}  // namespace gbl
