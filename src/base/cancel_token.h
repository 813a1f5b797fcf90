#pragma once
// A request to stop long work, shared by whoever asks and the work that listens. The work polls
// cancelled() between its steps (a comparison between runs, a search between rounds) and may set
// an action that runs at once on the asking thread (a comparison writes the report of the runs that
// finished). gbufferlab's command line asks on SIGINT and SIGTERM (interrupt.h's watcher, which then
// ends the process); a test or another front end asks with cancel() and gets the work's result.
#include <atomic>
#include <functional>
#include <mutex>

namespace gbl {

class CancelToken {
public:
    CancelToken() = default;
    CancelToken(const CancelToken&) = delete;
    CancelToken& operator=(const CancelToken&) = delete;

    // Asks the work to stop; `signal` says why (SIGINT, SIGTERM, or any number > 0 of the caller's).
    // The first call marks the request, then runs the action, if the work set one, on the calling
    // thread; later calls do nothing.
    void cancel(int signal);
    // 0 while nobody asked; else the first cancel()'s signal.
    int signal() const { return signal_.load(); }
    bool cancelled() const { return signal() != 0; }

    // What the work does when asked ({}: nothing). Waits while an action runs on another thread, so
    // that what an action uses may be destroyed once this returns.
    void setAction(std::function<void(int signal)> action);

private:
    std::atomic<int> signal_{0};
    std::mutex actionMutex_;  // action_, and an action while it runs
    std::function<void(int)> action_;
};

}  // namespace gbl
