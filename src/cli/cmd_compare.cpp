// `gbufferlab compare`: the product's main job. Renders the float reference and every chosen
// layout (under every chosen IBL mode) at the same camera, measures attribute and image error,
// writes error images, the bandwidth model and report.html / report.json / report.csv.
// The flags: compare_flags.h; the comparison itself: app/compare_api.h.
#include "commands.h"
#include "compare_api.h"
#include "compare_flags.h"
#include "console_run.h"

namespace gbl {

int runCompareCommand(const std::vector<std::string>& args) {
    const std::optional<compare::CompareOptions> options = compare::parseCompareOptions(args);
    if (!options) return 0;  // --help
    const app::CompareResult result = app::runComparison(*options, consoleRunControl());
    return consoleExitStatus(result.exitStatus, result.interruptedBy);
}

}  // namespace gbl
