#pragma once
// Runs a list of independent tasks (files to encode, images to prepare) side by side.
#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <vector>

#include "parallel_for.h"

namespace gbl {

// Runs every task once, up to hardwareThreads() at a time; each thread takes the next task not
// yet started, so uneven tasks balance. Returns when all are done and rethrows the first
// exception in task order.
inline void parallelInvoke(const std::vector<std::function<void()>>& tasks) {
    std::vector<std::exception_ptr> errors(tasks.size());
    std::atomic<size_t> next{0};
    const int threads = int(std::min<size_t>(tasks.size(), size_t(hardwareThreads())));
    parallelFor(threads, threads, [&](int64_t, int64_t) {
        for (size_t t; (t = next.fetch_add(1)) < tasks.size();) {
            try {
                tasks[t]();
            } catch (...) {
                errors[t] = std::current_exception();
            }
        }
    });
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
}

}  // namespace gbl
