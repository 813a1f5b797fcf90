#pragma once
// A comparison over several scenes (compare --scene A --scene B, or a scene suite): each scene's
// own report (ReportModel, written in full under scenes/<name>/) and the summary across them:
// each layout's mean error, mean rank and worst rank. report.json and report.html of the top
// folder hold it; docs/report-schema.md documents the keys.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "report_model.h"

namespace gbl {

struct SuiteScene {
    std::string name;         // its folder: scenes/<name>/
    std::string scene;        // glTF file, or the built-in scene's name
    std::string environment;  // environment file, or the built-in sky
    bool builtin = false;     // the built-in scene (whatever its name)
    bool ok = true;           // false: the scene failed before its runs (it could not be loaded)
    std::string error;        // why ("" when ok)
    int exitStatus = 0;       // of its comparison (0, 1 a file not written, 4 some runs failed)
    std::optional<ReportModel> report;  // absent when it failed
    std::string folder() const { return "scenes/" + name; }
};

// One layout under one IBL mode across the scenes. The error is the run's mean LDR-FLIP over its
// views (`image_errors.flip_mean`); ranks are 1 = lowest error among the layouts of that mode in
// that scene, layouts of equal error sharing the better rank.
struct SuiteLayoutSummary {
    std::string layout;
    std::string iblMode;
    int bytesPerPixel = 0;
    std::vector<std::optional<double>> errors;  // per scene (SuiteModel::scenes order); unset: no ok run
    std::vector<std::optional<int>> ranks;
    std::vector<std::string> tiedRanks;  // per scene: its report's rank range ("4-6"), "" without a run
    std::string tiedRankAcross;          // across the scenes (SuiteModel::acrossScenes)
    int scenesMeasured = 0;  // scenes with an ok run
    double meanError = 0.0;  // over those scenes
    double meanRank = 0.0;
    int worstRank = 0;
};

// Two scenes' rankings of the same layouts (under one IBL mode): Kendall's tau-b
// (rank_agreement.h) of their mean FLIP, and the layout pairs whose order swaps.
struct SceneAgreement {
    std::string sceneA, sceneB, iblMode;
    int layouts = 0;  // ranked in both
    double tau = 1.0;
    int pairs = 0;
    std::vector<std::pair<std::string, std::string>> swaps;  // (better in A, better in B)
};

// A comparison of several scenes interrupted by a signal: its report holds the scenes that
// finished; these are the ones that did not (the one interrupted has its own partial report in
// its folder, the rest never started).
struct SuiteInterruption {
    std::string signal;  // "SIGINT" / "SIGTERM"
    int scenesPlanned = 0;
    std::vector<std::string> notFinished;  // scene names, in the order given
};

struct SuiteModel {
    ReportRunInfo run;  // what every scene shares (scene, environment and exposure are each scene's)
    std::optional<SuiteInterruption> interruption;  // absent: every scene finished
    std::vector<SuiteScene> scenes;
    std::vector<SuiteLayoutSummary> summary;  // by mean rank, then mean error
    // Pairwise significance across the scenes (every scene's tiles pooled; rank_significance.h),
    // ranked by mean error over the scenes.
    SignificanceReport acrossScenes;
    std::vector<SceneAgreement> agreement;  // every pair of scenes, per IBL mode
};

// Fills model.summary from the scenes' reports.
void summariseSuite(SuiteModel& model);

nlohmann::ordered_json suiteToJson(const SuiteModel& model);
std::string suiteHtml(const SuiteModel& model);
// report.json and report.html of the top folder, atomically.
void writeSuiteReport(const std::filesystem::path& dir, const SuiteModel& model);

}  // namespace gbl
