// The read-back's two decoders on real content (RenderSettings::decodeOnCpu): the built-in scene
// rendered through layouts that exercise the codec's harder parts (a light pre-pass with its
// material pass, checkerboard chroma, dithered normals and the emissive/albedo ratio, Z-up and
// view-space normals, R8 targets, the float reference), decoded once by the decode pass
// (readGBuffer on the device) and once by the layout's CPU codec on the host. Every SurfaceImages
// plane must agree within gpu_cpu_bits_test's bound (4 ulps of max(1, |value|)), coverage and
// depth exactly, and the CPU path must not build the decode pass's pipeline.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <tuple>

#include "layered_scene.h"
#include "layout_catalog.h"
#include "procedural_sky.h"
#include "renderer.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

class CpuDecodeTest : public test::VulkanTest {};

// gpu_cpu_bits_test's `near`: the bound it holds readGBuffer on the device and the codec to.
bool near(float a, float b) {
    if (a == b) return true;
    return std::abs(a - b) <= 4.0f * std::numeric_limits<float>::epsilon() * std::max(1.0f, std::abs(b));
}

struct PlaneDiff {
    size_t beyond = 0;   // values outside `near`
    size_t differ = 0;   // values not bit-equal
    float worst = 0.0f;  // max |pass - cpu|
};

PlaneDiff comparePlane(const Image& pass, const Image& cpu, const char* what) {
    PlaneDiff d;
    EXPECT_EQ(pass.width, cpu.width) << what;
    EXPECT_EQ(pass.height, cpu.height) << what;
    EXPECT_EQ(pass.channels, cpu.channels) << what;
    if (pass.pixels.size() != cpu.pixels.size()) {
        ADD_FAILURE() << what << ": " << pass.pixels.size() << " vs " << cpu.pixels.size() << " values";
        return d;
    }
    for (size_t i = 0; i < pass.pixels.size(); ++i) {
        const float a = pass.pixels[i], b = cpu.pixels[i];
        d.differ += a != b;
        d.worst = std::max(d.worst, std::abs(a - b));
        if (!near(a, b) && d.beyond++ < 3)
            ADD_FAILURE() << what << " value " << i << " (pixel " << i / size_t(pass.channels) << "): decode pass " << a
                          << ", cpu codec " << b;
    }
    return d;
}

// The two decodes of one frame: what differs is the decode alone (the frame is rendered twice by a
// deterministic rasteriser: HDR and depth must be identical).
void compareDecodes(const char* name, const char* view, const RenderOutput& host, const RenderOutput& device) {
    SCOPED_TRACE(view);
    ASSERT_EQ(host.hdr.pixels, device.hdr.pixels);
    ASSERT_EQ(host.depth, device.depth);
    const SurfaceImages& a = device.surfaces;
    const SurfaceImages& b = host.surfaces;
    ASSERT_EQ(a.coverage, b.coverage);
    size_t covered = 0;
    for (uint8_t c : a.coverage) covered += c;
    ASSERT_GT(covered, a.coverage.size() / 4) << "too little geometry to compare";
    ASSERT_LT(covered, a.coverage.size()) << "no background pixel to compare";

    // The layers' images in a scene with layers (issue 40), as both decodes fill them.
    ASSERT_EQ(a.hasLayers(), b.hasLayers());
    const std::pair<const Image*, const Image*> planes[] = {
        {&a.normal, &b.normal},       {&a.baseColor, &b.baseColor}, {&a.diffuseColor, &b.diffuseColor},
        {&a.specularColor, &b.specularColor}, {&a.roughness, &b.roughness}, {&a.metallic, &b.metallic},
        {&a.occlusion, &b.occlusion}, {&a.emissive, &b.emissive}, {&a.depth, &b.depth},
        {&a.viewDepth, &b.viewDepth}, {&a.coat, &b.coat}, {&a.coatRoughness, &b.coatRoughness},
        {&a.coatNormal, &b.coatNormal}, {&a.sheenColor, &b.sheenColor}, {&a.sheenRoughness, &b.sheenRoughness},
        {&a.anisotropyStrength, &b.anisotropyStrength}, {&a.anisotropyDirection, &b.anisotropyDirection}};
    const char* names[] = {"normal",    "base colour", "diffuse colour", "specular colour", "roughness",
                           "metallic",  "occlusion",   "emissive",       "depth",           "view depth",
                           "coat",      "coat roughness", "coat normal", "sheen colour",    "sheen roughness",
                           "anisotropy strength", "anisotropy direction"};
    static_assert(std::size(planes) == std::size(names));
    size_t beyond = 0, differ = 0, values = 0;
    for (size_t p = 0; p < std::size(planes); ++p) {
        const PlaneDiff d = comparePlane(*planes[p].first, *planes[p].second, names[p]);
        beyond += d.beyond;
        differ += d.differ;
        values += planes[p].first->pixels.size();
        if (d.differ)
            std::printf("[ planes   ] %-14s %-12s %-15s %6zu of %zu values differ, max |pass - cpu| %g\n", name, view, names[p],
                        d.differ, planes[p].first->pixels.size(), double(d.worst));
    }
    EXPECT_EQ(beyond, 0u);
    std::printf("[ decode   ] %-14s %-12s %zu values, %zu not bit-equal, %zu beyond 4 ulp\n", name, view, values, differ,
                beyond);
}

