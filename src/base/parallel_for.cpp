#include "parallel_for.h"

#include <algorithm>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace gbl {

int hardwareThreads() { return std::max(1, int(std::thread::hardware_concurrency())); }

void parallelFor(int64_t count, int threads, const std::function<void(int64_t, int64_t)>& fn) {
    if (count <= 0) return;
    const int64_t n = std::min<int64_t>(count, threads > 0 ? threads : hardwareThreads());
    if (n <= 1) {
        fn(0, count);
        return;
    }
    std::exception_ptr failure;
    std::mutex failureLock;
    auto run = [&](int64_t chunk) {
        const int64_t begin = count * chunk / n, end = count * (chunk + 1) / n;
        try {
            fn(begin, end);
        } catch (...) {
            const std::lock_guard<std::mutex> lock(failureLock);
            if (!failure) failure = std::current_exception();
        }
    };
    std::vector<std::thread> workers;
    workers.reserve(size_t(n - 1));
    for (int64_t chunk = 1; chunk < n; ++chunk) {
        try {
            workers.emplace_back(run, chunk);
        } catch (const std::system_error&) {
            run(chunk);  // no thread to be had: do that chunk here rather than fail
        }
    }
    run(0);
    for (std::thread& t : workers) t.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace gbl
