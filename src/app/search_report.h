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
    // Every metric (search_front.h): the full renders' (mean over scenes), when confirmed; for a
    // found layout, its role on the front, the published layout it is set beside, and the
    // significance of their FLIP difference (compare's sign-flip test on tiles).
    std::optional<search::Evaluation> full;
    std::string role;
    std::string comparator;
    std::optional<double> flipPValue;
    int flipUnits = 0;
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
    std::vector<std::string> constraints;       // search_constraints.h describeConstraints
    std::vector<search::Candidate> front;       // the whole front, by bytes then the objective
};

// Reads compare's report.json: each layout's flip_mean (split-sum) into the rows; a report of
// several scenes (schema gbufferlab-scene-suite): each scene's into fullFlipPerScene and their
// mean, over the scenes where it ran, into fullFlip.
void readConfirmation(const std::filesystem::path& reportJson, std::vector<SearchRow>& rows);

// search-report.md and search.json in `dir`; returns the closing note (also printed).
std::string writeSearchReport(const SearchSummary& summary, const std::filesystem::path& dir);

}  // namespace gbl