// An orbit about the scene camera's target (as compare_views.cpp's), lower and from the side.
Camera orbitCamera(const Scene& scene) {
    Camera c = scene.camera;
    const glm::vec3 from = c.position - c.target;
    const float a = glm::radians(40.0f);
    c.position = c.target + glm::vec3(std::cos(a) * from.x + std::sin(a) * from.z, 0.6f * from.y,
                                      -std::sin(a) * from.x + std::cos(a) * from.z);
    return c;
}

TEST_F(CpuDecodeTest, CpuCodecDecodesRenderedLayoutsAsTheDecodePass) {
    constexpr uint32_t kWidth = 160, kHeight = 90;
    const Scene scene = makeSphereGridScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    Renderer renderer(test::sharedContext(), scene, sky);
    const RenderSettings pass = test::decodedFrame(kWidth, kHeight);
    RenderSettings cpu = pass;
    cpu.decodeOnCpu = true;

    for (const char* name :
         {"ue4", "crysis2-slim", "crysis3-thin", "niagara", "ryse", "bevy-deferred", "bevy-deferred-webgl2", "killzone2",
          "reference"}) {
        SCOPED_TRACE(name);
        const GBufferWiring wiring = generateWiring(loadLayout(name));
        ASSERT_NE(wiring.cpuDecoder, nullptr);
        ASSERT_TRUE(Renderer::decodesOnCpu(wiring, cpu));
        ASSERT_FALSE(Renderer::decodesOnCpu(wiring, pass));

        // The host decode first: it builds the G-buffer (+ material) and lighting pipelines only.
        const size_t before = renderer.pipelineCount();
        const RenderOutput host = renderer.render(wiring, cpu);
        const size_t passes = wiring.materialPass ? 3 : 2;
        EXPECT_EQ(renderer.pipelineCount() - before, passes) << "the CPU decode built the decode pass's pipeline";
        const RenderOutput device = renderer.render(wiring, pass);
        EXPECT_EQ(renderer.pipelineCount() - before, passes + 1);
        EXPECT_TRUE(host.targetWords.empty());  // readTargetWords = false: the words are not kept
        compareDecodes(name, "scene camera", host, device);
        // A second view (compare --views): other matrices, another spread of depths.
        RenderSettings cpuOrbit = cpu, passOrbit = pass;
        cpuOrbit.camera = passOrbit.camera = orbitCamera(scene);
        compareDecodes(name, "orbit", renderer.render(wiring, cpuOrbit), renderer.render(wiring, passOrbit));
    }
}


