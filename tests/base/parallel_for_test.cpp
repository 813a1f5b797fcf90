// parallelFor (src/base/parallel_for.h) covers its range once in contiguous chunks and passes an
// exception on only after every chunk has finished.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <vector>

#include "parallel_for.h"

namespace gbl {
namespace {

// ---------------------------------------------------------------------------------------------

TEST(ParallelFor, CoversTheRangeOnceInContiguousChunks) {
    for (int threads : {1, 2, 3, 7, 64})
        for (int64_t count : {0, 1, 2, 5, 100, 1001}) {
            std::vector<std::atomic<int>> hits(static_cast<size_t>(count));
            std::atomic<int> chunks{0};
            parallelFor(count, threads, [&](int64_t begin, int64_t end) {
                EXPECT_LT(begin, end);
                ++chunks;
                for (int64_t i = begin; i < end; ++i) ++hits[size_t(i)];
            });
            for (const std::atomic<int>& h : hits) EXPECT_EQ(h.load(), 1);
            EXPECT_EQ(chunks.load(), int(std::min<int64_t>(count, threads)));
        }
}

TEST(ParallelFor, RethrowsAfterEveryChunkFinished) {
    std::atomic<int> finished{0};
    EXPECT_THROW(parallelFor(4, 4,
                             [&](int64_t begin, int64_t) {
                                 if (begin == 2) throw std::runtime_error("chunk 2");
                                 ++finished;
                             }),
                 std::runtime_error);
    EXPECT_EQ(finished.load(), 3);
}

}  // namespace
}  // namespace gbl
