// GPU vs CPU mirror, for every layouts/*.toml on lavapipe: random Surfaces at 256x256 are written
// by the generated writeGBuffer (a full-screen triangle into the layout's UINT targets, the
// Surface fetched from an SSBO by pixel) and the packed words must equal the CPU mirror's bit for
// bit. Then the generated readGBuffer decodes them in a compute shader and must match the CPU
// decode within a few ulps. Deferred-lighting layouts also run the material pass.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include "best_fit_normals.h"
#include "cpu_codec.h"
#include "encodings.h"
#include "layout_catalog.h"
#include "layout_files.h"
#include "layout_text.h"
#include "renderer_passes.h"
#include "shader_compiler.h"
#include "surface_support.h"
#include "vk_pipeline.h"
#include "vk_resources.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

constexpr uint32_t kSize = 256;
constexpr size_t kPixels = size_t(kSize) * kSize;
constexpr int kFloatsPerSurface = 40;  // 10 vec4, see kSurfaceIn

const char* kSurfaceIn = R"(
struct SurfaceIn { vec4 a[10]; };
layout(set = 0, binding = 0, std430) readonly buffer Surfaces { SurfaceIn surfaces[]; };
Surface fetchSurface(ivec2 p) {
    SurfaceIn i = surfaces[p.y * SIZE + p.x];
    Surface s;
    s.normal = i.a[0].xyz; s.metallic = i.a[0].w;
    s.baseColor = i.a[1].xyz; s.roughness = i.a[1].w;
    s.specularColor = i.a[2].xyz; s.specular = i.a[2].w;
    s.diffuseColor = i.a[3].xyz; s.occlusion = i.a[3].w;
    s.emissive = i.a[4].xyz; s.coat = i.a[4].w;
    s.position = i.a[5].xyz; s.coatRoughness = i.a[5].w;
    s.coatNormal = i.a[7].xyz; s.sheenRoughness = i.a[7].w;
    s.sheenColor = i.a[8].xyz; s.anisotropyStrength = i.a[8].w;
    s.anisotropyDirection = i.a[9].xyz; s.shadingModel = i.a[9].w;
    return s;
}
)";

// gblFrameIndex(): what a dither that moves with time reads (gbuffer_pass.frag.glsl: frame.band.z);
// 0, or with `frameFromSurface` each pixel's own, the bits of its SurfaceIn's a[6].x.
std::string fragmentSource(bool frameFromSurface = false) {
    return std::string("#version 450\n#extension GL_GOOGLE_include_directive : require\n#include \"surface.glsl\"\n") +
           kSurfaceIn + "uint gblFrame = 0u;\nuint gblFrameIndex() { return gblFrame; }\n" +
           "#define GBUFFER_WRITE 1\n#include \"gbuffer_wiring.glsl\"\nvoid main() { ivec2 p = ivec2(gl_FragCoord.xy); " +
           (frameFromSurface ? "gblFrame = floatBitsToUint(surfaces[p.y * SIZE + p.x].a[6].x); " : "") +
           "writeGBuffer(fetchSurface(p), p); }\n";
}

std::string decodeSource() {
    return R"(#version 450
#extension GL_GOOGLE_include_directive : require
#include "surface.glsl"
#define GBUFFER_READ 1
#define GBL_GEOMETRY_MASK 1
#include "gbuffer_wiring.glsl"
// Pixels "without geometry" (test::coveredAt's pattern, surface_support.h): checkerboard chroma skips them.
bool gblHasGeometry(ivec2 p) { return ((p.x * 7 + p.y * 3) % 5) != 0; }
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, std430) writeonly buffer Out { vec4 decoded[]; };
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    Surface s = readGBuffer(p);
    uint i = uint(p.y * SIZE + p.x) * 10u;
    decoded[i + 0u] = vec4(s.normal, s.metallic);
    decoded[i + 1u] = vec4(s.baseColor, s.roughness);
    decoded[i + 2u] = vec4(s.specularColor, s.specular);
    decoded[i + 3u] = vec4(s.diffuseColor, s.occlusion);
    decoded[i + 4u] = vec4(s.emissive, s.coat);
    decoded[i + 5u] = vec4(s.position, s.coatRoughness);
    decoded[i + 6u] = vec4(0.0);
    decoded[i + 7u] = vec4(s.coatNormal, s.sheenRoughness);
    decoded[i + 8u] = vec4(s.sheenColor, s.anisotropyStrength);
    decoded[i + 9u] = vec4(s.anisotropyDirection, s.shadingModel);
}
)";
}

