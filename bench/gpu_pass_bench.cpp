// gpu_pass_bench: the G-buffer pass and the lighting pass of every layout in layouts/, on the
// built-in scene under the built-in sky, at 1920x1080 (and 3840x2160 with GBL_BENCH_4K=1 or
// --gbl_4k), timed with the renderer's Vulkan timestamp queries (RenderOutput::timings) and
// reported through UseManualTime. Each (layout, size) renders one warm-up frame first (pipeline
// compile, first-touch allocations), which is not measured.
//
//   gbuffer_pass/<layout>/<W>x<H>    manual time = timings.gbufferMs of each frame
//   lighting_pass/<layout>/<W>x<H>   manual time = timings.lightingMs of each frame
//   readback/<layout>/<W>x<H>/decode_pass, .../cpu_codec
//                                    manual time = the frame's read-back stage (StageClock): HDR,
//                                    depth and the decoded surfaces, by the decode pass or by the
//                                    CPU codec from the raw words (RenderSettings::decodeOnCpu)
//
// Every frame times both passes, so lighting_pass first uses the lighting times of the frames
// that gbuffer_pass of the same layout and size rendered (same frames, not re-rendered) and
// renders new frames only when those run out. Counters: bytes_per_pixel (G-buffer targets +
// depth-stencil, layout.h bytesPerPixel), bytes_per_frame, light_buffer_bytes_per_pixel
// (deferred lighting), peak_rss_MiB (getrusage ru_maxrss of the whole process so far: on
// lavapipe "GPU" memory is host memory and is included).
//
// Environment: GBL_BENCH_4K=1 adds 3840x2160; GBL_BENCH_LAYOUTS=a,b limits the layouts;
// GBL_BENCH_DEVICE picks the Vulkan device as --device does (default: lavapipe; "gpu" for a GPU).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "gbuffer_wiring.h"
#include "layout.h"
#include "layout_catalog.h"
#include "procedural_sky.h"
#include "renderer.h"
#include "scene.h"
#include "stage_clock.h"
#include "vk_context.h"
#include "wiring_codegen.h"

namespace {

struct Gpu {
    std::unique_ptr<gbl::VulkanContext> ctx;
    gbl::Scene scene;
    gbl::EnvironmentMap environment;
    std::unique_ptr<gbl::Renderer> renderer;
};
Gpu& gpu() {
    static Gpu g;
    return g;
}

double peakRssMiB() {
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return double(ru.ru_maxrss) / 1024.0;  // Linux: KiB
}

struct Size {
    uint32_t width, height;
    std::string text() const { return std::to_string(width) + "x" + std::to_string(height); }
};

// Lighting times of frames already rendered (by gbuffer_pass), per "layout/WxH".
std::map<std::string, std::deque<double>>& spareLightingMs() {
    static std::map<std::string, std::deque<double>> m;
    return m;
}
std::set<std::string>& warmed() {
    static std::set<std::string> s;
    return s;
}

gbl::RenderOutput renderFrame(const gbl::GBufferWiring& wiring, Size size) {
    gbl::RenderSettings settings;
    settings.width = size.width;
    settings.height = size.height;
    return gpu().renderer->render(wiring, settings);
}

void warmUp(const std::string& key, const gbl::GBufferWiring& wiring, Size size) {
    if (warmed().insert(key).second) (void)renderFrame(wiring, size);
}

void setCounters(benchmark::State& state, const gbl::Layout& layout, Size size) {
    const double bpp = gbl::bytesPerPixel(layout);
    state.counters["bytes_per_pixel"] = bpp;
    state.counters["bytes_per_frame"] = bpp * double(size.width) * double(size.height);
    state.counters["light_buffer_bytes_per_pixel"] = gbl::lightBufferBytesPerPixel(layout);
    state.counters["peak_rss_MiB"] = peakRssMiB();
}

void registerLayout(const gbl::Layout& layout, Size size) {
    const auto wiring = std::make_shared<gbl::GBufferWiring>(gbl::generateWiring(layout));
    const std::string key = layout.name + "/" + size.text();
    benchmark::RegisterBenchmark(("gbuffer_pass/" + key).c_str(), [=](benchmark::State& state) {
        try {
            warmUp(key, *wiring, size);
            for (auto _ : state) {
                const gbl::RenderOutput out = renderFrame(*wiring, size);
                state.SetIterationTime(out.timings.gbufferMs / 1000.0);
                spareLightingMs()[key].push_back(out.timings.lightingMs);
            }
            setCounters(state, layout, size);
        } catch (const std::exception& e) {
            state.SkipWithError(e.what());
        }
    })->UseManualTime()->Iterations(3)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("lighting_pass/" + key).c_str(), [=](benchmark::State& state) {
        try {
            warmUp(key, *wiring, size);
            std::deque<double>& spare = spareLightingMs()[key];
            for (auto _ : state) {
                double ms;
                if (!spare.empty()) {
                    ms = spare.front();
                    spare.pop_front();
                } else {
                    ms = renderFrame(*wiring, size).timings.lightingMs;
                }
                state.SetIterationTime(ms / 1000.0);
            }
            setCounters(state, layout, size);
        } catch (const std::exception& e) {
            state.SkipWithError(e.what());
        }
    })->UseManualTime()->Iterations(3)->Unit(benchmark::kMillisecond);
}