// The same with material layers (issue 40): the sphere grid with a clear coat, a sheen or
// anisotropy on every fourth sphere (layers_render_test's), where both decodes fill the seven
// layer images: the reference's float32 layers, 0 from ue4, which stores none, and UE 5's rows
// with the shading model per pixel (ue5, ue5-anisotropy: the selector) and ue5-cloth: the coated
// spheres' pixels ClearCoat, the sheen ones' Cloth, the anisotropic ones' (ue5-anisotropy) Default
// Lit with anisotropy, each decoding its own layer; a Cloth pixel's sheen roughness is its decoded
// roughness (sheen_roughness = "from_roughness", UE's cloth lobe), on both paths; and hdrp-lit, whose
// anisotropic spheres are of HDRP's anisotropic feature (the coat a flag beside it, no sheen); and
// ue5-clearcoat-normal, whose ClearCoat pixels hold the coat's normal and the base normal's delta.
TEST_F(CpuDecodeTest, LayerImagesDecodeAlikeOnBothPaths) {
    Scene scene = makeSphereGridScene();
    test::addLayersToSphereGrid(scene);
    const EnvironmentMap sky = makeProceduralSky(64);
    Renderer renderer(test::sharedContext(), scene, sky);
    const RenderSettings pass = test::decodedFrame(160, 90);
    RenderSettings cpu = pass;
    cpu.decodeOnCpu = true;
    for (const char* name : {"reference", "ue4", "ue5", "ue5-anisotropy", "ue5-cloth", "hdrp-lit", "ue5-clearcoat-normal"}) {
        SCOPED_TRACE(name);
        const std::string n = name;
        const GBufferWiring wiring = generateWiring(loadLayout(name));
        const RenderOutput host = renderer.render(wiring, cpu), device = renderer.render(wiring, pass);
        ASSERT_TRUE(host.surfaces.hasLayers());
        compareDecodes(name, "scene camera", host, device);
        // What the stored id switches decodes bit for bit alike on both paths (the normal and the
        // directions may differ in the last bit, as ue4's: compareDecodes' 4 ulp).
        for (const auto& [a, b, what] : {std::tuple{&device.surfaces.coat, &host.surfaces.coat, "coat"},
                                         {&device.surfaces.coatRoughness, &host.surfaces.coatRoughness, "coat roughness"},
                                         {&device.surfaces.sheenColor, &host.surfaces.sheenColor, "sheen colour"},
                                         {&device.surfaces.sheenRoughness, &host.surfaces.sheenRoughness, "sheen roughness"},
                                         {&device.surfaces.anisotropyStrength, &host.surfaces.anisotropyStrength,
                                          "anisotropy strength"},
                                         {&device.surfaces.roughness, &host.surfaces.roughness, "roughness"}})
            EXPECT_EQ(a->pixels, b->pixels) << what;
        for (const RenderOutput* out : {&device, &host}) {
            const SurfaceImages& s = out->surfaces;
            size_t coated = 0, sheen = 0, anisotropic = 0, sheenRoughnessOff = 0, coatNormals = 0;
            for (size_t i = 0; i < s.coverage.size(); ++i) {
                if (!s.coverage[i]) continue;
                coated += s.coat.pixels[i] > 0.0f;
                const float* cn = &s.coatNormal.pixels[i * 3];
                coatNormals += s.coat.pixels[i] > 0.0f && (cn[0] != 0.0f || cn[1] != 0.0f || cn[2] != 0.0f);
                anisotropic += s.anisotropyStrength.pixels[i] > 0.0f;
                const bool hasSheen = s.sheenColor.pixels[i * 3] + s.sheenColor.pixels[i * 3 + 1] + s.sheenColor.pixels[i * 3 + 2] > 0.0f;
                sheen += hasSheen;
                if (hasSheen && s.sheenRoughness.pixels[i] != s.roughness.pixels[i]) ++sheenRoughnessOff;
            }
            SCOPED_TRACE(out == &device ? "decode pass" : "cpu codec");
            // the coated spheres are in view; ue4 and ue5-cloth drop the coat (it decodes 0)
            if (n == "ue4" || n == "ue5-cloth") EXPECT_EQ(coated, 0u);
            else EXPECT_GT(coated, 100u);
            if (n == "ue4" || n == "hdrp-lit") EXPECT_EQ(sheen, 0u);  // HDRP's Lit has no sheen
            else EXPECT_GT(sheen, 100u);  // the sheen spheres: Cloth pixels in UE's rows
            if (n == "reference" || n == "ue5-anisotropy" || n == "hdrp-lit") EXPECT_GT(anisotropic, 100u);
            else EXPECT_EQ(anisotropic, 0u);
            // UE's cloth lobe takes the base roughness: the decoded sheen roughness is the decoded roughness
            if (n.rfind("ue5", 0) == 0) EXPECT_EQ(sheenRoughnessOff, 0u);
            if (n == "reference") EXPECT_GT(sheenRoughnessOff, 0u);  // the glTF sheen roughness, 0.5, stored apart
            // r.ClearCoatNormal = 1: every ClearCoat pixel decodes the coat's normal from GBufferA
            // (and its base normal from CustomData); ue5 stores none (0: the base normal serves)
            if (n == "ue5-clearcoat-normal" || n == "reference") EXPECT_EQ(coatNormals, coated);
            if (n == "ue5") EXPECT_EQ(coatNormals, 0u);
        }
    }
}