std::vector<float> packSurfaces(const std::vector<Surface>& v) {
    std::vector<float> f(v.size() * kFloatsPerSurface, 0.0f);
    for (size_t i = 0; i < v.size(); ++i) {
        float* p = &f[i * kFloatsPerSurface];
        const Surface& s = v[i];
        auto put = [&](int k, glm::vec3 a, float w) {
            p[k * 4] = a.x;
            p[k * 4 + 1] = a.y;
            p[k * 4 + 2] = a.z;
            p[k * 4 + 3] = w;
        };
        put(0, s.normal, s.metallic);
        put(1, s.baseColor, s.roughness);
        put(2, s.specularColor, s.specular);
        put(3, s.diffuseColor, s.occlusion);
        put(4, s.emissive, s.coat);
        put(5, s.position, s.coatRoughness);
        put(7, s.coatNormal, s.sheenRoughness);
        put(8, s.sheenColor, s.anisotropyStrength);
        put(9, s.anisotropyDirection, s.shadingModel);
    }
    return f;
}

std::vector<Surface> unpackSurfaces(const float* f, size_t n) {
    std::vector<Surface> v(n);
    for (size_t i = 0; i < n; ++i) {
        const float* p = f + i * kFloatsPerSurface;
        Surface& s = v[i];
        s.normal = {p[0], p[1], p[2]};
        s.metallic = p[3];
        s.baseColor = {p[4], p[5], p[6]};
        s.roughness = p[7];
        s.specularColor = {p[8], p[9], p[10]};
        s.specular = p[11];
        s.diffuseColor = {p[12], p[13], p[14]};
        s.occlusion = p[15];
        s.emissive = {p[16], p[17], p[18]};
        s.coat = p[19];
        s.position = {p[20], p[21], p[22]};
        s.coatRoughness = p[23];
        s.coatNormal = {p[28], p[29], p[30]};
        s.sheenRoughness = p[31];
        s.sheenColor = {p[32], p[33], p[34]};
        s.anisotropyStrength = p[35];
        s.anisotropyDirection = {p[36], p[37], p[38]};
        s.shadingModel = p[39];
    }
    return v;
}

std::vector<Surface> randomSurfaces(uint32_t seed) { return test::randomSurfaces(kPixels, seed); }

// Writes the Surfaces in `surfaces` through the generated writeGBuffer, one per pixel, into a
// G-buffer made by the renderer's own code (renderer_passes.h: targets, depth, pipeline state,
// clears and transitions); only the shaders are the test's: a full-screen triangle whose fragment
// shader fetches its Surface from the buffer instead of evaluating a material. Returns the pass
// with its targets in SHADER_READ_ONLY_OPTIMAL.
GBufferPass renderTargets(const VulkanContext& ctx, const GBufferWiring& w, const Buffer& surfaces, bool draw = true,
                          bool frameFromSurface = false) {
    GBufferPass pass;
    createGBufferImages(ctx, w, kSize, kSize, pass);
    const std::vector<Binding> set0 = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                       {enc::kBestFitTableBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    pass.setLayout = createSetLayout(ctx.device, set0, VK_SHADER_STAGE_FRAGMENT_BIT);
    pass.pipelineLayout = createPipelineLayout(ctx.device, {pass.setLayout}, 0, 0);
    pass.pool = createPoolFor(ctx.device, {set0});
    pass.set = allocateSet(ctx.device, pass.pool, pass.setLayout);
    pass.bestFitTable = createBestFitTableBuffer(ctx);  // the renderer's table, as createGBufferPass binds it
    DescriptorWriter()
        .buffer(pass.set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, surfaces.buffer)
        .buffer(pass.set, enc::kBestFitTableBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pass.bestFitTable.buffer)
        .flush(ctx.device);
    const ShaderSource vs{"fullscreen.vert (test)", test::kFullScreenTriangleVertex, VK_SHADER_STAGE_VERTEX_BIT, {}, {}};
    const ShaderSource fs{"gpu_cpu_bits.frag (layout " + w.layoutName + ")", fragmentSource(frameFromSurface),
                          VK_SHADER_STAGE_FRAGMENT_BIT, {{"SIZE", std::to_string(kSize)}}, {}};
    pass.pipeline = createGBufferPipeline(ctx, w, pass.pipelineLayout, vs, fs, false);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        beginGBufferPass(cmd, pass);
        if (draw) vkCmdDraw(cmd, 3, 1, 0, 0);
        endGBufferPass(cmd, pass);
    });
    return pass;
}

std::vector<uint32_t> readWords(const VulkanContext& ctx, const GpuImage& img) { return test::targetWords(ctx, img, kPixels); }