// The read-back of compare's renders (decoded surfaces, no raw words kept), one way or the other.
void registerReadback(const gbl::Layout& layout, Size size) {
    const auto wiring = std::make_shared<gbl::GBufferWiring>(gbl::generateWiring(layout));
    for (const bool cpu : {false, true}) {
        const std::string name = "readback/" + layout.name + "/" + size.text() + (cpu ? "/cpu_codec" : "/decode_pass");
        benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
            try {
                gbl::RenderSettings settings;
                settings.width = size.width;
                settings.height = size.height;
                settings.decodeSurfaces = true;
                settings.readTargetWords = false;
                settings.decodeOnCpu = cpu;
                if (cpu && !gbl::Renderer::decodesOnCpu(*wiring, settings)) {
                    state.SkipWithError("no CPU decoder for this layout (visibility buffer)");
                    return;
                }
                (void)gpu().renderer->render(*wiring, settings);  // warm-up: pipelines, first-touch pages
                for (auto _ : state) {
                    const double before = gbl::StageClock::global().read()[gbl::Stage::Readback];
                    const gbl::RenderOutput out = gpu().renderer->render(*wiring, settings);
                    state.SetIterationTime((gbl::StageClock::global().read()[gbl::Stage::Readback] - before) / 1000.0);
                    benchmark::DoNotOptimize(out.surfaces.normal.pixels.data());
                }
                setCounters(state, layout, size);
            } catch (const std::exception& e) {
                state.SkipWithError(e.what());
            }
        })->UseManualTime()->Iterations(3)->Unit(benchmark::kMillisecond);
    }
}

std::vector<std::string> selectedLayouts() {
    std::vector<std::string> names;
    if (const char* env = std::getenv("GBL_BENCH_LAYOUTS"); env && *env) {
        std::stringstream ss(env);
        for (std::string n; std::getline(ss, n, ',');)
            if (!n.empty()) names.push_back(n);
        return names;
    }
    return gbl::listLayoutNames();
}

}  // namespace

int main(int argc, char** argv) {
    bool with4k = false;
    if (const char* env = std::getenv("GBL_BENCH_4K")) with4k = std::strcmp(env, "1") == 0;
    std::vector<char*> args;
    for (int i = 0; i < argc; ++i) {
        if (std::strcmp(argv[i], "--gbl_4k") == 0)
            with4k = true;
        else
            args.push_back(argv[i]);
    }
    int n = int(args.size());
    benchmark::Initialize(&n, args.data());
    if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;

    try {
        const char* device = std::getenv("GBL_BENCH_DEVICE");
        Gpu& g = gpu();
        g.ctx = std::make_unique<gbl::VulkanContext>(gbl::DeviceOptions{device ? device : "", false});
        g.scene = gbl::makeDefaultScene();
        g.environment = gbl::makeProceduralSky();
        g.renderer = std::make_unique<gbl::Renderer>(*g.ctx, g.scene, g.environment);
        benchmark::AddCustomContext("vulkan_device", g.ctx->info.name);
        benchmark::AddCustomContext("vulkan_driver", g.ctx->info.driver);
        benchmark::AddCustomContext("gbl_4k", with4k ? "1" : "0");

        std::vector<Size> sizes = {{1920, 1080}};
        if (with4k) sizes.push_back({3840, 2160});
        for (const Size size : sizes)
            for (const std::string& name : selectedLayouts()) {
                registerLayout(gbl::loadLayout(name), size);
                registerReadback(gbl::loadLayout(name), size);
            }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gpu_pass_bench: %s\n", e.what());
        return 1;
    }

    gbl::StageClock::global().start();  // the renderer marks its read-back stage on it
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    std::fprintf(stderr, "gpu_pass_bench: peak RSS of the process %.1f MiB\n", peakRssMiB());
    gpu().renderer.reset();
    gpu().ctx.reset();
    return 0;
}
