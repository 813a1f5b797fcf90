#pragma once
// Which layouts' error differences are real, and the ranks they share when not (compare's
// significance section, docs/compare.md). For every pair of layouts under one IBL mode, the
// paired sign-flip test of measure/significance.h on their per-tile LDR-FLIP over every view (of
// every scene, across scenes); a layout's rank is then the range "low-high" of the places it may
// hold: low = 1 + the layouts significantly better, high = the layouts of its mode - those
// significantly worse (the ranks a single ordering of the tied layouts could give it).
#include <optional>
#include <string>
#include <vector>

#include "report_model.h"

namespace gbl {

// One layout under one mode, as the test sees it: its mean error and its units per scene (empty:
// it has no ok run there).
struct LayoutUnits {
    std::string layout, iblMode;
    double meanError = 0.0;
    std::vector<std::vector<double>> unitsPerScene;
};

// A run's units: its per-tile FLIP of every view in order (a view without tiles, measured on the
// device evaluator, gives its mean FLIP as one unit). Empty for a failed run.
std::vector<double> runUnits(const RunReport& run);

// The pairs and ranks of these layouts (units of one scene each, or of several scenes: a pair is
// tested on the scenes where both ran).
SignificanceReport rankWithSignificance(const std::vector<LayoutUnits>& layouts);

// Of one comparison's layout runs (lighting comparisons left out).
SignificanceReport rankWithSignificance(const ReportModel& model);

// The same per layer class (measure/layer_classes.h): each run's units are its per-tile LDR-FLIP
// over the class's pixels of every view (a tile without any: 0 for every layout, a zero
// difference), its mean error the class's flip_mean. One (class name, report) per class that
// some run measured, in kLayerClasses order; empty in a scene without layers.
std::vector<std::pair<std::string, SignificanceReport>> rankLayerClassesWithSignificance(const ReportModel& model);

}  // namespace gbl