// The decoded view depth against the exact view depth of each stored depth value: the float
// projection the depth was rasterised with, solved for view z in double precision.
// decode_pass.comp.glsl takes it from the depth value and the projection alone; the way it took
// before, through world space and back (kept here as `worldRoundTrip`), cancels large
// coordinates. Both are measured; the decode must stay within 2 ulp and beat the round trip.
double ulpsApart(float value, double exact) {
    const double ulp = double(std::nextafter(float(exact), std::numeric_limits<float>::infinity())) - double(float(exact));
    return std::abs(double(value) - exact) / ulp;
}

float worldRoundTrip(const CameraMatrices& m, int x, int y, int w, int h, float depth) {
    const glm::vec2 ndc = (glm::vec2(float(x), float(y)) + 0.5f) / glm::vec2(float(w), float(h)) * 2.0f - 1.0f;
    const glm::vec4 world = m.invViewProj * glm::vec4(ndc, depth, 1.0f);
    return -(m.view * glm::vec4(glm::vec3(world) / world.w, 1.0f)).z;
}

TEST_F(CpuDecodeTest, ViewDepthIsTheProjectionsWithinTwoUlp) {
    constexpr uint32_t kWidth = 160, kHeight = 90;
    const Scene scene = makeSphereGridScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    Renderer renderer(test::sharedContext(), scene, sky);
    for (const char* name : {"reference", "ue4", "crysis3-thin"}) {
        const GBufferWiring wiring = generateWiring(loadLayout(name));
        for (const bool orbit : {false, true}) {
            SCOPED_TRACE(std::string(name) + (orbit ? " orbit" : " scene camera"));
            RenderSettings settings = test::decodedFrame(kWidth, kHeight);
            const Camera camera = orbit ? orbitCamera(scene) : scene.camera;
            settings.camera = camera;
            const RenderOutput out = renderer.render(wiring, settings);  // the decode pass
            const float aspect = float(kWidth) / float(kHeight);
            const CameraMatrices m = computeCameraMatrices(camera, aspect, wiring.reversedZ);
            const glm::dmat4 p(m.proj);  // the projection the depth was rasterised with, exactly
            const bool unorm24 = wiring.depthFormat == VK_FORMAT_D24_UNORM_S8_UINT ||
                                 wiring.depthFormat == VK_FORMAT_X8_D24_UNORM_PACK32;
            double worst = 0.0, worstRoundTrip = 0.0;
            size_t covered = 0;
            for (uint32_t y = 0; y < kHeight; ++y)
                for (uint32_t x = 0; x < kWidth; ++x) {
                    const size_t i = size_t(y) * kWidth + x;
                    if (!out.surfaces.coverage[i]) continue;
                    ++covered;
                    // The depth the decode pass read: a 24-bit UNORM depth as llvmpipe's sampler
                    // converts it (cpu_decode.cpp `sampled`), the read-back value otherwise.
                    const float read = unorm24 ? float(std::nearbyint(double(out.depth[i]) * 16777215.0)) * (1.0f / 16777215.0f)
                                               : out.depth[i];
                    const double d = read;
                    const double exact = (d * p[3][3] - p[3][2]) / (d * p[2][3] - p[2][2]);
                    worst = std::max(worst, ulpsApart(out.surfaces.viewDepth.pixels[i], exact));
                    worstRoundTrip = std::max(
                        worstRoundTrip, ulpsApart(worldRoundTrip(m, int(x), int(y), int(kWidth), int(kHeight), read), exact));
                }
            ASSERT_GT(covered, size_t(kWidth) * kHeight / 4);
            std::printf("[ depth    ] %-13s %-6s view depth within %.2f ulp of the double projection (world round trip: %.2f)\n",
                        name, orbit ? "orbit" : "scene", worst, worstRoundTrip);
            EXPECT_LE(worst, 2.0);
            EXPECT_LT(worst, worstRoundTrip);
        }
    }
}