std::vector<Surface> gpuDecode(const VulkanContext& ctx, const GBufferWiring& w, const std::vector<GpuImage>& targets,
                               const std::vector<GpuImage>& material) {
    test::TestBuffer out(ctx, kPixels * kFloatsPerSurface * sizeof(float));
    VkSampler sampler = createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    std::vector<std::vector<test::Resource>> sets = {{test::storage(out)}, {}, {}};
    for (const GpuImage& t : targets) sets[1].push_back(test::combinedImage(t, sampler));
    for (const GpuImage& m : material) sets[2].push_back(test::combinedImage(m, sampler));
    if (material.empty()) sets.pop_back();
    ShaderSource cs{"gpu_cpu_bits.comp (layout " + w.layoutName + ")", decodeSource(), VK_SHADER_STAGE_COMPUTE_BIT,
                    {{"SIZE", std::to_string(kSize)}}, {{"gbuffer_wiring.glsl", w.glsl}}};
    test::ComputeKernel(ctx, cs, sets).dispatch(kSize / 8, kSize / 8);
    vkDestroySampler(ctx.device, sampler, nullptr);
    return unpackSurfaces(out.mapped<const float>(), kPixels);
}

// `surfaces` packed by the CPU mirror (its decode skipping the pixels without geometry, as
// gblHasGeometry in decodeSource does) and by the generated writeGBuffer of `w` (and its material
// pass): the words of both, until the object goes.
struct Packed {
    Packed(VulkanContext& c, const Layout& layout, const GBufferWiring& w, const std::vector<Surface>& surfaces)
        : ctx(c), cpu(encodeGBuffer(layout, surfaces, int(kSize), int(kSize))),
          ssbo(test::TestBuffer::holding(c, packSurfaces(surfaces))) {
        cpu.covered = test::coverageMask(kSize, kSize);
        gbuffer = renderTargets(c, w, ssbo);
        if (w.materialPass) material = renderTargets(c, materialPassWiring(w), ssbo);
    }
    ~Packed() {
        destroyGBufferPass(ctx, gbuffer);
        destroyGBufferPass(ctx, material);
    }
    VulkanContext& ctx;
    CpuGBuffer cpu;
    test::TestBuffer ssbo;
    GBufferPass gbuffer, material;
};

// Random Surfaces written by the generated writeGBuffer of `layout` and by the CPU mirror: the
// words must be equal, and their decodes equal within 4 ulp.
void checkWordsAndDecodes(VulkanContext& c, const Layout& layout, const std::vector<Surface>& surfaces) {
    {
        const std::string& name = layout.name;
        const GBufferWiring w = generateWiring(layout);
        const Packed packed(c, layout, w, surfaces);
        const CpuGBuffer& cpu = packed.cpu;
        const std::vector<GpuImage>& targets = packed.gbuffer.targets;
        const std::vector<GpuImage>& material = packed.material.targets;

        size_t compared = 0, mismatches = 0;
        for (size_t t = 0; t < targets.size(); ++t) {
            std::vector<uint32_t> gpu = readWords(c, targets[t]);
            ASSERT_EQ(gpu.size(), cpu.targetWords[t].size()) << "target " << t;
            for (size_t i = 0; i < gpu.size(); ++i) {
                ++compared;
                if (gpu[i] != cpu.targetWords[t][i] && mismatches++ < 5)
                    ADD_FAILURE() << "target " << layout.targets[t].name << " word " << i << ": gpu 0x" << std::hex
                                  << gpu[i] << " cpu 0x" << cpu.targetWords[t][i] << std::dec;
            }
        }
        for (size_t t = 0; t < material.size(); ++t) {
            std::vector<uint32_t> gpu = readWords(c, material[t]);
            for (size_t i = 0; i < gpu.size(); ++i) {
                ++compared;
                if (gpu[i] != cpu.materialWords[t][i] && mismatches++ < 5)
                    ADD_FAILURE() << "material target " << t << " word " << i;
            }
        }
        EXPECT_EQ(mismatches, 0u);
        std::printf("[ bits     ] %-20s %8zu words compared, %zu mismatches\n", name.c_str(), compared, mismatches);

        const std::vector<Surface> gpuDecoded = gpuDecode(c, w, targets, material);
        const std::vector<Surface> cpuDecoded = decodeGBuffer(layout, cpu);
        size_t decodeMismatches = 0;
        float worst = 0.0f;
        for (size_t i = 0; i < gpuDecoded.size(); ++i) {
            const Surface& g = gpuDecoded[i];
            const Surface& s = cpuDecoded[i];
            const float a[] = {g.normal.x, g.normal.y, g.normal.z, g.baseColor.x, g.baseColor.y, g.baseColor.z,
                               g.metallic, g.roughness, g.specular, g.specularColor.x, g.specularColor.y,
                               g.specularColor.z, g.diffuseColor.x, g.diffuseColor.y, g.diffuseColor.z,
                               g.occlusion, g.emissive.x, g.emissive.y, g.emissive.z, g.position.x, g.position.y,
                               g.position.z, g.coat, g.coatRoughness, g.coatNormal.x, g.coatNormal.y, g.coatNormal.z,
                               g.sheenColor.x, g.sheenColor.y, g.sheenColor.z, g.sheenRoughness, g.anisotropyStrength,
                               g.anisotropyDirection.x, g.anisotropyDirection.y, g.anisotropyDirection.z,
                               g.shadingModel};
            const float b[] = {s.normal.x, s.normal.y, s.normal.z, s.baseColor.x, s.baseColor.y, s.baseColor.z,
                               s.metallic, s.roughness, s.specular, s.specularColor.x, s.specularColor.y,
                               s.specularColor.z, s.diffuseColor.x, s.diffuseColor.y, s.diffuseColor.z,
                               s.occlusion, s.emissive.x, s.emissive.y, s.emissive.z, s.position.x, s.position.y,
                               s.position.z, s.coat, s.coatRoughness, s.coatNormal.x, s.coatNormal.y, s.coatNormal.z,
                               s.sheenColor.x, s.sheenColor.y, s.sheenColor.z, s.sheenRoughness, s.anisotropyStrength,
                               s.anisotropyDirection.x, s.anisotropyDirection.y, s.anisotropyDirection.z,
                               s.shadingModel};
            for (size_t k = 0; k < std::size(a); ++k) {
                worst = std::max(worst, std::abs(a[k] - b[k]));
                if (!test::within4Ulp(a[k], b[k]) && decodeMismatches++ < 5)
                    ADD_FAILURE() << "decode pixel " << i << " value " << k << ": gpu " << a[k] << " cpu " << b[k];
            }
        }
        EXPECT_EQ(decodeMismatches, 0u);
        std::printf("[ decode   ] %-20s max |gpu - cpu| %g, %zu beyond 4 ulp\n", name.c_str(), double(worst),
                    decodeMismatches);
    }
}

