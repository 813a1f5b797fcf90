// The comparison (compare_api.h): one scene's CompareSession, or several scenes' (compare_suite.h).
#include "compare_api.h"

#include "compare_session.h"
#include "compare_suite.h"
#include "stage_clock.h"

namespace gbl::app {

CompareResult runComparison(const compare::CompareOptions& options, const RunControl& control) {
    StageClock::global().start();
    if (compare::comparesSeveralScenes(options)) return compare::runCompareSuite(options, control);
    if (const int signal = control.cancelSignal()) {  // asked before anything was read or written
        CompareResult result;
        result.interruptedBy = signal;
        result.exitStatus = 128 + signal;
        result.outDir = options.outDir;
        return result;
    }
    compare::CompareSession comparison(options, control);
    for (int view = 0; view < comparison.viewCount() && !control.cancelSignal(); ++view) comparison.runView(view);
    if (const int signal = control.cancelSignal()) return comparison.interrupted(signal);
    CompareResult result = comparison.finish();
    if (control.onReport) control.onReport(result);
    return result;
}

}  // namespace gbl::app
