#pragma once
// compare over several scenes (--scene given more than once, or a scene-suite .toml): every layout
// rendered on every scene, each scene's full report under scenes/<name>/, and the summary across
// them in the top folder's report.json / report.html and on the console (suite_report.h). The
// scenes share one device, the pipelines and each environment's IBL pre-computation
// (CompareShared). A scene that cannot be loaded fails alone: one line, the others still run, the
// report lists it and the exit status is 4 (as for a failed run).
#include "compare_api.h"
#include "compare_options.h"

namespace gbl::compare {

// True when the options name several scenes or a suite file.
bool comparesSeveralScenes(const CompareOptions& options);

// Runs the comparison (compare_api.h runComparison does for several scenes); the result's exit
// status: 0, 1 a file not written, kExitRunsFailed, 128 + the signal when interrupted. `control`
// hears each scene's report, then the summary's.
app::CompareResult runCompareSuite(const CompareOptions& options, const app::RunControl& control);

}  // namespace gbl::compare
