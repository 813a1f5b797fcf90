// compare_bench: the CPU side of `gbufferlab compare` at 1920x1080 on synthetic images (fixed
// seed): what one layout's comparison costs outside the GPU passes.
//
//   run_metrics/no_hdr_flip   computeRunMetrics, attributes + image errors + LDR-FLIP
//   run_metrics/full          the same with HDR-FLIP (as `compare --hdr-flip` runs)
//   flip_ldr                  flipLdr of two sRGB images
//   flip_hdr                  flipHdr of two linear HDR images (exposure count as a counter)
//
// `compare` itself, end to end and split into stages, is timed by `bench/run.sh e2e` (its
// timings.json).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "flip.h"
#include "image.h"
#include "run_metrics.h"
#include "surface_images.h"

namespace {

constexpr int kW = 1920, kH = 1080;

// A smooth scene-like image plus per-pixel noise of amplitude `noise` (fixed seed).
gbl::Image makeImage(int channels, float scale, float noise, unsigned seed) {
    gbl::Image img(kW, kH, channels);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < channels; ++c) {
                const float base = 0.5f + 0.4f * std::sin(0.01f * float(x) * float(c + 1)) * std::cos(0.013f * float(y));
                img.at(x, y, c) = std::max(0.0f, scale * base * (1.0f + noise * u(rng)));
            }
    return img;
}

gbl::SurfaceImages makeSurfaces(float noise, unsigned seed) {
    gbl::SurfaceImages s;
    s.normal = makeImage(3, 1.0f, noise, seed + 1);
    for (size_t i = 0; i < s.normal.pixelCount(); ++i) {  // unit normals
        float* n = &s.normal.pixels[i * 3];
        n[0] = 2.0f * n[0] - 1.0f;
        n[1] = 2.0f * n[1] - 1.0f;
        n[2] = 0.3f + n[2];
        const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int c = 0; c < 3; ++c) n[c] /= len;
    }
    s.baseColor = makeImage(3, 1.0f, noise, seed + 2);
    s.diffuseColor = makeImage(3, 1.0f, noise, seed + 3);
    s.specularColor = makeImage(3, 0.5f, noise, seed + 4);
    s.roughness = makeImage(1, 1.0f, noise, seed + 5);
    s.metallic = makeImage(1, 1.0f, noise, seed + 6);
    s.occlusion = makeImage(1, 1.0f, noise, seed + 7);
    s.emissive = makeImage(3, 0.1f, noise, seed + 8);
    s.depth = makeImage(1, 1.0f, 0.0f, seed + 9);
    s.viewDepth = makeImage(1, 10.0f, noise, seed + 10);
    s.coverage.assign(size_t(kW) * kH, 1);
    for (size_t i = 0; i < s.coverage.size(); i += 7) s.coverage[i] = 0;  // some background
    return s;
}

struct Inputs {
    gbl::SurfaceImages reference = makeSurfaces(0.0f, 10);
    gbl::SurfaceImages test = makeSurfaces(0.02f, 10);
    gbl::Image referenceHdr = makeImage(4, 4.0f, 0.0f, 30);
    gbl::Image testHdr = makeImage(4, 4.0f, 0.02f, 30);
    gbl::Image referenceSrgb = makeImage(3, 1.0f, 0.0f, 40);
    gbl::Image testSrgb = makeImage(3, 1.0f, 0.02f, 40);
};
const Inputs& inputs() {
    static const Inputs in;
    return in;
}

void pixelRate(benchmark::State& state) {
    state.counters["pixels_per_s"] =
        benchmark::Counter(double(kW) * kH * double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_RunMetrics(benchmark::State& state) {
    const Inputs& in = inputs();
    gbl::RunMetricsOptions options;
    options.hdrFlip = state.range(0) != 0;
    for (auto _ : state) {
        gbl::RunMetrics m = gbl::computeRunMetrics(in.reference, in.test, in.referenceHdr, in.testHdr, 1.0f, options);
        benchmark::DoNotOptimize(m);
    }
    pixelRate(state);
}
BENCHMARK(BM_RunMetrics)->Name("run_metrics/no_hdr_flip")->Arg(0)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RunMetrics)->Name("run_metrics/full")->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_FlipLdr(benchmark::State& state) {
    const Inputs& in = inputs();
    for (auto _ : state) {
        gbl::Image map = gbl::flipLdr(in.referenceSrgb, in.testSrgb);
        benchmark::DoNotOptimize(map.pixels.data());
    }
    pixelRate(state);
}
BENCHMARK(BM_FlipLdr)->Name("flip_ldr")->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_FlipHdr(benchmark::State& state) {
    const Inputs& in = inputs();
    int exposures = 0;
    for (auto _ : state) {
        gbl::HdrFlipResult r = gbl::flipHdr(in.referenceHdr, in.testHdr);
        exposures = r.range.count;
        benchmark::DoNotOptimize(r.flip.pixels.data());
    }
    pixelRate(state);
    state.counters["exposures"] = exposures;
}
BENCHMARK(BM_FlipHdr)->Name("flip_hdr")->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
