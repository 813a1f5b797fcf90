#include "background_writer.h"

#include <algorithm>
#include <exception>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace gbl {

BackgroundWriter::BackgroundWriter(int threads, size_t maxQueued, int niceness)
    : maxQueued_(std::max<size_t>(1, maxQueued)) {
    for (int i = 0; i < std::max(1, threads); ++i)
        threads_.emplace_back([this, niceness] {
#if defined(__linux__)
            // Per thread on Linux (the nice value is a thread's own; threads started later
            // inherit it). A refusal leaves the thread at the command's priority: no error.
            if (niceness > 0) setpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid)), niceness);
#else
            (void)niceness;
#endif
            work();
        });
}

BackgroundWriter::~BackgroundWriter() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    for (std::thread& t : threads_) t.join();
}

void BackgroundWriter::enqueue(std::string what, std::function<void()> job) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return queue_.size() < maxQueued_; });
    queue_.push_back({nextTicket_++, std::move(what), std::move(job)});
    peakWaiting_ = std::max(peakWaiting_, queue_.size());
    lock.unlock();
    changed_.notify_all();
}

void BackgroundWriter::work() {
    std::unique_lock lock(mutex_);
    for (;;) {
        changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (queue_.empty()) return;  // stopping, and nothing left to write
        Job job = std::move(queue_.front());
        queue_.pop_front();
        running_.push_back(job.ticket);
        lock.unlock();
        changed_.notify_all();  // a place in the queue is free
        std::string error;
        try {
            job.run();
        } catch (const std::exception& e) {
            error = e.what();
        } catch (...) {
            error = "unknown error";
        }
        job.run = nullptr;  // free what the job owned before the next one starts
        lock.lock();
        if (!error.empty()) {
            // One line, whatever the library's message looked like.
            std::replace(error.begin(), error.end(), '\n', ' ');
            errors_.emplace_back(job.ticket, WriteFailure{job.what, error});
        }
        running_.erase(std::find(running_.begin(), running_.end(), job.ticket));
        changed_.notify_all();
    }
}

void BackgroundWriter::drain() {
    std::unique_lock lock(mutex_);
    const uint64_t until = nextTicket_;  // jobs with a smaller ticket must be done
    changed_.wait(lock, [&] {
        const bool queued = !queue_.empty() && queue_.front().ticket < until;
        const bool running = std::any_of(running_.begin(), running_.end(), [&](uint64_t t) { return t < until; });
        return !queued && !running;
    });
}

std::vector<WriteFailure> BackgroundWriter::finish() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return queue_.empty() && running_.empty(); });
    std::sort(errors_.begin(), errors_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<WriteFailure> out;
    for (auto& [ticket, failure] : errors_) out.push_back(std::move(failure));
    errors_.clear();
    return out;
}

uint64_t BackgroundWriter::queuedCount() const {
    std::lock_guard lock(mutex_);
    return nextTicket_;
}

size_t BackgroundWriter::peakWaiting() const {
    std::lock_guard lock(mutex_);
    return peakWaiting_;
}

}  // namespace gbl
