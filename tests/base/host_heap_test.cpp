// host_heap.h: with large blocks retained, an image freed and allocated again reuses its pages
// (no minor faults), where the C library's default faults them in afresh. Each policy runs in
// its own child process: mallopt settings are process-wide and cannot be undone.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

#include "host_heap.h"
#include "sanitizers.h"

// Under AddressSanitizer the allocator is the sanitizer's: it ignores mallopt, and
// retainHostBlocks says so by returning false (CI's sanitizer run).
#if GBL_ASAN
constexpr bool kGlibcAllocator = false;
#elif defined(__GLIBC__)
constexpr bool kGlibcAllocator = true;
#else
constexpr bool kGlibcAllocator = false;
#endif

namespace {

long minorFaults() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_minflt;
}

constexpr size_t kBytes = size_t(30) << 20;  // about a 1080p RGBA float image (33 MB), under 32 MiB
constexpr long kPages = long(kBytes / 4096);

// Faults taken by the second of two rounds of "allocate kBytes, touch every page, free".
long faultsOfSecondRound() {
    long before = 0;
    for (int round = 0; round < 2; ++round) {
        if (round == 1) before = minorFaults();
        char* p = static_cast<char*>(std::malloc(kBytes));
        if (!p) std::abort();
        for (size_t i = 0; i < kBytes; i += 4096) p[i] = char(i);
        asm volatile("" : : "r"(p) : "memory");  // the writes happen
        std::free(p);
    }
    return minorFaults() - before;
}

// Runs body in a child; returns what it wrote to the pipe (a count), or -1.
template <class Body>
long inChild(Body body) {
    int fds[2];
    if (pipe(fds) != 0) return -1;
    const pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        const long v = body();
        if (write(fds[1], &v, sizeof v) != sizeof v) _exit(2);
        _exit(0);
    }
    close(fds[1]);
    long v = -1;
    if (read(fds[0], &v, sizeof v) != sizeof v) v = -1;
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    return v;
}

}  // namespace

TEST(HostHeap, RetainedBlocksComeBackWithoutFaults) {
    if (!kGlibcAllocator) GTEST_SKIP() << "retention is glibc's mallopt, and this allocator is another";
    unsetenv("GBL_RETAIN_HOST_BLOCKS");
    const long retained = inChild([] { return gbl::retainHostBlocks(true) ? faultsOfSecondRound() : -2L; });
    const long byDefault = inChild([] { return gbl::retainHostBlocks(false) ? -2L : faultsOfSecondRound(); });
    ASSERT_GE(retained, 0) << "retainHostBlocks(true) did not take (mallopt refused)";
    ASSERT_GE(byDefault, 0);
    // Retained: the second round reuses the first round's pages. The default maps the block
    // afresh (or grows the heap into new pages) and faults each page again.
    EXPECT_LT(retained, kPages / 20) << "retained, the second round faulted " << retained << " of " << kPages << " pages";
    EXPECT_GT(byDefault, kPages / 2) << "the default policy faulted only " << byDefault << " of " << kPages << " pages";
}

TEST(HostHeap, TheEnvironmentOverridesTheChoice) {
    const long off = inChild([] {
        setenv("GBL_RETAIN_HOST_BLOCKS", "0", 1);
        return gbl::retainHostBlocks(true) ? 1L : 0L;
    });
    EXPECT_EQ(off, 0);
    if (!kGlibcAllocator) GTEST_SKIP() << "retention is glibc's mallopt, and this allocator is another";
    const long on = inChild([] {
        setenv("GBL_RETAIN_HOST_BLOCKS", "1", 1);
        return gbl::retainHostBlocks(false) ? 1L : 0L;
    });
    EXPECT_EQ(on, 1);
}