class GpuCpuBits : public test::VulkanTest {};

// Every shipped layout but the visibility buffers (ids, not attributes: render/visibility_test).
TEST_F(GpuCpuBits, EveryLayoutPacksTheSameWordsAndDecodesAlike) {
    const std::vector<Layout> layouts = test::shippedAttributeLayouts();
    ASSERT_GE(layouts.size(), 7u);
    uint32_t seed = 1;
    for (const Layout& layout : layouts) {
        SCOPED_TRACE(layout.name);
        std::vector<Surface> surfaces = randomSurfaces(seed++);
        // A selector's rows (ue5, ue5-anisotropy; hdrp-lit, hdrp-lit-apv: HDRP's standard and anisotropic
        // features, the tangent stored against the normal's frame): every model of the rule on its own pixels.
        if (layout.selector()) test::assignLayerPatterns(surfaces);
        checkWordsAndDecodes(ctx(), layout, surfaces);
    }
}

// A dither that moves with time (a field's dither_per_frame): niagara's normal field declared per
// frame, written by the GPU's generated writeGBuffer with each pixel at its own frame index (0 to
// 127: every index of the noise's 64-frame cycle, twice) and by the CPU codec at each index: the
// same words at every index. The codes move from frame to frame and repeat after 64 frames; the
// field as niagara declares it (no frame term) ignores the index.
TEST_F(GpuCpuBits, DitherThatMovesWithTimePacksTheSameWordsAtEveryFrame) {
    Layout layout = test::shippedLayout("niagara");
    Field* dithered = nullptr;
    for (Target& t : layout.targets)
        for (Field& f : t.fields)
            if (f.encoding == "normal_octahedral_dithered") dithered = &f;
    ASSERT_NE(dithered, nullptr);
    EXPECT_TRUE(dithered->ditherDeclared);
    EXPECT_FALSE(dithered->ditherPerFrame);  // niagara: gradientNoise(gl_FragCoord.xy), no frame term
    const Layout fixed = layout;
    dithered->ditherPerFrame = true;
    const GBufferWiring w = generateWiring(layout);
    EXPECT_NE(w.glsl.find("gblFrameIndex()"), std::string::npos);
    EXPECT_EQ(generateWiring(fixed).glsl.find("gblFrameIndex()"), std::string::npos);
    constexpr uint32_t kFrames = 128;
    const auto frameOf = [](size_t pixel) { return uint32_t((pixel % kSize + 3 * (pixel / kSize)) % kFrames); };
    const std::vector<Surface> surfaces = randomSurfaces(77);
    std::vector<float> packed = packSurfaces(surfaces);
    for (size_t i = 0; i < surfaces.size(); ++i) {
        const uint32_t frame = frameOf(i);
        std::memcpy(&packed[i * kFloatsPerSurface + 24], &frame, sizeof frame);  // a[6].x's bits
    }
    std::vector<std::vector<uint32_t>> gpu;
    {
        const test::TestBuffer ssbo = test::TestBuffer::holding(ctx(), packed);
        GBufferPass pass = renderTargets(ctx(), w, ssbo, true, true);
        for (const GpuImage& t : pass.targets) gpu.push_back(readWords(ctx(), t));
        destroyGBufferPass(ctx(), pass);
    }
    std::vector<CpuGBuffer> cpu;  // the whole image encoded at each frame index
    for (uint32_t frame = 0; frame < kFrames; ++frame) {
        CpuCodecOptions options;
        options.frameIndex = frame;
        cpu.push_back(CpuCodec(layout, options).encode(surfaces, int(kSize), int(kSize)));
    }
    size_t compared = 0, mismatches = 0;
    for (size_t t = 0; t < gpu.size(); ++t) {
        const size_t wordsPerPixel = gpu[t].size() / surfaces.size();
        for (size_t i = 0; i < gpu[t].size(); ++i) {
            ++compared;
            const uint32_t want = cpu[frameOf(i / wordsPerPixel)].targetWords[t][i];
            if (gpu[t][i] != want && mismatches++ < 5)
                ADD_FAILURE() << "target " << t << " word " << i << " (frame " << frameOf(i / wordsPerPixel) << "): gpu 0x"
                              << std::hex << gpu[t][i] << " cpu 0x" << want << std::dec;
        }
    }
    EXPECT_EQ(mismatches, 0u);
    std::printf("[ bits     ] niagara, moving dither, frames 0-%u per pixel: %zu words compared, %zu mismatches\n",
                kFrames - 1, compared, mismatches);
    // The dither moves: frames 0 and 1 store other codes in many pixels; frame 64 is frame 0.
    size_t moved = 0, words = 0;
    for (size_t t = 0; t < gpu.size(); ++t)
        for (size_t i = 0; i < cpu[0].targetWords[t].size(); ++i) {
            ++words;
            moved += cpu[0].targetWords[t][i] != cpu[1].targetWords[t][i];
        }
    EXPECT_GT(moved, words / 8) << moved << " of " << words << " words differ between frames 0 and 1";
    EXPECT_EQ(cpu[0].targetWords, cpu[64].targetWords);
    EXPECT_EQ(cpu[0].targetWords, CpuCodec(fixed).encode(surfaces, int(kSize), int(kSize)).targetWords);
    CpuCodecOptions late;
    late.frameIndex = 5;
    EXPECT_EQ(CpuCodec(fixed, late).encode(surfaces, int(kSize), int(kSize)).targetWords, cpu[0].targetWords);
}

