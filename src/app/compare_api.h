#pragma once
// The comparison as a library call: what `gbufferlab compare` runs once its flags are read, and
// what a test, a benchmark or another front end runs without a command line.
//
//   compare::CompareOptions options;             // compare_options.h: the flags' defaults
//   options.layoutsSpec = "ue4,crysis3-thin";
//   options.width = 64, options.height = 36, options.viewCount = 1;
//   options.outDir = "out/tiny";
//   const app::CompareResult result = app::runComparison(options, {});
//   result.report->runs[0].image->flipMean ...
//
// One scene or several (options.sceneArgs naming more than one, or a suite .toml:
// compare_suite.h), single frames or --temporal, whole frames or bands: as the options say. The
// report files are written to options.outDir as the command writes them; the result holds the
// model they were written from.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "compare_options.h"
#include "compare_timings.h"
#include "report_model.h"
#include "run_control.h"
#include "suite_report.h"

namespace gbl::compare {

// Exit status when the report was written but some runs failed (1: bad input, 2: usage, 3: bug).
inline constexpr int kExitRunsFailed = 4;

}  // namespace gbl::compare

namespace gbl::app {

struct CompareResult {
    // The command's exit status: 0; 1 a file could not be written; compare::kExitRunsFailed (4) some
    // runs or scenes failed, or no view had anything to measure; 128 + the signal when interrupted.
    int exitStatus = 0;
    // RunControl::cancel's signal when the comparison stopped for it; 0: it ran to its end.
    int interruptedBy = 0;
    // One scene: the report written to outDir (interrupted: the partial report, when the set-up had
    // finished). Several scenes: each scene's, in suite->scenes[i].report.
    std::optional<ReportModel> report;
    std::optional<SuiteModel> suite;  // several scenes: the summary across them
    std::filesystem::path outDir;
    std::optional<compare::CompareTimings> timings;  // also outDir/timings.json
    // What failed, one line each, to be told after the report ("2 of 7 runs failed (see ...)").
    std::vector<std::string> errors;

    bool interrupted() const { return interruptedBy != 0; }
};

// Runs the comparison `options` describe (every input checked before the first render; a bad
// one throws UserError), writing its report to options.outDir.
CompareResult runComparison(const compare::CompareOptions& options, const RunControl& control = {});

}  // namespace gbl::app
