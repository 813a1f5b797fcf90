#pragma once
// The LDR-FLIP pipeline's parts that HDR-FLIP reuses (flip.cpp defines them, flip_hdr.cpp runs
// them once per exposure). Internal to the measure library; the interface is flip.h.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "image.h"
#include "parallel_for.h"

namespace gbl::flip_pipeline {

// ---- Kernels ---------------------------------------------------------------------------------

struct Kernels {
    int csfRadius = 0;
    std::vector<float> csfA, csfRG, csfBY1, csfBY2;  // 1D, each summing to 1
    float wBY1 = 1.0f, wBY2 = 0.0f;                  // BY = wBY1 * (BY1 x BY1) + wBY2 * (BY2 x BY2)
    int featRadius = 0;
    std::vector<float> gauss, edge, point;           // 1D; see makeKernels
};

// ---- Parallel loops -----------------------------------------------------------------------------
// Every output pixel is computed by the same expression whatever the split, so the maps are
// identical for any thread count.

constexpr size_t kMinRowsPerThread = 16;
constexpr size_t kMinPixelsPerThread = 1 << 15;

// body(begin, end) over [0, count), in chunks of at least minChunk items (small images stay on
// one thread: starting threads costs more than it saves).
template <class Body>
void forChunks(size_t count, size_t minChunk, Body&& body) {
    const int threads = int(std::clamp<size_t>(count / minChunk, 1, size_t(hardwareThreads())));
    parallelFor(int64_t(count), threads, [&](int64_t b, int64_t e) { body(size_t(b), size_t(e)); });
}

// body(begin, end) over pixel ranges of an n-pixel plane.
template <class Body>
void forPixels(size_t n, Body&& body) {
    forChunks(n, kMinPixelsPerThread, body);
}

using Plane = std::vector<float>;

struct Prepared {
    Plane L, a, b;       // CSF-filtered, clamped, Hunt-adjusted CIELAB
    Plane edge, point;   // feature magnitudes |(e_x, e_y)| and |(p_x, p_y)| of the luminance
};

// Scratch planes shared by the prepare() calls of one comparison (fewer fresh pages to fault in).
struct Workspace {
    explicit Workspace(size_t n) {
        for (Plane& p : s) p.resize(n);
    }
    Plane s[7];
};

// The kernels of FLIP's colour (CSF) and feature (edge, point) filters at `ppd` pixels per degree.
Kernels makeKernels(double ppd);
// c_max of eq. (6): the largest colour difference (pure green against pure blue).
double maxColorDifference();
// Filtered colour and feature planes of one image; rgb: three planes of linear RGB in [0,1].
Prepared prepare(const Plane rgb[3], int w, int h, const Kernels& k, Workspace& ws);
// The FLIP map of two prepared images, eqs. (5)-(10), into out[0, n).
void combine(const Prepared& r, const Prepared& t, float cMax, float* out, size_t n);
// Throws a UserError (naming `what`) unless the two images can be compared.
void checkPair(const Image& ref, const Image& test, const char* what);
// Throws a UserError (naming `what`) unless 0 < ppd <= kMaxFlipPixelsPerDegree.
void checkPixelsPerDegree(double ppd, const char* what);
// v clamped to [0,1]; NaN -> 0.
inline float clamp01(float v) { return v >= 0.0f ? (v <= 1.0f ? v : 1.0f) : 0.0f; }

}  // namespace gbl::flip_pipeline
