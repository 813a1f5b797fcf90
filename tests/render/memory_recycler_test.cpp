// On a GPU the context reuses freed device memory (memory_recycler.h): a render then lands in
// blocks that still hold the last render's bytes. That is only safe if every pass writes what it
// reads. Here the recycler is switched on for lavapipe with poison: every parked block is filled
// with 0xFF (NaN floats, all-ones words) before reuse. Each layout's render on recycled, poisoned
// memory must equal, bit for bit, its render on fresh memory: the HDR image, every decoded
// surface, depth, the G-buffer's and light buffers' words. The layouts cover a light pre-pass
// and material pass (crysis2-slim), checkerboard chroma reading neighbours (crysis3-thin), a
// visibility buffer (visibility-32), emissive targets (ue5) and the float reference.
#include <gtest/gtest.h>

#include <cstring>

#include "layout_catalog.h"
#include "procedural_sky.h"
#include "renderer.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

class MemoryRecyclerTest : public test::VulkanTest {};

RenderSettings settings() {
    RenderSettings s;
    s.width = 67;  // odd sizes: partial workgroups and tiles
    s.height = 45;
    s.splitSumShaderSamples = 16;
    s.decodeSurfaces = true;
    s.readTargetWords = true;
    return s;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

void expectSameRender(const RenderOutput& fresh, const RenderOutput& recycled, const std::string& layout) {
    SCOPED_TRACE(layout);
    EXPECT_TRUE(sameBits(fresh.hdr.pixels, recycled.hdr.pixels)) << "HDR image";
    const SurfaceImages& f = fresh.surfaces;
    const SurfaceImages& r = recycled.surfaces;
    const std::pair<const char*, std::pair<const Image*, const Image*>> planes[] = {
        {"normal", {&f.normal, &r.normal}},       {"base colour", {&f.baseColor, &r.baseColor}},
        {"diffuse", {&f.diffuseColor, &r.diffuseColor}}, {"specular", {&f.specularColor, &r.specularColor}},
        {"roughness", {&f.roughness, &r.roughness}}, {"metallic", {&f.metallic, &r.metallic}},
        {"occlusion", {&f.occlusion, &r.occlusion}}, {"emissive", {&f.emissive, &r.emissive}},
        {"view depth", {&f.viewDepth, &r.viewDepth}}};
    for (const auto& [name, images] : planes) EXPECT_TRUE(sameBits(images.first->pixels, images.second->pixels)) << name;
    EXPECT_EQ(f.coverage, r.coverage);
    EXPECT_TRUE(sameBits(fresh.depth, recycled.depth)) << "depth";
    EXPECT_EQ(fresh.targetWords, recycled.targetWords) << "G-buffer words";
    EXPECT_EQ(fresh.lightBufferWords, recycled.lightBufferWords) << "light buffer words";
}

TEST_F(MemoryRecyclerTest, RendersOnPoisonedRecycledMemoryEqualRendersOnFreshMemory) {
    VulkanContext& c = ctx();
    ASSERT_FALSE(c.recycler.enabled() && c.info.type == VK_PHYSICAL_DEVICE_TYPE_CPU)
        << "the recycler must be off on a CPU device (its 4K peak memory)";
    const Scene scene = makeSphereGridScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    const std::vector<std::string> names = {"crysis2-slim", "crysis3-thin", "visibility-32", "ue5-velocity", "reference"};
    std::vector<GBufferWiring> wirings;
    for (const std::string& n : names) wirings.push_back(generateWiring(loadLayout(n)));
    Renderer renderer(c, scene, sky);

    const bool wasOn = c.recycler.enabled();
    c.recycler.enable(c.device, false);
    std::vector<RenderOutput> fresh;
    for (const GBufferWiring& w : wirings) fresh.push_back(renderer.render(w, settings()));

    uint32_t mappable = 0;
    for (uint32_t t = 0; t < c.memoryProperties.memoryTypeCount; ++t)
        if (c.memoryProperties.memoryTypes[t].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) mappable |= 1u << t;
    c.recycler.enable(c.device, true);
    c.recycler.poisonParked(mappable);
    const uint64_t reusedBefore = c.recycler.reused();
    // Twice round: the second round's renders take the blocks the first round parked (poisoned).
    for (int round = 0; round < 2; ++round)
        for (size_t i = 0; i < wirings.size(); ++i) expectSameRender(fresh[i], renderer.render(wirings[i], settings()), names[i]);
    const uint64_t reused = c.recycler.reused() - reusedBefore;
    c.recycler.poisonParked(0);
    c.recycler.clear();
    c.recycler.enable(c.device, wasOn);
    EXPECT_GT(reused, 20u) << "the renders took too few recycled blocks for this test to mean anything";
    std::printf("[ recycler ] %zu layouts x 2 rounds on poisoned recycled memory: %llu blocks reused, all equal\n",
                names.size(), static_cast<unsigned long long>(reused));
}

}  // namespace
}  // namespace gbl
