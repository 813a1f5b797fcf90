// png_bench: writing one 3840x2160 RGB PNG, the slowest single file of a 4K `compare`, by the
// encoder writePng used before (stb_image_write, Sub filter forced, zlib compress2 at level 1:
// tests/support/stb_png_encoder.h) and by encodePng (src/image/png_writer.h) with one band (one core)
// and with its default bands (24 at 4K RGB) on hardwareThreads() threads. All in memory: no disk.
//
//   png/old_stb           the old encoder
//   png/new/chunks:1      encodePng, one band: the same bytes as the old encoder
//   png/new/chunks:0      encodePng, pngChunkCount bands (the default writePng uses)
//   png/new/chunks:N      other band counts, for the size / speed trade of the band size
//
// The image: a viridis error heat map (applyColorMap, as compare's error images) of a smooth
// field plus per-pixel noise; GBL_BENCH_PNG_IMAGE=<file.png> encodes that PNG instead (e.g. a
// heat map from a real 4K compare). Counters: bytes (the file's size), chunks, threads,
// Mpix_per_s, cpu_ms (CPU time of the whole process, every thread, per encode: the work the
// bands cost, which a loaded machine does not change much). Wall time (the work runs on several
// threads).
#include <benchmark/benchmark.h>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <sys/resource.h>
#include <vector>

#include "color_map.h"
#include "image_io.h"
#include "parallel_for.h"
#include "png_writer.h"

#include "stb_png_encoder.h"  // the old encoder (tests/support)

namespace {

constexpr int kWidth = 3840, kHeight = 2160;

const gbl::Image8& benchImage() {
    static const gbl::Image8 image = [] {
        if (const char* path = std::getenv("GBL_BENCH_PNG_IMAGE"); path && *path) return gbl::readImage8(path);
        // Relative error of a render: broad smooth structure (lighting, geometry) with
        // per-pixel noise (quantisation of the encodings), mapped as compare maps errors.
        gbl::Image field(kWidth, kHeight, 1);
        std::mt19937 rng(11);
        std::uniform_real_distribution<float> noise(-0.04f, 0.04f);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const float smooth = 0.35f + 0.25f * std::sin(float(x) / 310.0f) * std::cos(float(y) / 170.0f) +
                                     0.15f * float(x + y) / float(kWidth + kHeight);
                field.pixels[size_t(y) * kWidth + size_t(x)] = smooth + noise(rng);
            }
        return gbl::applyColorMap(field, 0.0f, 1.0f);
    }();
    return image;
}

std::vector<unsigned char> oldEncode(const gbl::Image8& image) {
    std::vector<unsigned char> png = gbl::test::stbPngSubLevel1(image);
    if (png.empty()) std::abort();
    return png;
}

// CPU seconds of the whole process so far, every thread (user + system).
double processCpuSeconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

void setCounters(benchmark::State& state, const gbl::Image8& image, size_t bytes, int chunks, double cpuSeconds) {
    state.counters["cpu_ms"] = 1e3 * cpuSeconds / double(state.iterations());
    state.counters["bytes"] = double(bytes);
    state.counters["chunks"] = chunks;
    state.counters["threads"] = gbl::hardwareThreads();
    state.counters["Mpix_per_s"] = benchmark::Counter(double(image.width) * image.height * 1e-6,
                                                      benchmark::Counter::kIsIterationInvariantRate);
}

void BM_PngOld(benchmark::State& state) {
    const gbl::Image8& image = benchImage();
    size_t bytes = 0;
    const double cpu = processCpuSeconds();
    for (auto _ : state) {
        const auto png = oldEncode(image);
        bytes = png.size();
        benchmark::DoNotOptimize(png.data());
    }
    setCounters(state, image, bytes, 1, processCpuSeconds() - cpu);
}
BENCHMARK(BM_PngOld)->Name("png/old_stb")->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PngNew(benchmark::State& state) {
    const gbl::Image8& image = benchImage();
    const int chunks = int(state.range(0));
    size_t bytes = 0;
    const double cpu = processCpuSeconds();
    for (auto _ : state) {
        const auto png = gbl::encodePng(image, chunks);
        bytes = png.size();
        benchmark::DoNotOptimize(png.data());
    }
    setCounters(state, image, bytes, chunks > 0 ? std::min(chunks, image.height) : gbl::pngChunkCount(image),
                processCpuSeconds() - cpu);
}
BENCHMARK(BM_PngNew)
    ->Name("png/new")
    ->ArgName("chunks")
    ->Arg(1)
    ->Arg(0)
    ->Arg(12)
    ->Arg(48)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
