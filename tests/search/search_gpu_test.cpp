// The search's fast evaluation against the GPU (lavapipe): the CPU re-shade of the reference
// against the GPU's render of it, and the fast evaluation's ranking of layouts against full GPU
// renders measured as compare measures them (8-bit tone-mapped LDR-FLIP, mean over views).
#include <gtest/gtest.h>

#include <cstdio>

#include "compare_views.h"
#include "fast_eval.h"
#include "flip.h"
#include "ibl_cache.h"
#include "layout_catalog.h"
#include "layout_packer.h"
#include "layout_search.h"
#include "scene_inputs.h"
#include "search_reference.h"
#include "tone_map.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

constexpr uint32_t kW = 192, kH = 108;

struct Fixture {
    SceneInputs inputs = loadSceneInputs("", "", float(kW) / float(kH));
    IblMaps ibl = loadOrComputeIbl(test::sharedContext(), inputs.environment, IblSettings{});
    Renderer renderer{test::sharedContext(), inputs.scene, inputs.environment, ibl};
    std::vector<Camera> cameras;
    SearchReference reference;
    std::unique_ptr<search::FastEvaluator> evaluator;
    Fixture() {
        for (const auto& v : compare::compareViews(inputs.scene, 2, float(kW) / float(kH))) cameras.push_back(v.camera);
        // As the search (app/search_api.cpp): the reference under every depth format the tested layouts use.
        reference = renderSearchReference(renderer, cameras, kW, kH,
                                          {{"D16_UNORM", false}, {"D24_UNORM_S8_UINT", false}, {"D32_SFLOAT", true},
                                           {"D32_SFLOAT_S8_UINT", true}});
        evaluator = std::make_unique<search::FastEvaluator>(reference.views, search::shadeLights(inputs.scene.lights),
                                                            ibl, search::Objective::Flip);
    }
    // compare's flip_mean of a full GPU render of `layout`, mean over the views.
    double fullFlip(const Layout& layout) {
        const GBufferWiring wiring = generateWiring(layout);
        double sum = 0.0;
        for (size_t v = 0; v < cameras.size(); ++v) {
            RenderSettings s;
            s.width = kW;
            s.height = kH;
            s.readTargetWords = false;
            s.camera = cameras[v];
            const RenderOutput out = renderer.render(wiring, s);
            sum += flipStats(flipLdr(toneMapToSrgb8AsFloat(reference.gpuHdr[v]), toneMapToSrgb8AsFloat(out.hdr))).mean;
        }
        return sum / double(cameras.size());
    }
};

Fixture& fixture() {
    static Fixture f;
    return f;
}

class SearchGpu : public test::VulkanTest {};

TEST_F(SearchGpu, CpuReshadeOfTheReferenceMatchesTheGpuRender) {
    Fixture& f = fixture();
    for (size_t v = 0; v < f.cameras.size(); ++v) {
        const Image& gpu = f.reference.gpuHdr[v];
        const Image& cpu = f.evaluator->referenceHdr(v);
        const double flip = flipStats(flipLdr(toneMapToSrgb8AsFloat(gpu), toneMapToSrgb8AsFloat(cpu))).mean;
        double sumRel = 0.0, mean = 0.0;
        size_t covered = 0;
        auto lum = [](const Image& im, size_t i) {
            return 0.2126 * im.pixels[i * 4] + 0.7152 * im.pixels[i * 4 + 1] + 0.0722 * im.pixels[i * 4 + 2];
        };
        for (size_t i = 0; i < gpu.pixelCount(); ++i) mean += lum(gpu, i) / double(gpu.pixelCount());
        for (size_t i = 0; i < gpu.pixelCount(); ++i)
            if (f.reference.views[v].shade.covered[i]) {
                sumRel += std::abs(lum(cpu, i) - lum(gpu, i)) / std::max(lum(gpu, i), 0.01 * mean);
                ++covered;
            }
        const double meanRel = sumRel / double(covered);
        std::printf("view %zu: CPU re-shade vs GPU render: FLIP %.5f, mean relative luminance error %.5f\n", v, flip,
                    meanRel);
        // Measured (lavapipe, 192x108, built-in scene): FLIP 0.00040 / 0.00141 and mean relative
        // luminance error 0.00026 / 0.00077 on the two views (the rest is the cube's seamless
        // filtering and the GPU's filtering precision); the bounds leave room for other drivers.
        EXPECT_LT(flip, 0.01) << "view " << v;
        EXPECT_LT(meanRel, 0.01) << "view " << v;
    }
}

TEST_F(SearchGpu, FastEvaluationRanksLayoutsAsFullRendersDo) {
    Fixture& f = fixture();
    std::vector<Layout> layouts;
    for (const char* name : {"crysis3-thin", "ryse", "compact-octahedral", "ue4", "fat-naive"})
        layouts.push_back(loadLayout(name));
    // Three packer-made layouts at the cheap end (few bits: the search's territory).
    search::Genome low;
    low.normalEncoding = 3;  // spheremap 6
    low.normalBits = 6;
    low.roughnessBits = 4;
    low.colourEncoding = 7;  // luma only
    low.colourBits = 5;
    low.metallicBits = 1;
    search::Genome mid = low;
    mid.normalEncoding = 0;  // octahedral 9
    mid.normalBits = 9;
    mid.colourEncoding = 5;  // YCbCr checkerboard 6
    mid.colourBits = 6;
    search::Genome mid16 = mid;  // D16: its far geometry resolves differently (the depth variants)
    mid16.depthFormat = 0;
    mid16.normalBits = 12;
    for (const search::Genome& g : {low, mid, mid16}) {
        const search::PackResult p = search::packGenome(g, 64);
        ASSERT_TRUE(p.ok) << p.why;
        layouts.push_back(parseLayout(search::layoutText("candidate", "", p.body), "candidate.toml"));
    }
    std::vector<double> fast, full;
    for (const Layout& l : layouts) {
        fast.push_back(f.evaluator->evaluate(l, 0).flip);
        full.push_back(f.fullFlip(l));
        std::printf("%-20s fast FLIP %.5f  full-render FLIP %.5f\n", l.name.c_str(), fast.back(), full.back());
    }
    const double rho = search::spearman(fast, full);
    std::printf("Spearman rank correlation, fast vs full, %zu layouts: %.3f\n", fast.size(), rho);
    // Measured: 0.976 over 8 layouts (the one swap: ue4 0.01078 / 0.01033 against
    // compact-octahedral 0.01072 / 0.00990, within 0.6 % of each other in the fast evaluation);
    // the D16 candidate 0.06304 fast / 0.06306 full, through its depth variant.
    EXPECT_GE(rho, 0.85);
}

}  // namespace
}  // namespace gbl
