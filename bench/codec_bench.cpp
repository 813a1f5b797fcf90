// codec_bench: throughput of the CPU mirror (src/encoding/encodings.h, src/codec/cpu_codec.h), each figure beside
// memcpy of the same number of bytes measured in the same run.
//
//   encode/<encoding>, decode/<encoding>   one primitive over 1M elements (floats, colours or unit
//                                          normals -> packed codes in the smallest word that holds them)
//   layout_encode/<layout>, layout_decode/<layout>
//                                          a whole 1920x1080 image of Surfaces through CpuCodec, on
//                                          hardwareThreads() threads, into reused buffers
//   memcpy/bytes:<n>                       memcpy of n bytes (per-encoding sizes), one thread
//   memcpy/bytes:<n>/threads:<t>           memcpy of n bytes (per-layout sizes and the whole Surface
//                                          image), on 1 thread and split over the codec's t threads
//                                          (parallelFor, as the codec)
//
// Counters: pixels_per_s (elements or pixels per second), GB_per_s (encoded G-buffer bytes per
// second, 1e9 bytes), bytes (encoded bytes per iteration: match it to memcpy/bytes:<n> for the
// ratio; bench/run.sh prints the ratios); per layout also threads, bytes_per_pixel,
// surface_bytes_per_pixel (sizeof(Surface)) and material_bytes_per_pixel (deferred lighting's
// material words, which the codec writes and reads too) for the memory-bound roofline.
// Per-encoding benchmarks are single-threaded and timed in CPU time (steady on a shared, loaded
// machine); the per-layout ones and their memcpy run on several threads and are timed in wall
// time (CPU time would count the calling thread only).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "cpu_codec.h"
#include "encodings.h"
#include "encodings_fast.h"
#include "layout.h"
#include "layout_catalog.h"
#include "parallel_for.h"
#include "surface.h"
#include "wiring_codegen.h"

