// The background writer (issue 14): jobs run off the caller's thread, at most maxQueued wait
// (enqueue blocks past that), every failure comes back as one line in queue order, and a job
// that fails leaves no partial or temporary file.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <chrono>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <thread>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#endif

#include "background_writer.h"
#include "error.h"
#include "file_io.h"
#include "temp_dir.h"

namespace gbl {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

struct TempDir : test::TempDir {
    TempDir() : test::TempDir("gbl_bgwriter_") {}
};

// A gate the test opens: jobs that wait on it stay "running" until then.
struct Gate {
    std::mutex m;
    std::condition_variable cv;
    bool open = false;
    void wait() {
        std::unique_lock lock(m);
        cv.wait(lock, [&] { return open; });
    }
    void release() {
        {
            std::lock_guard lock(m);
            open = true;
        }
        cv.notify_all();
    }
};

TEST(BackgroundWriter, RunsJobsOffTheCallersThread) {
    BackgroundWriter writer(2, 4);
    const auto caller = std::this_thread::get_id();
    std::atomic<int> done{0}, onCaller{0};
    for (int i = 0; i < 20; ++i)
        writer.enqueue("job " + std::to_string(i), [&] {
            if (std::this_thread::get_id() == caller) ++onCaller;
            ++done;
        });
    EXPECT_TRUE(writer.finish().empty());
    EXPECT_EQ(done.load(), 20);
    EXPECT_EQ(onCaller.load(), 0);
    EXPECT_EQ(writer.queuedCount(), 20u);
}

TEST(BackgroundWriter, EnqueueBlocksWhileTheQueueIsFull) {
    Gate gate;
    BackgroundWriter writer(1, 2);
    writer.enqueue("blocker", [&] { gate.wait(); });  // taken by the one worker...
    std::this_thread::sleep_for(20ms);  // ... (give it the time to take it; either way the bound holds)
    writer.enqueue("a", [] {});
    writer.enqueue("b", [] {});
    std::atomic<bool> returned{false};
    std::thread late([&] {
        writer.enqueue("c", [] {});  // a third waiting job: must wait for a free place
        returned = true;
    });
    std::this_thread::sleep_for(100ms);
    // Only a place freed by the worker lets it in, and the worker is held by the gate. (If the
    // worker had not yet taken the blocker, three jobs would be waiting: still over the bound.)
    EXPECT_FALSE(returned.load());
    gate.release();
    late.join();
    EXPECT_TRUE(returned.load());
    EXPECT_TRUE(writer.finish().empty());
    EXPECT_LE(writer.peakWaiting(), 2u);
}

TEST(BackgroundWriter, EveryErrorComesBackAsOneLineInQueueOrder) {
    BackgroundWriter writer(3, 8);
    for (int i = 0; i < 12; ++i)
        writer.enqueue("file" + std::to_string(i) + ".png", [i] {
            // Later jobs fail first: the order must still be the queue's.
            std::this_thread::sleep_for(std::chrono::milliseconds(12 - i));
            if (i % 4 == 1) throw std::runtime_error("disk full\nsecond line");
            if (i == 6) throwUserError("cannot write");
        });
    std::vector<std::string> errors;
    for (const WriteFailure& f : writer.finish()) errors.push_back(f.line());
    EXPECT_EQ(errors, (std::vector<std::string>{"file1.png: disk full second line", "file5.png: disk full second line",
                                                "file6.png: cannot write", "file9.png: disk full second line"}));
    EXPECT_TRUE(writer.finish().empty()) << "errors are returned once";
}

TEST(BackgroundWriter, DrainWaitsForEarlierJobsOnly) {
    Gate gate;
    std::atomic<int> early{0};
    BackgroundWriter writer(2, 4);
    for (int i = 0; i < 3; ++i)
        writer.enqueue("early", [&] {
            std::this_thread::sleep_for(20ms);
            ++early;
        });
    writer.drain();
    EXPECT_EQ(early.load(), 3);
    writer.enqueue("held", [&] { gate.wait(); });
    std::atomic<bool> drained{false};
    std::thread t([&] {
        writer.drain();
        drained = true;
    });
    std::this_thread::sleep_for(60ms);
    EXPECT_FALSE(drained.load()) << "drain returned while a job queued before it was still running";
    gate.release();
    t.join();
    EXPECT_TRUE(drained.load());
}

TEST(BackgroundWriter, AFailedWriteLeavesNoPartialOrTemporaryFile) {
    TempDir dir;
    BackgroundWriter writer(2, 2);
    writer.enqueue("good.bin", [&] { writeFileAtomic(dir.path / "good.bin", std::string(1 << 20, 'x')); });
    writer.enqueue("bad.bin", [&] {
        writeViaTemporary(dir.path / "bad.bin", [](const fs::path& tmp) {
            writeFileAtomic(tmp, "half of it");  // the temporary exists ...
            throw std::runtime_error("encoder failed");  // ... and the write fails
        });
    });
    const std::vector<WriteFailure> errors = writer.finish();
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].what, "bad.bin");
    EXPECT_EQ(errors[0].message, "encoder failed");
    EXPECT_EQ(dir.list(), std::vector<std::string>{"good.bin"});
    EXPECT_EQ(fs::file_size(dir.path / "good.bin"), size_t(1) << 20);
}

TEST(BackgroundWriter, TheSameFileFromTwoThreadsEndsWhole) {
    // Two writers of one path (the SPIR-V cache when two pipelines compile the same shader): each
    // has its own temporary, so the file is one of the two, whole, and no temporary is left.
    TempDir dir;
    const std::string a(300000, 'a'), b(200000, 'b');
    {
        BackgroundWriter writer(2, 64);
        for (int i = 0; i < 40; ++i)
            writer.enqueue("same", [&, i] { writeFileAtomic(dir.path / "same.bin", i % 2 ? a : b); });
        EXPECT_TRUE(writer.finish().empty());
    }
    const std::string text = readTextFile(dir.path / "same.bin");
    EXPECT_TRUE(text == a || text == b);
    EXPECT_EQ(dir.list(), std::vector<std::string>{"same.bin"});
}

}  // namespace
}  // namespace gbl

#if defined(__linux__)
// A writer made with a niceness runs its jobs at it, and so do the threads a job starts (the
// files' encoders: parallelInvoke, OpenEXR's pool); the caller's own priority is left alone.
TEST(BackgroundWriter, JobsRunAtTheWritersNiceValue) {
    const auto niceOfThisThread = [] {
        errno = 0;
        return getpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid)));
    };
    const int callerBefore = niceOfThisThread();
    if (callerBefore >= 19) GTEST_SKIP() << "already at the lowest priority";
    gbl::BackgroundWriter writer(1, 2, 19);
    std::atomic<int> inJob{-100}, inChild{-100};
    writer.enqueue("nice", [&] {
        inJob = niceOfThisThread();
        std::thread child([&] { inChild = niceOfThisThread(); });
        child.join();
    });
    EXPECT_TRUE(writer.finish().empty());
    EXPECT_EQ(inJob.load(), 19);
    EXPECT_EQ(inChild.load(), 19);
    EXPECT_EQ(niceOfThisThread(), callerBefore);
    gbl::BackgroundWriter plain(1, 2);
    std::atomic<int> inPlain{-100};
    plain.enqueue("plain", [&] { inPlain = niceOfThisThread(); });
    EXPECT_TRUE(plain.finish().empty());
    EXPECT_EQ(inPlain.load(), callerBefore);
}
#endif