// HDRP's engine encodings with inputs the random Surfaces rarely give, so that their GLSL twins are
// held to the CPU's words on their edges: the normal buffer (normal_octahedral_hdrp) near its
// 1/1024 clamp, fresnel0 (srgb8_fast_hdrp) below sRGB's toe, and GBuffer3's AO tag
// (float11_11_10_hdrp_ao_tag) where emissive is exactly 0, with AO at 0, 1, float11's denormals
// and its rounding ties, and emissive that quantises to 0 without being 0.
// HDRP's GBuffer1, GBuffer2 and GBuffer3 (occlusion rides in GBuffer3's AO tag: no fallback for it).
std::string engineEncodingsLayout() {
    return test::LayoutText("engine-encodings", "engine encodings no seed layout stores", test::kHdrpSource)
        .target(test::hdrpGBuffer1())
        .target(test::hdrpGBuffer2())
        .target(test::hdrpGBuffer3())
        .noFallback("occlusion")
        .clear("specular_color = 0.0")
        .clear("emissive = 0.0")
        .clear("occlusion = 0.5");
}

TEST_F(GpuCpuBits, EngineEncodingsWithoutASeedLayoutPackTheSameWords) {
    const Layout layout = parseLayout(engineEncodingsLayout(), "engine-encodings.toml");
    std::vector<Surface> surfaces = randomSurfaces(900);
    // A quarter of the normals within HDRP's 1/1024 of the equator (its clamp acts), +-0 included.
    const float zs[] = {0.0f, -0.0f, 1.0f / 1024.0f, -1.0f / 1024.0f, 3e-4f, -3e-4f, 1e-30f, -1e-7f};
    for (size_t i = 0; i < surfaces.size(); i += 4) surfaces[i].normal.z = zs[(i / 4) % 8];
    // and a third of the F0 channels below sRGB's linear toe, where HDRP's curve is its own
    for (size_t i = 1; i < surfaces.size(); i += 3) surfaces[i].specularColor *= 0.004f;
    // Half the pixels without emissive (the tag), +-0 included; AO on float11's edges: 0, 1, its
    // denormals (below 2^-14), ties between two codes (1 + 2.5 / 64: a tie to even), and beyond 1.
    const float aos[] = {0.0f, 1.0f, 6.0e-5f, 1.0e-6f, 4.7e-7f, 1.0f + 2.5f / 64.0f, 0.5f + 1.0f / 256.0f, 0.999f};
    for (size_t i = 0; i < surfaces.size(); i += 2) {
        surfaces[i].emissive = (i / 2) % 3 == 0 ? glm::vec3(-0.0f, 0.0f, -0.0f) : glm::vec3(0.0f);
        if ((i / 2) % 4 == 1) surfaces[i].occlusion = aos[(i / 8) % 8];
    }
    // and emissive that is not 0 but quantises to it (no tag: the word 0), or holds the tag's floats
    for (size_t i = 1; i < surfaces.size(); i += 10) surfaces[i].emissive = glm::vec3(1e-30f, 0.0f, 0.0f);
    for (size_t i = 3; i < surfaces.size(); i += 50) surfaces[i].emissive = glm::vec3(2048.0f, 0.25f, 1024.0f);
    checkWordsAndDecodes(ctx(), layout, surfaces);
}

