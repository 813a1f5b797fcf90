#pragma once
// How the command line runs the app's work (app/run_control.h): progress printed as gbufferlab
// prints it (base/progress.h ConsoleProgress: steps and status lines on stderr, notes on stdout),
// each comparison's report told when written (its table, where the time went, the report's path,
// what failed: compare_console.h), and SIGINT / SIGTERM turned into a cancel request whose action
// (the partial report) runs on interrupt.h's watcher before it ends the process.
#include "run_control.h"

namespace gbl {

// The command line's control; the same one for every run of the process.
const app::RunControl& consoleRunControl();

// A run's exit status, returned when the run finished; when it stopped for a signal, the watcher
// (interrupt.h) is ending the process: this waits for it and never returns.
int consoleExitStatus(int exitStatus, int interruptedBy);

}  // namespace gbl
