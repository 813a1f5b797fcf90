#pragma once
// SIGINT and SIGTERM end gbufferlab cleanly: no temporary file is left behind, the command gets
// a chance to leave its output folder marked (compare writes the report of the runs that finished
// and an INCOMPLETE file), and the exit status is 128 + the signal (130, 143).
//
// How: installInterruptHandling() blocks both signals in the calling thread before any other
// thread exists (so every thread inherits the mask) and starts a watcher thread that waits for
// them with sigwait. The watcher runs in a normal thread context, so the command's action may
// take locks and write files, which a signal handler could not.
#include <filesystem>
#include <functional>

namespace gbl {

// Call once, first thing in main(), before any thread is started.
void installInterruptHandling();

// What the command wants done on interruption (before temporaries are removed), e.g. write a
// partial report. Runs on the watcher thread; `signal` is SIGINT or SIGTERM. Pass {} to clear.
// The command line sets one action for the whole process: it cancels the run's CancelToken
// (cancel_token.h), whose own action the comparison sets.
void setInterruptAction(std::function<void(int signal)> action);

// For a command whose work stopped because of a signal: the watcher is cleaning up and ends the
// process (exit status 128 + the signal), so this waits for it and never returns. Without a signal
// received, returns at once.
void awaitInterruptExit();

// Temporary files in flight (file_io's writeViaTemporary registers every one): removed on
// interruption. After interruption has begun, registering blocks forever (the process is about
// to exit), so no new temporary can appear behind the clean-up.
void registerTemporary(const std::filesystem::path& path);
void unregisterTemporary(const std::filesystem::path& path);

// "SIGINT" / "SIGTERM".
const char* signalName(int signal);

}  // namespace gbl