// A layout with a shading-model selector (tests/layout/data/shading-models.toml): Surfaces with
// every combination of layers (test::assignLayerPatterns), so that every model of the rule is
// picked, its conditional fields written over the same bits as the other models', and decoded where
// the stored id says; the GPU's generated wiring and the CPU codec agree on every word and value
// (the stored id, decoded into shadingModel, included). What the words hold is checked against the
// statement itself in tests/codec/shading_model_codec_test.cpp.
TEST_F(GpuCpuBits, ASelectorLayoutPacksTheSameWordsAndDecodesAlike) {
    const Layout layout = test::testLayout("shading-models");
    std::vector<Surface> surfaces = randomSurfaces(920);
    test::assignLayerPatterns(surfaces);
    checkWordsAndDecodes(ctx(), layout, surfaces);
    // and fallbacks deriving each other per model (HDRP's fresnel0 and metallic): one order for both
    checkWordsAndDecodes(ctx(), test::selectorLayoutDerivingEachOther(), surfaces);
}

// killzone2's specular power (kz2_log_power): roughness on each of its 255 thresholds and the
// floats beside them, on its two ends and beyond them, so that the GLSL search is held to the CPU's
// code at every boundary, not only at the random Surfaces' roughnesses.
TEST_F(GpuCpuBits, Killzone2PowerPacksTheSameWordsOnItsThresholds) {
    const Layout layout = test::shippedLayout("killzone2");
    std::vector<Surface> surfaces = randomSurfaces(910);
    std::vector<float> probes = {0.0f, -0.0f, 1.0f, 2.0f, -1.0f, 0.1f, 0.95f, enc::kKz2PowerRoughness[0],
                                 enc::kKz2PowerRoughness[255]};
    for (float t : enc::kKz2PowerEncodeThresholds) {
        probes.push_back(t);
        probes.push_back(std::nextafter(t, 0.0f));
        probes.push_back(std::nextafter(t, 1.0f));
    }
    for (size_t i = 0; i < surfaces.size(); i += 2) surfaces[i].roughness = probes[(i / 2) % probes.size()];
    checkWordsAndDecodes(ctx(), layout, surfaces);
}

// Issue 11 item 3: a pixel without geometry holds the layout's [clear] values through its own
// encoders. Nothing is drawn: every word of every target must equal the CPU mirror's clearWords,
// and (crysis3-thin) those words decode to a black albedo without tint, not chroma -0.5.
TEST_F(GpuCpuBits, ClearedPixelsHoldTheEncodedClearValues) {
    VulkanContext& c = ctx();
    for (const Layout& layout : test::shippedAttributeLayouts()) {  // visibility buffers: render/visibility_test
        const std::string& name = layout.name;
        SCOPED_TRACE(name);
        const GBufferWiring w = generateWiring(layout);
        const test::TestBuffer ssbo = test::TestBuffer::holding(c, packSurfaces(std::vector<Surface>(kPixels)));
        GBufferPass gbuffer = renderTargets(c, w, ssbo, false);
        const std::vector<std::array<uint32_t, 4>> clear = clearWords(layout);
        CpuGBuffer cleared;
        cleared.width = cleared.height = int(kSize);
        size_t mismatches = 0;
        for (size_t t = 0; t < gbuffer.targets.size(); ++t) {
            const std::vector<uint32_t> gpu = readWords(c, gbuffer.targets[t]);
            const size_t words = gpu.size() / kPixels;
            for (size_t i = 0; i < gpu.size(); ++i)
                if (gpu[i] != clear[t][i % words] && mismatches++ < 3)
                    ADD_FAILURE() << "target " << t << " word " << i << ": 0x" << std::hex << gpu[i] << " expected 0x"
                                  << clear[t][i % words] << std::dec;
            cleared.targetWords.push_back(gpu);
        }
        EXPECT_EQ(mismatches, 0u);
        if (name == "crysis3-thin") {
            const std::vector<Surface> s = decodeGBuffer(layout, cleared);
            EXPECT_LT(glm::length(s[0].diffuseColor), 1e-6f);
            EXPECT_LT(glm::length(s[1].diffuseColor), 1e-6f);
        }
        destroyGBufferPass(c, gbuffer);
    }
}

