#pragma once
// The headline of a comparison over several scenes: the verdict per byte budget across the scenes
// (the single scene's budget_verdict.h, with each layout's FLIP averaged over the scenes), and how
// far the scenes agree on the ranking, in words a user reads, with the layouts that move most
// between them. The console, report.html and report.json of the top folder all print these, from
// these functions, so they cannot disagree.
#include <optional>
#include <string>
#include <vector>

#include "budget_verdict.h"
#include "suite_report.h"

namespace gbl {

// The verdict across the scenes, under the first IBL mode with a layout measured on every scene
// that ran: per budget, the lowest FLIP averaged over the scenes (each scene's mean over its
// views) among the layouts measured on every scene. A layout's counted bytes are the largest of
// its scenes' (they differ only for a visibility buffer, whose modelled vertex fetches depend on
// the scene). nullopt when fewer than two scenes ran or no layout was measured on all of them.
std::optional<BudgetVerdict> suiteBudgetVerdict(const SuiteModel& model);

// A layout whose rank differs between the scenes: its plain rank in each scene (SuiteModel's
// order, as SuiteLayoutSummary::ranks; unset where it has no run) and the spread, worst rank -
// best, over the scenes the agreement compares.
struct LayoutMove {
    std::string layout;
    std::vector<std::optional<int>> ranks;
    int spread = 0;
};

// How far the scenes agree, under one IBL mode (the verdict's):
//   "The built-in scene agrees with the assets at tau 0.30-0.33 (FlightHelmet 0.30, WaterBottle
//    0.33), they with each other at tau 0.92: rankings depend on content."
// and the layouts that move most, e.g. "ue5-16bit-unorm 1st on the built-in scene, 21st on
// FlightHelmet and WaterBottle". A scene stands apart when its mean tau with the others is at
// least kApartTau below theirs among themselves (three scenes or more).
struct SuiteAgreementWords {
    std::string iblMode;
    double meanTau = 1.0;      // over every pair of scenes
    std::string sentence;      // how far they agree, and what it means for the verdict
    std::vector<LayoutMove> moves;  // the largest spreads first, at most kMovesListed
    std::string movesSentence;      // "Largest moves: ..." ("" when no layout moves)
};

inline constexpr double kApartTau = 0.2;
inline constexpr int kMovesListed = 4;

// nullopt when no two scenes ranked the same layouts (SuiteModel::agreement is empty).
std::optional<SuiteAgreementWords> suiteAgreementWords(const SuiteModel& model);

// What a tau means for a verdict: >= 0.8 "the ranking holds across them", >= 0.5 "the rankings
// agree in broad lines but swap some layouts", below "rankings depend on content".
std::string agreementMeaning(double tau);

// "1st", "2nd", "3rd", "4th", "11th", "21st", ...
std::string ordinal(int n);

}  // namespace gbl
