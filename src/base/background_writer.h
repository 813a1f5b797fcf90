#pragma once
// Output files written on worker threads while the command goes on (issue 14: "image writing is
// off the critical path": compare renders the next layout while the last one's PNG and EXR files
// are encoded).
//
// - Memory stays bounded: at most `maxQueued` jobs wait (each owns the images it writes); enqueue
//   blocks while the queue is full, so a slow disk slows the command instead of filling memory.
// - No error is lost: a job that throws is recorded (its `what` and the exception's message, made
//   one line) and finish() returns them all, in the order the jobs were queued.
// - No partial file: jobs write through file_io's atomic writes (temporary + rename), whose
//   temporaries interrupt.h removes on SIGINT / SIGTERM.
// - Priority: with `niceness` > 0 the writer's threads (and the threads their jobs start, which
//   inherit it) run at that nice value (Linux). On a machine whose cores are all busy (lavapipe
//   renders on the same cores) the files then take the time the render and the metrics leave
//   over instead of stretching them; compare uses it to measure its passes unstretched.
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace gbl {

struct WriteFailure {
    std::string what;     // as given to enqueue
    std::string message;  // the exception's, on one line
    std::string line() const { return what + ": " + message; }
};

class BackgroundWriter {
public:
    explicit BackgroundWriter(int threads = 1, size_t maxQueued = 2, int niceness = 0);
    // Waits for the queued jobs (their errors are dropped only if finish() was never called:
    // call it to see them).
    ~BackgroundWriter();
    BackgroundWriter(const BackgroundWriter&) = delete;
    BackgroundWriter& operator=(const BackgroundWriter&) = delete;

    // Queues `job`; `what` names it in an error line (e.g. the file or run it writes).
    void enqueue(std::string what, std::function<void()> job);
    // Waits until every job queued before this call has finished (later ones may still run).
    void drain();
    // Waits for every job and returns the failures of those that threw (then forgets them).
    std::vector<WriteFailure> finish();

    // Jobs queued so far, and the most that ever waited at once (tests check the bound).
    uint64_t queuedCount() const;
    size_t peakWaiting() const;

private:
    void work();
    struct Job {
        uint64_t ticket;
        std::string what;
        std::function<void()> run;
    };
    const size_t maxQueued_;
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Job> queue_;
    uint64_t nextTicket_ = 0;
    std::vector<uint64_t> running_;  // tickets being run
    std::vector<std::pair<uint64_t, WriteFailure>> errors_;
    size_t peakWaiting_ = 0;
    bool stopping_ = false;
    std::vector<std::thread> threads_;
};

}  // namespace gbl
