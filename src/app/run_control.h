#pragma once
// What the caller of a comparison or a search gives it besides its options: where its progress
// goes, how it is asked to stop, and who hears of each report as it is written. All optional: an
// empty RunControl runs silently to the end.
#include <functional>

#include "cancel_token.h"
#include "progress.h"

namespace gbl::app {

struct CompareResult;

struct RunControl {
    // Steps ("[3/27] ue4 / split-sum ..."), notes and errors as the work goes; null: told to nobody.
    // The command line's prints them as gbufferlab always did (ConsoleProgress).
    ProgressSink* progress = nullptr;
    // Asked to stop: the work ends at its next step with an interrupted result (a comparison writes
    // the report of the runs that finished, as on SIGINT); null: never asked.
    CancelToken* cancel = nullptr;
    // A comparison's report, once written: each scene's, then (several scenes) their summary; the
    // command line prints its table there. Called on the thread that runs the work.
    std::function<void(const CompareResult&)> onReport;

    int cancelSignal() const { return cancel ? cancel->signal() : 0; }
};

}  // namespace gbl::app