// Bevy on WebGL2 lights from the 20-bit depth in its G-buffer word b, not from the depth attachment
// (deferred_lighting.wgsl:51-52). Bevy's packing of frag_coord.z, written out here again from
// pbr_deferred_types.wgsl:74-89: code = u32(saturate(z) * 1048575 + 0.5), read as code / 1048575.
// Both decoders' view depth must be the projection's view depth of that value (within 2 ulp of the
// double solution), and must differ from the attachment's on most pixels (else the attachment
// was read). The lighting: the same layout without its depth field lights from the attachment;
// the two images must differ, and only by what moving a point by its 20-bit depth step can do.
TEST_F(CpuDecodeTest, BevyWebgl2LightsFromItsTwentyBitDepth) {
    constexpr uint32_t kWidth = 160, kHeight = 90;
    const Scene scene = makeSphereGridScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    Renderer renderer(test::sharedContext(), scene, sky);
    const Layout webgl2 = loadLayout("bevy-deferred-webgl2");
    const GBufferWiring wiring = generateWiring(webgl2);
    ASSERT_TRUE(wiring.storesDepth);
    for (const bool onCpu : {false, true}) {
        SCOPED_TRACE(onCpu ? "cpu decode" : "decode pass");
        RenderSettings settings = test::decodedFrame(kWidth, kHeight);
        settings.decodeOnCpu = onCpu;
        const RenderOutput out = renderer.render(wiring, settings);
        const CameraMatrices m = computeCameraMatrices(scene.camera, float(kWidth) / float(kHeight), wiring.reversedZ);
        const glm::dmat4 p(m.proj);
        double worst = 0.0;
        size_t covered = 0, moved = 0;
        for (size_t i = 0; i < out.depth.size(); ++i) {
            if (!out.surfaces.coverage[i]) continue;
            ++covered;
            const float z = out.depth[i];  // D32: the rasterised gl_FragCoord.z, as the G-buffer pass saw it
            const uint32_t code = uint32_t(std::min(std::max(z, 0.0f), 1.0f) * 1048575.0f + 0.5f);
            const double d = double(float(code) / 1048575.0f);
            const double exact = (d * p[3][3] - p[3][2]) / (d * p[2][3] - p[2][2]);
            const double attachment = (double(z) * p[3][3] - p[3][2]) / (double(z) * p[2][3] - p[2][2]);
            worst = std::max(worst, ulpsApart(out.surfaces.viewDepth.pixels[i], exact));
            moved += ulpsApart(out.surfaces.viewDepth.pixels[i], attachment) > 4.0;
        }
        std::printf("[ webgl2   ] %s: view depth within %.2f ulp of the 20-bit depth's; %zu of %zu pixels moved from the "
                    "attachment's\n", onCpu ? "cpu decode " : "decode pass", worst, moved, covered);
        ASSERT_GT(covered, size_t(kWidth) * kHeight / 4);
        EXPECT_LE(worst, 2.0);
        EXPECT_GT(moved, covered / 2);
    }
    // The same layout lighting from the attachment: drop the depth field (and its clear value).
    Layout attachment = webgl2;
    for (Target& t : attachment.targets)
        t.fields.erase(std::remove_if(t.fields.begin(), t.fields.end(),
                                      [](const Field& f) { return f.attribute == Attribute::Depth; }),
                       t.fields.end());
    attachment.clears.erase(std::remove_if(attachment.clears.begin(), attachment.clears.end(),
                                           [](const ClearValue& c) { return c.attribute == Attribute::Depth; }),
                            attachment.clears.end());
    const GBufferWiring fromAttachment = generateWiring(attachment);
    ASSERT_FALSE(fromAttachment.storesDepth);
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    const RenderOutput a = renderer.render(wiring, settings), b = renderer.render(fromAttachment, settings);
    ASSERT_EQ(a.hdr.pixels.size(), b.hdr.pixels.size());
    size_t differ = 0;
    double worstRelative = 0.0;
    for (size_t i = 0; i < a.hdr.pixels.size(); ++i) {
        const double x = a.hdr.pixels[i], y = b.hdr.pixels[i];
        differ += x != y;
        worstRelative = std::max(worstRelative, std::abs(x - y) / std::max(std::abs(y), 1e-3));
    }
    std::printf("[ webgl2   ] HDR: %zu of %zu values differ from lighting by the attachment's depth, at most %.3g relative\n",
                differ, a.hdr.pixels.size(), worstRelative);
    EXPECT_GT(differ, a.hdr.pixels.size() / 10);
    EXPECT_LT(worstRelative, 1e-3);
}

