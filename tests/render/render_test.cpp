// The backbone's render path on lavapipe: the reference G-buffer + lighting of the built-in
// scene, checked for properties a rendering bug would break.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>
#include <cstring>

#include "layout_catalog.h"
#include "layout.h"
#include "procedural_sky.h"
#include "renderer.h"
#include "wiring_codegen.h"
#include "vk_test_support.h"

namespace gbl {
namespace {

constexpr uint32_t kWidth = 480, kHeight = 270;

struct Rendered {
    Scene scene;
    RenderOutput output;
};

const Rendered& defaultRender() {
    static Rendered r = [] {
        Rendered x;
        x.scene = makeSphereGridScene();
        const EnvironmentMap sky = makeProceduralSky(256);
        Renderer renderer(test::sharedContext(), x.scene, sky);
        RenderSettings s;
        s.width = kWidth;
        s.height = kHeight;
        x.output = renderer.render(makeReferenceWiring(), s);
        return x;
    }();
    return r;
}

// Pixel position of a world point under the scene camera.
glm::ivec2 project(const Scene& scene, glm::vec3 world) {
    const CameraMatrices m = computeCameraMatrices(scene.camera, float(kWidth) / float(kHeight), false);
    const glm::vec4 clip = m.viewProj * glm::vec4(world, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return glm::ivec2((ndc * 0.5f + 0.5f) * glm::vec2(kWidth, kHeight));
}

const Draw& drawWithMaterial(const Scene& scene, const std::string& prefix) {
    for (const Draw& d : scene.draws)
        if (scene.materials[d.material].name.rfind(prefix, 0) == 0) return d;
    throw std::runtime_error("no material named " + prefix);
}

glm::vec3 pixel(const Image& img, glm::ivec2 p) {
    return {img.at(p.x, p.y, 0), img.at(p.x, p.y, 1), img.at(p.x, p.y, 2)};
}

float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

class RenderTest : public test::VulkanTest {};

TEST_F(RenderTest, ImageIsFiniteAndCoversTheSpheres) {
    const Rendered& r = defaultRender();
    const Image& hdr = r.output.hdr;
    ASSERT_EQ(hdr.width, int(kWidth));
    size_t covered = 0;
    for (size_t i = 0; i < hdr.pixelCount(); ++i) {
        for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(hdr.pixels[i * 4 + c])) << "pixel " << i;
        for (int c = 0; c < 3; ++c) ASSERT_GE(hdr.pixels[i * 4 + c], 0.0f) << "negative radiance at pixel " << i;
        covered += hdr.pixels[i * 4 + 3] > 0.5f;
    }
    // Spheres and ground cover a good part of the frame, and the sky the rest.
    EXPECT_GT(covered, hdr.pixelCount() / 4);
    EXPECT_LT(covered, hdr.pixelCount());
    // Every sphere centre is covered.
    for (const Draw& d : r.scene.draws) {
        if (r.scene.materials[d.material].name.rfind("ground", 0) == 0) continue;
        const glm::ivec2 p = project(r.scene, glm::vec3(d.model[3]));
        EXPECT_GT(hdr.at(p.x, p.y, 3), 0.5f) << r.scene.materials[d.material].name;
    }
}

TEST_F(RenderTest, SphereIsBrighterOnItsLitSide) {
    const Rendered& r = defaultRender();
    const Light& sun = r.scene.lights.at(0);
    ASSERT_EQ(sun.type, LightType::Directional);
    const glm::vec3 towardsSun = -glm::normalize(sun.direction);
    const Draw& d = drawWithMaterial(r.scene, "dielectric roughness 1");
    const glm::vec3 centre(d.model[3]);
    const float radius = 0.4f;
    // Points on the sphere facing the sun and facing away (both seen by the camera).
    glm::vec3 side = glm::normalize(glm::vec3(towardsSun.x, towardsSun.y, 0.0f));
    const glm::vec3 toCamera = glm::normalize(r.scene.camera.position - centre);
    const glm::vec3 lit = glm::normalize(side + toCamera) * radius * 0.9f + centre;
    const glm::vec3 dark = glm::normalize(-side + toCamera) * radius * 0.9f + centre;
    const float litLum = luminance(pixel(r.output.hdr, project(r.scene, lit)));
    const float darkLum = luminance(pixel(r.output.hdr, project(r.scene, dark)));
    EXPECT_GT(litLum, 2.0f * darkLum) << "lit " << litLum << " dark " << darkLum;
}

TEST_F(RenderTest, MetalsAreTintedByTheirF0) {
    const Rendered& r = defaultRender();
    // The reference G-buffer stores F0 as float bits in target 2 (rgb).
    const auto& f0Words = r.output.targetWords.at(2);
    const Draw& gold = drawWithMaterial(r.scene, "gold roughness 0.2");
    const glm::ivec2 p = project(r.scene, glm::vec3(gold.model[3]));
    const size_t i = (size_t(p.y) * kWidth + p.x) * 4;
    float f0[3];
    std::memcpy(f0, &f0Words[i], sizeof(f0));
    EXPECT_NEAR(f0[0], 1.0f, 1e-5f);
    EXPECT_NEAR(f0[1], 0.766f, 1e-5f);
    EXPECT_NEAR(f0[2], 0.336f, 1e-5f);
    // And the shaded gold is warm: red > green > blue, around the highlight-free centre.
    const glm::vec3 c = pixel(r.output.hdr, p);
    EXPECT_GT(c.r, c.g);
    EXPECT_GT(c.g, c.b);
    // Under the same (coloured) lights, gold is much redder than the neutral silver metal of
    // similar roughness: its F0 red/blue ratio is 3 against silver's 1.08.
    const Draw& silver = drawWithMaterial(r.scene, "metal roughness 0.24");
    const glm::vec3 s = pixel(r.output.hdr, project(r.scene, glm::vec3(silver.model[3])));
    ASSERT_GT(s.b, 0.0f);
    EXPECT_GT(c.r / c.b, 2.0f * (s.r / s.b)) << "gold " << c.r / c.b << " silver " << s.r / s.b;
}

TEST_F(RenderTest, BackgroundShowsTheEnvironmentAndDepthIsCleared) {
    const Rendered& r = defaultRender();
    // Top row centre: sky, uncovered, depth at the clear value (0: the reference is reversed Z), radiance > 0.
    const size_t i = kWidth / 2;
    EXPECT_EQ(r.output.depth[i], 0.0f);
    EXPECT_EQ(r.output.hdr.at(int(kWidth / 2), 0, 3), 0.0f);
    EXPECT_GT(luminance(pixel(r.output.hdr, {int(kWidth / 2), 0})), 0.0f);
}

TEST_F(RenderTest, DecodeInBandsEqualsDecodeInOnePass) {
    // 270 rows in bands of 16: 17 bands, the last one partial.
    Scene scene = makeSphereGridScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    Renderer renderer(test::sharedContext(), scene, sky);
    RenderSettings s = test::decodedFrame(kWidth, kHeight);
    const RenderOutput whole = renderer.render(makeReferenceWiring(), s);
    s.decodeBandRows = 16;
    const RenderOutput banded = renderer.render(makeReferenceWiring(), s);
    EXPECT_TRUE(whole.targetWords.empty());
    const std::pair<const Image*, const Image*> pairs[] = {
        {&whole.surfaces.normal, &banded.surfaces.normal},       {&whole.surfaces.baseColor, &banded.surfaces.baseColor},
        {&whole.surfaces.roughness, &banded.surfaces.roughness}, {&whole.surfaces.viewDepth, &banded.surfaces.viewDepth},
        {&whole.surfaces.specularColor, &banded.surfaces.specularColor}};
    for (const auto& [a, b] : pairs) {
        ASSERT_EQ(a->pixels.size(), size_t(kWidth) * kHeight * size_t(a->channels));
        ASSERT_EQ(a->pixels, b->pixels);
    }
    EXPECT_EQ(whole.surfaces.coverage, banded.surfaces.coverage);
    size_t covered = 0;
    for (uint8_t c : whole.surfaces.coverage) covered += c;
    EXPECT_GT(covered, size_t(kWidth) * kHeight / 10);  // the spheres are there, in every band's rows
    EXPECT_GT(whole.surfaces.viewDepth.at(kWidth / 2, kHeight - 40, 0) + whole.surfaces.viewDepth.at(kWidth / 2, 40, 0) +
                  whole.surfaces.viewDepth.at(kWidth / 2, kHeight / 2, 0),
              0.0f);
}

TEST_F(RenderTest, ReversedZMatchesForwardZ) {
    const Rendered& r = defaultRender();
    const EnvironmentMap sky = makeProceduralSky(256);
    Renderer renderer(ctx(), r.scene, sky);
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    // The reference is reversed Z (layouts/reference.toml); the same with the conventional mapping.
    GBufferWiring forward = makeReferenceWiring();
    ASSERT_TRUE(forward.reversedZ);
    forward.reversedZ = false;
    const RenderOutput out = renderer.render(forward, s);
    EXPECT_EQ(out.depth[kWidth / 2], 1.0f);  // cleared to 1 with forward Z
    // Same coverage, nearly the same image (positions rebuilt from a different depth mapping).
    size_t differentCoverage = 0, bigDifferences = 0;
    for (size_t i = 0; i < out.hdr.pixelCount(); ++i) {
        differentCoverage += (out.hdr.pixels[i * 4 + 3] > 0.5f) != (r.output.hdr.pixels[i * 4 + 3] > 0.5f);
        const float a = out.hdr.pixels[i * 4], b = r.output.hdr.pixels[i * 4];
        bigDifferences += std::abs(a - b) > 0.01f * std::max(1.0f, b);
    }
    EXPECT_LT(differentCoverage, out.hdr.pixelCount() / 1000);
    EXPECT_LT(bigDifferences, out.hdr.pixelCount() / 100);
}

// The default scene (the grid and its surroundings) fills the frame, alpha-tested wires cut holes,
// and the emissive sign glows: what makes it separate layouts (issue 11 item 6).
TEST_F(RenderTest, DefaultSceneFillsTheFrameWithCutOutsAndEmissive) {
    Scene scene = makeDefaultScene();
    const EnvironmentMap sky = makeProceduralSky(256);
    Renderer renderer(test::sharedContext(), scene, sky);
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    s.decodeSurfaces = true;
    const RenderOutput out = renderer.render(makeReferenceWiring(), s);
    const Image& hdr = out.hdr;
    size_t covered = 0;
    for (int y = 0; y < int(kHeight); ++y)
        for (int x = 0; x < int(kWidth); ++x) covered += hdr.at(x, y, 3) > 0.5f;
    const double coverage = double(covered) / double(kWidth * kHeight);
    std::printf("[ scene    ] default scene covers %.1f%% of the frame\n", 100.0 * coverage);
    EXPECT_GT(coverage, 0.85);

    // The fence (alpha mask, a metal) stands in front of the mosaic wall (a dielectric): along a
    // row through it, metallic alternates between wire and wall, so the cut-outs are holes.
    const Draw& fence = drawWithMaterial(scene, "wire fence");
    const glm::ivec2 c = project(scene, glm::vec3(fence.model[3]));
    const Draw& sign = drawWithMaterial(scene, "emissive sign");
    const glm::ivec2 sc = project(scene, glm::vec3(sign.model[3]));
    ASSERT_TRUE(sc.x > 0 && sc.x < int(kWidth) && sc.y > 0 && sc.y < int(kHeight));
    ASSERT_TRUE(c.x > 0 && c.x < int(kWidth) && c.y > 0 && c.y < int(kHeight));
    // Emissive: the sign's stripes are emissive (decoded surface), and the lit image holds at
    // least that much light there (emissive is added to the reflected light).
    float signMax = 0.0f;
    int brightest = sc.x;
    for (int x = sc.x - 20; x <= sc.x + 20; ++x) {
        const glm::vec3 e(out.surfaces.emissive.at(x, sc.y, 0), out.surfaces.emissive.at(x, sc.y, 1),
                          out.surfaces.emissive.at(x, sc.y, 2));
        if (luminance(e) > signMax) signMax = luminance(e), brightest = x;
    }
    EXPECT_GT(signMax, 0.1f);
    EXPECT_GE(luminance(pixel(hdr, {brightest, sc.y})), 0.99f * signMax);
    int transitions = 0;
    for (int x = c.x - 30; x < c.x + 30; ++x)
        transitions += (out.surfaces.metallic.at(x, c.y, 0) > 0.5f) != (out.surfaces.metallic.at(x + 1, c.y, 0) > 0.5f);
    EXPECT_GE(transitions, 4) << "the alpha-tested fence shows no holes";
}

// emissive = "forward" (issue 11 item 2): the G-buffer pass writes the emissive, unquantised, into
// scene colour and the lighting pass adds it, so making an object emissive changes a forward
// layout's error against the reference (which stores emissive as float32) by nothing more than
// float rounding. Before, the emissive was dropped: the error grew by the whole emission.
TEST_F(RenderTest, ForwardEmissiveAddsNoError) {
    Scene plain = makeDefaultScene();
    Scene glowing = plain;
    int lit = 0;
    for (Material& m : glowing.materials)
        if (m.name.rfind("ground", 0) != 0 && lit++ < 3) m.emissiveFactor = glm::vec3(2.0f, 1.0f, 0.25f);
    ASSERT_GT(lit, 0);
    const EnvironmentMap sky = makeProceduralSky(64);
    RenderSettings rs;
    rs.width = 160;
    rs.height = 90;
    const GBufferWiring ue4 = generateWiring(loadLayout("ue4"));
    ASSERT_TRUE(ue4.emissiveForward);
    auto meanError = [&](const Scene& scene, double& emitted) {
        Renderer renderer(test::sharedContext(), scene, sky);
        const RenderOutput ref = renderer.render(makeReferenceWiring(), rs);
        const RenderOutput out = renderer.render(ue4, rs);
        double sum = 0.0, total = 0.0;
        for (size_t i = 0; i < ref.hdr.pixelCount(); ++i)
            for (int c = 0; c < 3; ++c) {
                sum += std::abs(double(out.hdr.pixels[i * 4 + c]) - double(ref.hdr.pixels[i * 4 + c]));
                total += double(ref.hdr.pixels[i * 4 + c]);
            }
        emitted = total;
        return sum / double(ref.hdr.pixelCount() * 3);
    };
    double plainTotal = 0.0, glowingTotal = 0.0;
    const double without = meanError(plain, plainTotal);
    const double with = meanError(glowing, glowingTotal);
    // The emission is there (in the reference) ...
    EXPECT_GT(glowingTotal - plainTotal, 0.01 * plainTotal);
    // ... and costs the forward layout nothing: the same error with and without it.
    EXPECT_NEAR(with, without, 1e-4 * without + 1e-7) << "without " << without << ", with " << with;
}

// Mean and largest angle (degrees) between a layout's decoded normals and the reference's, over the
// covered pixels where `select(reference normal)` holds.
struct AngleStats {
    double mean = 0.0, max = 0.0;
    int pixels = 0;
};
template <class Select>
AngleStats normalAngles(const SurfaceImages& ref, const SurfaceImages& out, Select select) {
    AngleStats a;
    for (size_t i = 0; i < ref.coverage.size(); ++i) {
        if (!ref.coverage[i]) continue;
        const glm::vec3 r(ref.normal.pixels[i * 3], ref.normal.pixels[i * 3 + 1], ref.normal.pixels[i * 3 + 2]);
        if (!select(r)) continue;
        const glm::vec3 o(out.normal.pixels[i * 3], out.normal.pixels[i * 3 + 1], out.normal.pixels[i * 3 + 2]);
        const double c = glm::clamp(double(glm::dot(glm::normalize(r), glm::normalize(o))), -1.0, 1.0);
        const double deg = std::acos(c) * 180.0 / 3.14159265358979;
        a.mean += deg;
        a.max = std::max(a.max, deg);
        ++a.pixels;
    }
    if (a.pixels) a.mean /= a.pixels;
    return a;
}

// Issue 11 item 4: the normal space is declared. The same layout (crysis3-thin's x, y + z sign)
// declared world Y-up stores the ground's normal at z = 0, where the z-sign encoding is worst;
// declared world Z-up (CryEngine's) the ground's normal is +Z and the error on it drops. Declared
// view space, the decode pass transforms back, so the decoded normals are gbufferlab's world normals
// within the encoding's error (a missing or wrong inverse would be tens of degrees off).
TEST_F(RenderTest, NormalSpaceChangesTheGroundsErrorAndDecodesBackToWorld) {
    const Scene scene = makeDefaultScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    RenderSettings rs;
    rs.width = 320;
    rs.height = 180;
    rs.decodeSurfaces = true;
    Renderer renderer(test::sharedContext(), scene, sky);
    const RenderOutput ref = renderer.render(makeReferenceWiring(), rs);
    auto render = [&](const char* name, StoredSpace space) {
        Layout layout = loadLayout(name);
        layout.space.normal = space;
        return renderer.render(generateWiring(layout), rs).surfaces;
    };
    auto ground = [](glm::vec3 n) { return n.y > 0.999f; };
    auto all = [](glm::vec3) { return true; };
    const SurfaceImages yUp = render("crysis3-thin", StoredSpace::WorldYUp);
    const SurfaceImages zUp = render("crysis3-thin", StoredSpace::WorldZUp);
    const AngleStats gy = normalAngles(ref.surfaces, yUp, ground), gz = normalAngles(ref.surfaces, zUp, ground);
    ASSERT_GT(gy.pixels, 1000);
    std::printf("crysis3-thin ground (%d px): world Y-up mean %.4f max %.4f deg; world Z-up mean %.4f max %.4f deg\n",
                gy.pixels, gy.mean, gy.max, gz.mean, gz.max);
    EXPECT_GT(gy.mean, 2.0 * gz.mean);

    for (const char* name : {"compact-octahedral", "fat-naive", "crysis3-thin"}) {
        const AngleStats world = normalAngles(ref.surfaces, render(name, StoredSpace::WorldYUp), all);
        const AngleStats view = normalAngles(ref.surfaces, render(name, StoredSpace::View), all);
        std::printf("%s all covered (%d px): world Y-up mean %.4f max %.4f deg; view mean %.4f max %.4f deg\n", name,
                    world.pixels, world.mean, world.max, view.mean, view.max);
        EXPECT_LT(view.mean, 3.0 * world.mean + 0.01) << name;
        EXPECT_LT(view.max, 3.0 * world.max + 0.05) << name;
    }
}

// Two ground quads side by side (x in [-2, 0] and [0, 2], z in [-1, 1], y = 0, normal +Y), the
// left with material 0, the right with material 1, seen from above.
Scene makeTwoQuadScene() {
    Scene scene;
    scene.source = "two quads";
    for (int q = 0; q < 2; ++q) {
        const float x0 = q == 0 ? -2.0f : 0.0f;
        const uint32_t base = uint32_t(scene.vertices.size());
        for (int c = 0; c < 4; ++c) {
            Vertex v{};
            v.position = glm::vec3(x0 + float(c & 1) * 2.0f, 0.0f, (c & 2) ? 1.0f : -1.0f);
            v.normal = glm::vec3(0.0f, 1.0f, 0.0f);
            v.tangent = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
            v.uv = glm::vec2(float(c & 1), (c & 2) ? 1.0f : 0.0f);
            scene.vertices.push_back(v);
        }
        Draw d;
        d.firstIndex = uint32_t(scene.indices.size());
        for (uint32_t i : {0u, 2u, 1u, 1u, 2u, 3u}) scene.indices.push_back(base + i);
        d.indexCount = 6;
        d.material = q;
        scene.draws.push_back(d);
        Material m;
        m.name = q == 0 ? "left" : "right";
        m.baseColorFactor = glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);
        m.metallicFactor = 0.0f;
        m.roughnessFactor = 0.7f;
        m.doubleSided = true;
        scene.materials.push_back(m);
    }
    scene.camera.position = glm::vec3(0.0f, 4.0f, 2.5f);
    scene.camera.target = glm::vec3(0.0f);
    scene.camera.zFar = 50.0f;
    scene.bounds = worldBounds(scene);
    return scene;
}

// Pixel of a world point under `scene`'s camera at w x h.
glm::ivec2 projectAt(const Scene& scene, glm::vec3 world, uint32_t w, uint32_t h) {
    const CameraMatrices m = computeCameraMatrices(scene.camera, float(w) / float(h), false);
    const glm::vec4 clip = m.viewProj * glm::vec4(world, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return glm::ivec2((ndc * 0.5f + 0.5f) * glm::vec2(w, h));
}

// Issue 11 item 7: KHR_lights_punctual spot cones are honoured, with the extension's smooth
// attenuation: full inside the inner cone, zero outside the outer, in between between. Before, a
// spot light lit like a point light, everywhere.
TEST_F(RenderTest, SpotLightLightsInsideItsConeOnly) {
    Scene scene = makeTwoQuadScene();
    Light spot;
    spot.type = LightType::Spot;
    spot.position = glm::vec3(0.0f, 2.0f, 0.0f);
    spot.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    spot.intensity = 10.0f;
    spot.innerConeAngle = glm::radians(10.0f);
    spot.outerConeAngle = glm::radians(20.0f);
    scene.lights = {spot};
    const EnvironmentMap sky = makeProceduralSky(32);
    RenderSettings rs;
    rs.width = 240;
    rs.height = 160;
    rs.environmentIntensity = 0.0f;
    rs.diffuseIbl = false;
    Renderer renderer(test::sharedContext(), scene, sky);
    const RenderOutput out = renderer.render(makeReferenceWiring(), rs);
    auto lum = [&](float degrees) {  // the ground point `degrees` off the spot's axis, along +x
        const glm::vec3 p(2.0f * std::tan(glm::radians(degrees)), 0.0f, 0.0f);
        return luminance(pixel(out.hdr, projectAt(scene, p, rs.width, rs.height)));
    };
    const float centre = lum(0.0f), inner = lum(8.0f), between = lum(15.0f), outside = lum(30.0f);
    std::printf("spot: luminance at 0 deg %.5f, 8 deg %.5f, 15 deg %.5f, 30 deg %.6f\n", centre, inner, between,
                outside);
    EXPECT_GT(centre, 0.01f);
    EXPECT_GT(inner, 0.5f * centre);   // inside the inner cone: full intensity (inverse square, n.l only)
    EXPECT_GT(between, 0.0f);          // the smooth edge ...
    EXPECT_LT(between, 0.8f * inner);  // ... dimmer than inside
    EXPECT_EQ(outside, 0.0f);          // outside the outer cone: no light at all
}

// Issue 11 item 7: the stencil extras a layout declares are written: per draw, the reference its
// material's values (or the declared ones) make, with op REPLACE. crysis3-thin: ambient_id in
// s[0:3], decals in s[4:7]; crysis2-slim: indoor in s[7].
TEST_F(RenderTest, StencilExtrasAreWrittenPerMaterial) {
    Scene scene = makeTwoQuadScene();
    scene.materials[0].stencilValues = {{"ambient_id", 5}, {"decals", 1}, {"indoor", 1}};
    scene.materials[1].stencilValues = {{"ambient_id", 9}};
    const EnvironmentMap sky = makeProceduralSky(32);
    RenderSettings rs;
    rs.width = 160;
    rs.height = 100;
    Renderer renderer(test::sharedContext(), scene, sky);
    const glm::ivec2 left = projectAt(scene, glm::vec3(-1.0f, 0.0f, 0.0f), rs.width, rs.height);
    const glm::ivec2 right = projectAt(scene, glm::vec3(1.0f, 0.0f, 0.0f), rs.width, rs.height);
    auto at = [&](const RenderOutput& o, glm::ivec2 p) { return int(o.stencil[size_t(p.y) * rs.width + size_t(p.x)]); };
    const RenderOutput thin = renderer.render(generateWiring(loadLayout("crysis3-thin")), rs);
    ASSERT_EQ(thin.stencil.size(), size_t(rs.width) * rs.height);
    EXPECT_EQ(at(thin, left), 5 | (1 << 4));
    EXPECT_EQ(at(thin, right), 9);  // decals: the declared 0
    EXPECT_EQ(at(thin, glm::ivec2(0, 0)), 0);  // no geometry: cleared to 0
    const RenderOutput slim = renderer.render(generateWiring(loadLayout("crysis2-slim")), rs);
    ASSERT_EQ(slim.stencil.size(), size_t(rs.width) * rs.height);
    EXPECT_EQ(at(slim, left), 0x80);
    EXPECT_EQ(at(slim, right), 0);
}

// Issue 11 item 7: a layout that stores position is lit from the decoded position, transformed
// back from the space it declares. fat-naive stores float16 view-space position; moved 2 km from
// the origin, the same scene declared world-space position keeps float16's 1-2 m steps there, and
// the lighting (V for specular; point-light distances) shows them. Lit from depth instead, both
// would be the same image.
TEST_F(RenderTest, StoredPositionIsWhatTheLightingUses) {
    Scene scene = makeDefaultScene();
    const glm::vec3 offset(2000.0f, 0.0f, 1500.0f);
    for (Draw& d : scene.draws) d.model = glm::translate(glm::mat4(1.0f), offset) * d.model;
    for (Light& l : scene.lights) l.position += offset;
    scene.camera.position += offset;
    scene.camera.target += offset;
    scene.bounds = worldBounds(scene);
    const EnvironmentMap sky = makeProceduralSky(64);
    RenderSettings rs;
    rs.width = 200;
    rs.height = 120;
    Renderer renderer(test::sharedContext(), scene, sky);
    const RenderOutput ref = renderer.render(makeReferenceWiring(), rs);
    Layout fat = loadLayout("fat-naive");
    ASSERT_EQ(fat.space.position, StoredSpace::View);
    const RenderOutput view = renderer.render(generateWiring(fat), rs);
    fat.space.position = StoredSpace::WorldYUp;
    const RenderOutput world = renderer.render(generateWiring(fat), rs);
    auto meanError = [&](const RenderOutput& o) {
        double sum = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < ref.hdr.pixelCount(); ++i) {
            if (ref.hdr.pixels[i * 4 + 3] < 0.5f) continue;
            for (int c = 0; c < 3; ++c) sum += std::abs(double(o.hdr.pixels[i * 4 + c]) - ref.hdr.pixels[i * 4 + c]);
            ++n;
        }
        return sum / double(3 * n);
    };
    const double eView = meanError(view), eWorld = meanError(world);
    std::printf("fat-naive 2 km from the origin: mean |error| position in view space %.6g, in world space %.6g\n",
                eView, eWorld);
    EXPECT_GT(eWorld, 3.0 * eView);
}

}  // namespace
}  // namespace gbl