namespace {

using namespace gbl::enc;

constexpr size_t kElements = size_t(1) << 20;  // 1M
constexpr int kImageWidth = 1920;
constexpr int kImageHeight = 1080;

std::set<int64_t>& memcpySizes() {  // per-encoding sizes: single-threaded, CPU time
    static std::set<int64_t> sizes;
    return sizes;
}
std::set<int64_t>& layoutMemcpySizes() {  // per-layout sizes: 1 and codecThreads() threads, wall time
    static std::set<int64_t> sizes;
    return sizes;
}

// The threads the layout benchmarks run on: CpuCodec's default.
int codecThreads() { return gbl::hardwareThreads(); }

void setCounters(benchmark::State& state, double elements, double bytes) {
    const double it = double(state.iterations());
    state.counters["pixels_per_s"] = benchmark::Counter(elements * it, benchmark::Counter::kIsRate);
    state.counters["GB_per_s"] = benchmark::Counter(bytes * it / 1e9, benchmark::Counter::kIsRate);
    state.counters["bytes"] = benchmark::Counter(bytes);
    state.SetBytesProcessed(int64_t(bytes * it));
}

// ---- inputs (fixed seed) -----------------------------------------------------------------------

const std::vector<float>& unitFloats() {
    static const std::vector<float> v = [] {
        std::mt19937 rng(1);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        std::vector<float> out(kElements);
        for (float& x : out) x = u(rng);
        return out;
    }();
    return v;
}
const std::vector<float>& signedFloats() {
    static const std::vector<float> v = [] {
        std::vector<float> out(unitFloats());
        for (float& x : out) x = 2.0f * x - 1.0f;
        return out;
    }();
    return v;
}
const std::vector<vec3>& colours() {
    static const std::vector<vec3> v = [] {
        std::mt19937 rng(2);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        std::vector<vec3> out(kElements);
        for (vec3& c : out) c = vec3(u(rng), u(rng), u(rng));
        return out;
    }();
    return v;
}
const std::vector<vec3>& normals() {
    static const std::vector<vec3> v = [] {
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        std::vector<vec3> out(kElements);
        for (vec3& n : out) {
            const float z = 1.0f - 2.0f * u(rng), phi = 6.2831853f * u(rng);
            const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
            n = vec3(r * std::cos(phi), r * std::sin(phi), z);
        }
        return out;
    }();
    return v;
}

// ---- per-encoding benchmarks -------------------------------------------------------------------

// Registers encode/<name> and decode/<name>: In -> Word (packed codes) -> In.
template <class Word, class In, class Enc, class Dec>
void registerPrimitive(const std::string& name, int totalBits, const std::vector<In>& (*inputs)(), Enc enc, Dec dec) {
    const double bytes = double(kElements) * totalBits / 8.0;
    memcpySizes().insert(int64_t(std::llround(bytes)));
    benchmark::RegisterBenchmark(("encode/" + name).c_str(), [=](benchmark::State& state) {
        const std::vector<In>& in = inputs();
        std::vector<Word> out(in.size());
        for (auto _ : state) {
            for (size_t i = 0; i < in.size(); ++i) out[i] = Word(enc(in[i]));
            benchmark::DoNotOptimize(out.data());
            benchmark::ClobberMemory();
        }
        setCounters(state, double(in.size()), std::llround(bytes));
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("decode/" + name).c_str(), [=](benchmark::State& state) {
        const std::vector<In>& in = inputs();
        std::vector<Word> codes(in.size());
        for (size_t i = 0; i < in.size(); ++i) codes[i] = Word(enc(in[i]));
        std::vector<In> out(in.size());
        for (auto _ : state) {
            for (size_t i = 0; i < codes.size(); ++i) out[i] = dec(uint(codes[i]));
            benchmark::DoNotOptimize(out.data());
            benchmark::ClobberMemory();
        }
        setCounters(state, double(in.size()), std::llround(bytes));
    })->Unit(benchmark::kMillisecond);
}

uint pack3(uvec3 c, uint bits) { return c.x | (c.y << bits) | (c.z << (2 * bits)); }
uvec3 unpack3(uint w, uint bits) {
    const uint m = (1u << bits) - 1u;
    return uvec3(w & m, (w >> bits) & m, (w >> (2 * bits)) & m);
}
uint pack2(uvec2 c, uint bits) { return c.x | (c.y << bits); }
uvec2 unpack2(uint w, uint bits) {
    const uint m = (1u << bits) - 1u;
    return uvec2(w & m, (w >> bits) & m);
}
uvec3 quantizeUnorm3(vec3 c, uint bits) {
    return uvec3(quantizeUnorm(c.x, bits), quantizeUnorm(c.y, bits), quantizeUnorm(c.z, bits));
}
vec3 dequantizeUnorm3(uvec3 c, uint bits) {
    return vec3(dequantizeUnorm(c.x, bits), dequantizeUnorm(c.y, bits), dequantizeUnorm(c.z, bits));
}

void registerPrimitives() {
    // Scalars.
    registerPrimitive<uint8_t>("unorm8", 8, unitFloats, [](float x) { return quantizeUnorm(x, 8); },
                               [](uint c) { return dequantizeUnorm(c, 8); });
    registerPrimitive<uint16_t>("unorm16", 16, unitFloats, [](float x) { return quantizeUnorm(x, 16); },
                                [](uint c) { return dequantizeUnorm(c, 16); });
    registerPrimitive<uint8_t>("snorm8", 8, signedFloats, [](float x) { return quantizeSnorm(x, 8); },
                               [](uint c) { return dequantizeSnorm(c, 8); });
    registerPrimitive<uint16_t>("float16", 16, unitFloats, [](float x) { return encodeFloat16(x); },
                                [](uint c) { return decodeFloat16(c); });
    registerPrimitive<uint16_t>("float11", 11, unitFloats, [](float x) { return encodeFloat11(x); },
                                [](uint c) { return decodeFloat11(c); });
    registerPrimitive<uint16_t>("float10", 10, unitFloats, [](float x) { return encodeFloat10(x); },
                                [](uint c) { return decodeFloat10(c); });
    registerPrimitive<uint32_t>("float32", 32, unitFloats, [](float x) { return encodeFloat32(x); },
                                [](uint c) { return decodeFloat32(c); });
    registerPrimitive<uint32_t>("depth24", 24, unitFloats, [](float x) { return quantizeDepth24(x); },
                                [](uint c) { return dequantizeDepth24(c); });
    registerPrimitive<uint8_t>("gloss8", 8, unitFloats, [](float x) { return quantizeUnorm(glossFromRoughness(x), 8); },
                               [](uint c) { return roughnessFromGloss(dequantizeUnorm(c, 8)); });
    registerPrimitive<uint8_t>(
        "smoothness_cry8", 8, unitFloats, [](float x) { return quantizeUnorm(smoothnessFromRoughnessCry(x), 8); },
        [](uint c) { return roughnessFromSmoothnessCry(dequantizeUnorm(c, 8)); });

    // Colours (linear RGB in [0,1]^3).
    registerPrimitive<uint32_t>(
        "srgb8", 24, colours,
        [](vec3 c) { return pack3(uvec3(encodeSrgb8(c.x), encodeSrgb8(c.y), encodeSrgb8(c.z)), 8); },
        [](uint w) {
            const uvec3 c = unpack3(w, 8);
            return vec3(decodeSrgb8(c.x), decodeSrgb8(c.y), decodeSrgb8(c.z));
        });
    registerPrimitive<uint32_t>(
        "ycbcr8", 24, colours, [](vec3 c) { return pack3(quantizeUnorm3(rgbToYCbCr(c), 8), 8); },
        [](uint w) { return yCbCrToRgb(dequantizeUnorm3(unpack3(w, 8), 8)); });
    registerPrimitive<uint32_t>(
        "ycbcr_sqrt8", 24, colours, [](vec3 c) { return pack3(quantizeUnorm3(rgbToYCbCrSqrt(c), 8), 8); },
        [](uint w) { return yCbCrSqrtToRgb(dequantizeUnorm3(unpack3(w, 8), 8)); });
    registerPrimitive<uint32_t>(
        "ycocg8", 24, colours, [](vec3 c) { return pack3(quantizeUnorm3(rgbToYCoCg(c), 8), 8); },
        [](uint w) { return yCoCgToRgb(dequantizeUnorm3(unpack3(w, 8), 8)); });
    registerPrimitive<uint8_t>(
        "luma8", 8, colours, [](vec3 c) { return quantizeUnorm(lumaBt601(c), 8); },
        [](uint w) { return vec3(dequantizeUnorm(w, 8)); });

    // Unit normals.
    registerPrimitive<uint32_t>(
        "normal_xyz8", 24, normals, [](vec3 n) { return pack3(encodeNormalXyz(n, 8), 8); },
        [](uint w) { return decodeNormalXyz(unpack3(w, 8), 8); });
    registerPrimitive<uint32_t>(
        "normal_xyz10", 30, normals, [](vec3 n) { return pack3(encodeNormalXyz(n, 10), 10); },
        [](uint w) { return decodeNormalXyz(unpack3(w, 10), 10); });
    registerPrimitive<uint32_t>(
        "normal_bestfit", 24, normals, [](vec3 n) { return pack3(encodeNormalBestFit(n), 8); },
        [](uint w) { return decodeNormalBestFit(unpack3(w, 8)); });
    // The CPU codec's search (same codes, vectorised over the 128 candidates): the speed-up is the
    // ratio of the two encode rows.
    registerPrimitive<uint32_t>(
        "normal_bestfit_fast", 24, normals, [](vec3 n) { return pack3(encodeNormalBestFitFast(n), 8); },
        [](uint w) { return decodeNormalBestFit(unpack3(w, 8)); });
    registerPrimitive<uint32_t>(
        "normal_xy_zsign8", 17, normals, [](vec3 n) { return pack3(encodeNormalXyZSign(n, 8), 8); },
        [](uint w) { return decodeNormalXyZSign(unpack3(w, 8), 8); });
    registerPrimitive<uint16_t>(
        "normal_spheremap8", 16, normals, [](vec3 n) { return pack2(encodeNormalSpheremap(n, 8), 8); },
        [](uint w) { return decodeNormalSpheremap(unpack2(w, 8), 8); });
    registerPrimitive<uint16_t>(
        "normal_stereographic8", 16, normals, [](vec3 n) { return pack2(encodeNormalStereographic(n, 8), 8); },
        [](uint w) { return decodeNormalStereographic(unpack2(w, 8), 8); });
    registerPrimitive<uint16_t>(
        "normal_octahedral8", 16, normals, [](vec3 n) { return pack2(encodeNormalOctahedral(n, 8), 8); },
        [](uint w) { return decodeNormalOctahedral(unpack2(w, 8), 8); });
    registerPrimitive<uint32_t>(
        "normal_octahedral12", 24, normals, [](vec3 n) { return pack2(encodeNormalOctahedral(n, 12), 12); },
        [](uint w) { return decodeNormalOctahedral(unpack2(w, 12), 12); });
    registerPrimitive<uint16_t>(
        "normal_octahedral_precise8", 16, normals,
        [](vec3 n) { return pack2(encodeNormalOctahedralPrecise(n, 8), 8); },
        [](uint w) { return decodeNormalOctahedralPrecise(unpack2(w, 8), 8); });
}

// ---- per-layout benchmarks (cpu_codec) ---------------------------------------------------------

// A plausible 1080p image of Surfaces (fixed seed): unit normals, colours in [0,1], consistent
// diffuse/specular colours, a little emissive, positions in a few metres.
const std::vector<gbl::Surface>& surfaces() {
    static const std::vector<gbl::Surface> v = [] {
        std::mt19937 rng(4);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        const std::vector<vec3>& n = normals();
        std::vector<gbl::Surface> out(size_t(kImageWidth) * kImageHeight);
        for (size_t i = 0; i < out.size(); ++i) {
            gbl::Surface& s = out[i];
            s.normal = n[i % n.size()];
            s.baseColor = vec3(u(rng), u(rng), u(rng));
            s.metallic = u(rng) < 0.3f ? 1.0f : 0.0f;
            s.roughness = u(rng);
            s.specular = 0.5f;
            s.specularColor = glm::mix(vec3(0.04f), s.baseColor, s.metallic);
            s.diffuseColor = s.baseColor * (1.0f - s.metallic);
            s.occlusion = u(rng);
            s.emissive = u(rng) < 0.05f ? vec3(u(rng), u(rng), u(rng)) : vec3(0.0f);
            s.position = vec3(4.0f * u(rng) - 2.0f, 4.0f * u(rng) - 2.0f, -1.0f - 8.0f * u(rng));
        }
        return out;
    }();
    return v;
}

// Encoded bytes of one image: the layout's colour targets (the CPU mirror does not produce depth).
double layoutImageBytes(const gbl::Layout& layout) {
    double perPixel = 0.0;
    for (const gbl::Target& t : layout.targets) perPixel += t.bytes();
    return perPixel * kImageWidth * kImageHeight;
}

void setLayoutCounters(benchmark::State& state, const gbl::Layout& layout, const gbl::CpuCodec& codec,
                       double bytes) {
    const double pixels = double(kImageWidth) * kImageHeight;
    setCounters(state, pixels, std::llround(bytes));
    state.counters["bytes_per_pixel"] = benchmark::Counter(bytes / pixels);
    state.counters["surface_bytes_per_pixel"] = benchmark::Counter(double(sizeof(gbl::Surface)));
    state.counters["material_bytes_per_pixel"] = benchmark::Counter(16.0 * gbl::materialTargetCount(layout));
    state.counters["threads"] = benchmark::Counter(codec.threads());
}

void registerLayouts() {
    // The whole image of Surfaces (182 MB at 1080p, always beyond the 32 MiB L3): the copy rate
    // from and to DRAM, for the bound summarize.py derives from it (the G-buffers are 8-41 MB, so
    // their own memcpy runs partly in L3, faster than the codec's Surface traffic ever can).
    layoutMemcpySizes().insert(int64_t(sizeof(gbl::Surface)) * kImageWidth * kImageHeight);
    std::vector<std::string> names;
    try {
        names = gbl::listLayoutNames();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "codec_bench: no layouts (%s); per-layout benchmarks skipped\n", e.what());
        return;
    }
    for (const std::string& name : names) {
        gbl::Layout layout;
        try {
            layout = gbl::loadLayout(name);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "codec_bench: layout %s skipped: %s\n", name.c_str(), e.what());
            continue;
        }
        const double bytes = layoutImageBytes(layout);
        layoutMemcpySizes().insert(int64_t(std::llround(bytes)));
        // Both write into buffers allocated before timing, as memcpy does: a fresh 20-180 MB
        // vector per iteration would time the kernel's page faults, not the codec.
        benchmark::RegisterBenchmark(("layout_encode/" + name).c_str(), [=](benchmark::State& state) {
            const gbl::CpuCodec codec(layout, gbl::CpuCodecOptions{codecThreads()});
            const std::vector<gbl::Surface>& in = surfaces();
            gbl::CpuGBuffer g = codec.encode(in, kImageWidth, kImageHeight);
            for (auto _ : state) {
                codec.encode(in, kImageWidth, kImageHeight, g);
                benchmark::DoNotOptimize(g.targetWords.data());
                benchmark::ClobberMemory();
            }
            setLayoutCounters(state, layout, codec, bytes);
        })->Unit(benchmark::kMillisecond)->UseRealTime();
        benchmark::RegisterBenchmark(("layout_decode/" + name).c_str(), [=](benchmark::State& state) {
            const gbl::CpuCodec codec(layout, gbl::CpuCodecOptions{codecThreads()});
            const gbl::CpuGBuffer g = codec.encode(surfaces(), kImageWidth, kImageHeight);
            std::vector<gbl::Surface> out = codec.decode(g);
            for (auto _ : state) {
                codec.decode(g, out);
                benchmark::DoNotOptimize(out.data());
                benchmark::ClobberMemory();
            }
            setLayoutCounters(state, layout, codec, bytes);
        })->Unit(benchmark::kMillisecond)->UseRealTime();
    }
}