// Where the codec cannot stand in for readGBuffer, the wiring has no CPU decoder and the renderer
// keeps the decode pass: a visibility buffer (its readGBuffer resolves triangles) and targets in
// their native formats (the hardware quantises). With the metrics on the device (keepOnDevice),
// the decode pass's images are what they read: no CPU decode either.
TEST(CpuDecodeChoice, DecodePassWhereTheCodecCannotStandIn) {
    RenderSettings cpu;
    cpu.decodeSurfaces = true;
    cpu.decodeOnCpu = true;
    const GBufferWiring visibility = generateWiring(loadLayout("visibility-32"));
    EXPECT_EQ(visibility.cpuDecoder, nullptr);
    EXPECT_FALSE(Renderer::decodesOnCpu(visibility, cpu));
    WiringOptions native;
    native.nativeFormats = true;
    EXPECT_EQ(generateWiring(loadLayout("ue4"), native).cpuDecoder, nullptr);  // ue4's targets map onto UNORM
    const GBufferWiring ue4 = generateWiring(loadLayout("ue4"));
    EXPECT_TRUE(Renderer::decodesOnCpu(ue4, cpu));
    RenderSettings onDevice = cpu;
    onDevice.keepOnDevice = true;
    EXPECT_FALSE(Renderer::decodesOnCpu(ue4, onDevice));
    RenderSettings noDecode = cpu;
    noDecode.decodeSurfaces = false;
    EXPECT_FALSE(Renderer::decodesOnCpu(ue4, noDecode));
}

}  // namespace
}  // namespace gbl
