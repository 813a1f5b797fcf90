// `gbufferlab compare`: the product's main job. Renders the float reference and every chosen
// layout (under every chosen IBL mode) at the same camera, measures attribute and image error,
// writes error images, the bandwidth model and report.html / report.json / report.csv.
// The flags: compare_options.h; the comparison itself: compare_session.h.
#include "commands.h"
#include "compare_options.h"
#include "compare_session.h"
#include "compare_suite.h"
#include "stage_clock.h"

namespace gbl {

int runCompareCommand(const std::vector<std::string>& args) {
    const std::optional<compare::CompareOptions> options = compare::parseCompareOptions(args);
    if (!options) return 0;  // --help
    StageClock::global().start();
    if (compare::comparesSeveralScenes(*options)) return compare::runCompareSuite(*options);
    compare::CompareSession comparison(*options);
    for (int view = 0; view < comparison.viewCount(); ++view) comparison.runView(view);
    return comparison.finish();
}

}  // namespace gbl