// --native-formats: targets in their real formats (the hardware quantises), decoded on the GPU and
// compared with the CPU's bit-exact decode within a quantisation step (lavapipe's SFLOAT
// conversion truncates, its SRGB one is off by a step on ~6% of values: STACK-FACTS.md).
TEST_F(GpuCpuBits, NativeFormatsRenderAndDecodeNearTheBitExactPath) {
    VulkanContext& c = ctx();
    uint32_t seed = 100;
    for (const Layout& layout : test::shippedAttributeLayouts()) {  // visibility buffers: render/visibility_test
        const std::string& name = layout.name;
        SCOPED_TRACE(name);
        const GBufferWiring w = generateWiring(layout, WiringOptions{true});
        const Packed packed(c, layout, w, randomSurfaces(seed++));
        const std::vector<Surface> g = gpuDecode(c, w, packed.gbuffer.targets, packed.material.targets);
        const std::vector<Surface> s = decodeGBuffer(layout, packed.cpu);
        size_t native = 0, far = 0;
        for (size_t t = 0; t < w.targetFormats.size(); ++t) native += w.targetFormats[t] != uintFormatOf(layout.targets[t]);
        // One 8-bit step in each code, through the widest inverse transform: YCbCr's
        // B = Y + 1.772 Cb moves by 1/255 + 1.772/254 = 0.0109 (ryse's native RT2 reaches
        // 0.0108 with the sample it got once niagara shifted the seeds; 0.0086 before). An
        // attribute derived from stored ones adds up their steps: the widest chain is base colour
        // from diffuse colour, F0 and the metallic derived from F0 (from_diffuse_specular +
        // from_specular_color: diffuse + (max F0 - 0.04) / 0.96 * F0), three steps, which
        // ue4-elemental reaches with both colours in native sRGB targets (0.0195: two steps).
        const float step = 0.0115f;
        auto boundOf = [&](Attribute a) { return layout.stores(a) ? step : 3.0f * step; };
        float worst = 0.0f;
        for (size_t i = 0; i < g.size(); ++i) {
            auto cmp = [&](float a, float b, Attribute attribute) {
                const float d = std::abs(a - b) / std::max(1.0f, std::abs(b));
                worst = std::max(worst, d);
                far += d > boundOf(attribute);
            };
            for (int k = 0; k < 3; ++k) {
                cmp(g[i].normal[k], s[i].normal[k], Attribute::Normal);
                cmp(g[i].baseColor[k], s[i].baseColor[k], Attribute::BaseColor);
                cmp(g[i].specularColor[k], s[i].specularColor[k], Attribute::SpecularColor);
                cmp(g[i].diffuseColor[k], s[i].diffuseColor[k], Attribute::DiffuseColor);
                cmp(g[i].emissive[k], s[i].emissive[k], Attribute::Emissive);
                cmp(g[i].position[k], s[i].position[k], Attribute::Position);
            }
            cmp(g[i].metallic, s[i].metallic, Attribute::Metallic);
            cmp(g[i].roughness, s[i].roughness, Attribute::Roughness);
            cmp(g[i].specular, s[i].specular, Attribute::Specular);
            cmp(g[i].occlusion, s[i].occlusion, Attribute::Occlusion);
        }
        EXPECT_EQ(far, 0u) << "worst relative difference " << worst;
        std::printf("[ native   ] %-20s %zu of %zu targets native, max rel. diff vs bit-exact decode %g\n",
                    name.c_str(), native, w.targetFormats.size(), double(worst));
    }
}