// ---- memcpy of the same byte counts --------------------------------------------------------------

void registerMemcpy() {
    for (const int64_t n : memcpySizes()) {
        benchmark::RegisterBenchmark(("memcpy/bytes:" + std::to_string(n)).c_str(), [n](benchmark::State& state) {
            std::vector<unsigned char> src(size_t(n), 1), dst(size_t(n), 0);
            for (auto _ : state) {
                std::memcpy(dst.data(), src.data(), size_t(n));
                benchmark::DoNotOptimize(dst.data());
                benchmark::ClobberMemory();
            }
            setCounters(state, double(n), double(n));
        })->Unit(benchmark::kMillisecond);
    }
    // The machine's copy bandwidth for the layout sizes: one thread, and split into as many
    // contiguous chunks as the codec has threads, started the same way (parallelFor per call).
    const std::set<int> threadCounts = {1, codecThreads()};
    for (const int64_t n : layoutMemcpySizes())
        for (const int threads : threadCounts) {
            const std::string name = "memcpy/bytes:" + std::to_string(n) + "/threads:" + std::to_string(threads);
            benchmark::RegisterBenchmark(name.c_str(), [n, threads](benchmark::State& state) {
                std::vector<unsigned char> src(size_t(n), 1), dst(size_t(n), 0);
                for (auto _ : state) {
                    gbl::parallelFor(n, threads, [&](int64_t begin, int64_t end) {
                        std::memcpy(dst.data() + begin, src.data() + begin, size_t(end - begin));
                    });
                    benchmark::DoNotOptimize(dst.data());
                    benchmark::ClobberMemory();
                }
                setCounters(state, double(n), double(n));
                state.counters["threads"] = benchmark::Counter(threads);
            })->Unit(benchmark::kMillisecond)->UseRealTime();
        }
}

}  // namespace

int main(int argc, char** argv) {
    registerPrimitives();
    registerLayouts();
    registerMemcpy();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
