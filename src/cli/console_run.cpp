#include "console_run.h"

#include <cstdio>

#include "compare_api.h"
#include "compare_console.h"
#include "interrupt.h"

namespace gbl {

const app::RunControl& consoleRunControl() {
    // Never destroyed: the watcher thread may cancel during exit.
    static ConsoleProgress* progress = new ConsoleProgress(stderr, stdout);
    static CancelToken* cancel = new CancelToken;
    static const app::RunControl control = [] {
        setInterruptAction([](int signal) { cancel->cancel(signal); });
        app::RunControl c;
        c.progress = progress;
        c.cancel = cancel;
        c.onReport = [](const app::CompareResult& result) { compare::printReport(result); };
        return c;
    }();
    return control;
}

int consoleExitStatus(int exitStatus, int interruptedBy) {
    if (interruptedBy) awaitInterruptExit();
    return exitStatus;
}

}  // namespace gbl