// The Forge's packVisBufData, written out here from its source (ConfettiFX/The-Forge @19cf606b,
// Examples_3/Visibility_Buffer/src/Shaders/Metal/visibilityBuffer_pass.frag.metal; the D3D12
// visibilityBuffer_pass.frag @36383240 calls it calculateOutputVBID):
// ((drawId << 23) & 0x7F800000) | (triangleId & 0x007FFFFF), | 1 << 31 for alpha-tested geometry;
// its shade pass (visibilityBuffer_shade.frag.metal @a36471d0) reads draw = (w >> 23) & 0xFF,
// triangle = w & 0x7FFFFF, flag = w >> 31.
uint32_t theForgePackVisBufData(bool opaque, uint32_t drawId, uint32_t triangleId) {
    const uint32_t packed = ((drawId << 23) & 0x7F800000u) | (triangleId & 0x007FFFFFu);
    return opaque ? packed : (1u << 31) | packed;
}

// visibility-32's ids as the generated wiring packs them (shaders/visibility_buffer.glsl,
// packVisibilityIds, run in a compute shader) against The Forge's packVisBufData, on 2^20 random
// (draw, triangle, alpha) triples, ids wider than their fields and the fields' edges included
// (The Forge masks the excess away, and so must gbufferlab), then unpacked as its shade pass does.
TEST_F(GpuCpuBits, VisibilityIdsEqualTheForgesPackVisBufData) {
    VulkanContext& c = ctx();
    const Layout layout = test::shippedLayout("visibility-32");
    ASSERT_EQ(layout.pipeline, Pipeline::VisibilityBuffer);
    const GBufferWiring w = generateWiring(layout);
    constexpr uint32_t kIds = 1u << 20;
    std::vector<uint32_t> in(size_t(kIds) * 4);
    std::mt19937 rng(2807);
    const uint32_t edges[] = {0u, 1u, 254u, 255u, 256u, 511u, 0x7FFFFEu, 0x7FFFFFu, 0x800000u, 0x800001u,
                              0xFFFFFFu, 0x1000000u, 0x7FFFFFFFu, 0x80000000u, 0xFFFFFFFEu, 0xFFFFFFFFu};
    for (uint32_t i = 0; i < kIds; ++i) {
        uint32_t draw = rng(), tri = rng();
        if (i % 4 == 1) draw &= 0xFFu;      // in range, as a scene's ids are
        if (i % 4 == 2) tri &= 0x7FFFFFu;
        if (i < 16u * 16u * 2u) {           // every pair of edges, both flags
            draw = edges[i % 16];
            tri = edges[(i / 16) % 16];
        }
        in[size_t(i) * 4] = draw;
        in[size_t(i) * 4 + 1] = tri;
        in[size_t(i) * 4 + 2] = (i / 512u) % 2u;  // alpha-tested
        in[size_t(i) * 4 + 3] = 0u;
    }
    const test::TestBuffer input = test::TestBuffer::holding(c, in);
    const test::TestBuffer out(c, size_t(kIds) * 4 * sizeof(uint32_t));
    const std::string source = test::wiringKernel(R"(    uvec4 v = inputs[i];
    uint packed = packVisibilityIds(v.x, v.y, v.z != 0u, 0.0).x;
    outputs[i] = uvec4(packed, unpackVisibilityIds(uvec2(packed, 0u)));
)");
    ShaderSource cs{"visibility_ids.comp (test)", source, VK_SHADER_STAGE_COMPUTE_BIT, {}, {{"gbuffer_wiring.glsl", w.glsl}}};
    test::ComputeKernel(c, cs, {{test::storage(input), test::storage(out)}}).dispatch(kIds / 64);
    const uint32_t* got = out.mapped<const uint32_t>();
    size_t mismatches = 0;
    for (uint32_t i = 0; i < kIds; ++i) {
        const uint32_t draw = in[size_t(i) * 4], tri = in[size_t(i) * 4 + 1];
        const bool alpha = in[size_t(i) * 4 + 2] != 0u;
        const uint32_t want = theForgePackVisBufData(!alpha, draw, tri);
        const uint32_t* g = got + size_t(i) * 4;
        // The shade pass's reading of the word: draw, triangle, flag.
        const bool ok = g[0] == want && g[1] == ((want >> 23) & 0xFFu) && g[2] == (want & 0x7FFFFFu) && g[3] == want >> 31;
        if (!ok && mismatches++ < 5)
            ADD_FAILURE() << std::hex << "draw 0x" << draw << " triangle 0x" << tri << " alpha " << alpha << ": gbufferlab 0x"
                          << g[0] << " (" << g[1] << ", " << g[2] << ", " << g[3] << "), The Forge 0x" << want;
    }
    EXPECT_EQ(mismatches, 0u);
    std::printf("[ ids      ] visibility-32: %u ids packed as packVisBufData, %zu mismatches\n", kIds, mismatches);
}

}  // namespace
}  // namespace gbl
