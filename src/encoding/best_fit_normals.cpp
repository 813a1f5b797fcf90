#include "best_fit_normals.h"

#include <future>
#include <stdexcept>
#include <system_error>

#include "encodings.h"
#include "encodings_fast.h"
#include "parallel_for.h"

namespace gbl::enc {

std::vector<uint32_t> generateBestFitNormalTable(int threads) {
    std::vector<uint32_t> words((kBestFitTableEntries + 3) / 4, 0u);
    std::vector<uint8_t> entries(kBestFitTableEntries);
    // Row i has i + 1 texels: rows are taken in pairs (p, 1023 - p) of 1025 texels each, so that
    // every thread's contiguous chunk of pairs holds the same work (contiguous rows left the last
    // thread three quarters of it on 2 threads).
    parallelFor(kBestFitTableSize / 2, threads > 0 ? threads : hardwareThreads(), [&](int64_t begin, int64_t end) {
        for (uint32_t p = uint32_t(begin); p < uint32_t(end); ++p)
            for (const uint32_t i : {p, kBestFitTableSize - 1u - p})
            for (uint32_t j = 0; j <= i; ++j) {
                const float mid = (float(i) + 0.5f) / float(kBestFitTableSize);
                const float lo = (float(j) + 0.5f) / float(kBestFitTableSize);
                const vec3 n = normalize(vec3(mid, lo, 1.0f));
                // The search's winner has d.z = k (q.z = 1 exactly): code.z = (k + 255) / 2.
                const uvec3 code = encodeNormalBestFitFast(n);
                const uint k = 2u * code.z - 255u;
                if (code.z < 128u || (k & 1u) == 0u) throw std::logic_error("best-fit table: unexpected search result");
                entries[i * (i + 1) / 2 + j] = uint8_t((255u - k) / 2u);
            }
    });
    for (uint32_t t = 0; t < kBestFitTableEntries; ++t) words[t >> 2] |= uint32_t(entries[t]) << ((t & 3u) * 8u);
    return words;
}

namespace {

// The one generation of the process: started by the first of prefetchBestFitNormalTable and
// bestFitNormalTable, on its own thread; the shared state outlives every caller (static). With no
// thread to be had it runs in the first get() instead (as parallelFor does its chunks).
const std::shared_future<std::vector<uint32_t>>& tableGeneration() {
    static const std::shared_future<std::vector<uint32_t>> table = [] {
        auto generate = [] { return generateBestFitNormalTable(); };
        try {
            return std::async(std::launch::async, generate).share();
        } catch (const std::system_error&) {
            return std::async(std::launch::deferred, generate).share();
        }
    }();
    return table;
}

}  // namespace

const std::vector<uint32_t>& bestFitNormalTable() { return tableGeneration().get(); }

void prefetchBestFitNormalTable() { tableGeneration(); }

}  // namespace gbl::enc
