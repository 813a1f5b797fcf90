#include "interrupt.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <mutex>
#include <set>
#include <thread>
#include <unistd.h>

namespace gbl {
namespace {

struct State {
    std::mutex mutex;
    std::set<std::filesystem::path> temporaries;
    std::function<void(int)> action;
    bool interrupted = false;
    std::atomic<bool> signalled{false};  // a signal was received: the watcher will end the process
};

State& state() {
    static State* s = new State;  // never destroyed: the watcher may use it during exit
    return *s;
}

thread_local bool isWatcherThread = false;

void watch(sigset_t set) {
    isWatcherThread = true;
    int signal = 0;
    if (sigwait(&set, &signal) != 0) return;
    State& s = state();
    s.signalled = true;
    std::function<void(int)> action;
    {
        std::lock_guard lock(s.mutex);
        action = s.action;
    }
    std::fflush(stdout);
    std::fprintf(stderr, "\ngbufferlab: interrupted by %s; cleaning up\n", signalName(signal));
    if (action) {
        try {
            action(signal);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "gbufferlab: could not record the interruption: %s\n", e.what());
        } catch (...) {
        }
    }
    {
        std::lock_guard lock(s.mutex);
        s.interrupted = true;
        for (const auto& path : s.temporaries) ::unlink(path.c_str());
    }
    // A writer registers its temporary, then creates it: one that registered before the
    // interruption may create it after the unlink above (cli_test's interrupt test once found a
    // .tmp left so). Such writers finish by committing (a whole file) or discarding, and either
    // unregisters; wait for them (at most 10 s), then remove whatever is still registered.
    for (int waited = 0; waited < 500; ++waited) {
        {
            std::lock_guard lock(s.mutex);
            if (s.temporaries.empty()) break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    {
        std::lock_guard lock(s.mutex);
        for (const auto& path : s.temporaries) ::unlink(path.c_str());
        s.temporaries.clear();
    }
    std::fflush(stdout);
    std::fflush(stderr);
    ::_exit(128 + signal);
}

}  // namespace

void installInterruptHandling() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    std::thread(watch, set).detach();
}

void setInterruptAction(std::function<void(int signal)> action) {
    std::lock_guard lock(state().mutex);
    state().action = std::move(action);
}

void awaitInterruptExit() {
    if (!state().signalled) return;
    for (;;) ::pause();  // the watcher calls _exit
}

void registerTemporary(const std::filesystem::path& path) {
    State& s = state();
    std::unique_lock lock(s.mutex);
    if (s.interrupted && !isWatcherThread) {
        lock.unlock();
        for (;;) ::pause();  // the watcher is about to _exit; nothing new may be written
    }
    s.temporaries.insert(path);
}

void unregisterTemporary(const std::filesystem::path& path) {
    std::lock_guard lock(state().mutex);
    state().temporaries.erase(path);
}

const char* signalName(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal"; }

}  // namespace gbl
