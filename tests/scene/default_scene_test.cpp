// Tests of the built-in scene: what it must cover (roughness x metallic, coloured F0, a detailed
// normal map), that its geometry is sound, and that its camera actually sees it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "procedural_textures.h"
#include "scene.h"
#include "scene_detail_normal_map.h"
#include "tangents.h"

namespace gbl {
namespace {

const Scene& defaultScene() {
    static const Scene scene = makeSphereGridScene();
    return scene;
}

// Draws whose geometry is the shared sphere (all but the ground plane, which uses a normal map).
std::vector<const Draw*> sphereDraws(const Scene& s) {
    std::vector<const Draw*> out;
    for (const Draw& d : s.draws)
        if (s.materials[size_t(d.material)].normalTexture == kNoTexture) out.push_back(&d);
    return out;
}

glm::vec3 centreOf(const Draw& d) { return glm::vec3(d.model[3]); }

TEST(DefaultScene, CoversRoughnessFromNearMirrorToFullyRoughForDielectricsAndMetals) {
    const Scene& s = defaultScene();
    std::set<float> dielectric, metal;
    for (const Draw* d : sphereDraws(s)) {
        const Material& m = s.materials[size_t(d->material)];
        if (m.specularColorFactor != glm::vec3(1.0f)) continue;  // the coloured-specular row
        if (m.metallicFactor == 0.0f) dielectric.insert(m.roughnessFactor);
        if (m.metallicFactor == 1.0f) metal.insert(m.roughnessFactor);
    }
    for (const std::set<float>* sweep : {&dielectric, &metal}) {
        ASSERT_GE(sweep->size(), 5u);
        EXPECT_LE(*sweep->begin(), 0.1f);
        EXPECT_EQ(*sweep->rbegin(), 1.0f);
    }
}

TEST(DefaultScene, HasGoldCopperAndAColouredSpecularDielectric) {
    const Scene& s = defaultScene();
    bool gold = false, copper = false, tintedDielectric = false;
    for (const Material& m : s.materials) {
        const glm::vec3 base(m.baseColorFactor);
        if (m.metallicFactor == 1.0f && glm::all(glm::lessThan(glm::abs(base - glm::vec3(1.0f, 0.766f, 0.336f)), glm::vec3(0.02f))))
            gold = true;
        if (m.metallicFactor == 1.0f && glm::all(glm::lessThan(glm::abs(base - glm::vec3(0.955f, 0.638f, 0.538f)), glm::vec3(0.02f))))
            copper = true;
        // KHR_materials_specular: F0 = min(0.04 * colour, 1) * factor; red clearly above green.
        const glm::vec3 f0 = glm::min(0.04f * m.specularColorFactor, 1.0f) * m.specularFactor;
        if (m.metallicFactor == 0.0f && f0.r > 2.0f * f0.g && f0.r > 0.06f) tintedDielectric = true;
    }
    EXPECT_TRUE(gold);
    EXPECT_TRUE(copper);
    EXPECT_TRUE(tintedDielectric);
}

TEST(DefaultScene, GroundNormalMapIsLinearDetailedAndDeterministic) {
    const Scene& s = defaultScene();
    const auto ground = std::find_if(s.materials.begin(), s.materials.end(),
                                     [](const Material& m) { return m.normalTexture != kNoTexture; });
    ASSERT_NE(ground, s.materials.end());
    const Texture& map = s.textures[size_t(ground->normalTexture)];
    EXPECT_EQ(map.width, 1024);
    EXPECT_EQ(map.height, 1024);
    EXPECT_FALSE(map.srgb);
    ASSERT_EQ(map.rgba.size(), size_t(1024) * 1024 * 4);

    // Decoded normals are unit-ish and face outwards; they vary a lot (not a flat map), and
    // neighbouring texels differ (detail at the texel scale, not only large bumps).
    double sumX = 0, sumY = 0, sumSqX = 0, neighbourDiff = 0;
    size_t backFacing = 0;
    const size_t n = size_t(map.width) * size_t(map.height);
    for (size_t i = 0; i < n; ++i) {
        const uint8_t* p = &map.rgba[i * 4];
        const glm::vec3 normal = glm::vec3(p[0], p[1], p[2]) / 255.0f * 2.0f - 1.0f;
        EXPECT_NEAR(glm::length(normal), 1.0f, 0.02f);
        backFacing += normal.z <= 0.0f ? 1 : 0;
        sumX += normal.x;
        sumY += normal.y;
        sumSqX += normal.x * normal.x;
        if (i % 1024 != 1023) neighbourDiff += std::abs(int(p[0]) - int(p[4]));
    }
    EXPECT_EQ(backFacing, 0u);
    EXPECT_NEAR(sumX / double(n), 0.0, 0.02);  // tileable height: slopes average out
    EXPECT_NEAR(sumY / double(n), 0.0, 0.02);
    EXPECT_GT(std::sqrt(sumSqX / double(n)), 0.1);   // measured 0.155
    EXPECT_GT(neighbourDiff / double(n), 3.0);        // measured 12.8; mean |dR| between neighbours, in 8-bit steps

    EXPECT_EQ(makeDetailNormalMap(1024).rgba, map.rgba) << "must be deterministic";
}

TEST(DefaultScene, NormalsAndTangentsAreUnitOrthogonalAndTrianglesFaceOutwards) {
    const Scene& s = defaultScene();
    for (const Vertex& v : s.vertices) {
        ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
        ASSERT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-5f);
        ASSERT_LT(std::abs(glm::dot(v.normal, glm::vec3(v.tangent))), 1e-5f);
        ASSERT_EQ(std::abs(v.tangent.w), 1.0f);
    }
    // Counter-clockwise triangles (glTF front faces) must face along their vertex normals.
    for (const Draw& d : s.draws) {
        for (uint32_t i = 0; i < d.indexCount; i += 3) {
            const auto vertex = [&](uint32_t k) -> const Vertex& {
                return s.vertices[s.indices[d.firstIndex + i + k] + uint32_t(d.vertexOffset)];
            };
            const glm::vec3 face = glm::cross(vertex(1).position - vertex(0).position, vertex(2).position - vertex(0).position);
            ASSERT_GT(glm::length(face), 0.0f) << "degenerate triangle " << i;
            ASSERT_GT(glm::dot(face, vertex(0).normal + vertex(1).normal + vertex(2).normal), 0.0f) << "triangle " << i;
        }
    }
}

TEST(DefaultScene, TangentsAgreeWithTheGeneratorsConvention) {
    // The built-in meshes write analytic tangents; they must match what generateTangents (and
    // glTF's own files, see scene_test) use, or the ground's bumps would light inside out.
    const Scene& s = defaultScene();
    std::vector<Vertex> generated = s.vertices;
    std::set<int32_t> done;  // the sphere geometry is shared by many draws
    for (const Draw& d : s.draws) {
        if (!done.insert(d.vertexOffset).second) continue;
        // Each draw's index range is relative to its vertexOffset.
        std::span<Vertex> vertices(generated.data() + d.vertexOffset, generated.size() - size_t(d.vertexOffset));
        generateTangents(vertices, std::span<const uint32_t>(s.indices.data() + d.firstIndex, d.indexCount));
    }
    size_t compared = 0;
    for (size_t i = 0; i < generated.size(); ++i) {
        if (std::abs(s.vertices[i].normal.y) > 0.999f && s.vertices[i].position.y != 0.0f) continue;  // sphere poles
        EXPECT_GT(glm::dot(glm::vec3(generated[i].tangent), glm::vec3(s.vertices[i].tangent)), 0.99f) << i;
        EXPECT_EQ(generated[i].tangent.w, s.vertices[i].tangent.w) << i;
        ++compared;
    }
    EXPECT_GT(compared, 2000u);
}

TEST(DefaultScene, CameraSeesEverySphereWhole) {
    const Scene& s = defaultScene();
    const auto spheres = sphereDraws(s);
    ASSERT_GE(spheres.size(), 18u);  // 6 roughness columns x (dielectric, metal, coloured) rows
    const float radius = glm::length(s.vertices[0].position);  // sphere geometry comes first
    for (float aspect : {1.0f, 16.0f / 9.0f}) {
        const Camera& c = s.camera;
        const glm::mat4 viewProj = glm::perspective(c.yFovRadians, aspect, c.zNear, c.zFar) * glm::lookAt(c.position, c.target, c.up);
        for (const Draw* d : spheres) {
            // Centre and the four silhouette extremes: the whole sphere is on screen.
            for (const glm::vec3& offset : {glm::vec3(0), glm::vec3(radius, 0, 0), glm::vec3(-radius, 0, 0),
                                            glm::vec3(0, radius, 0), glm::vec3(0, -radius, 0)}) {
                const glm::vec4 clip = viewProj * glm::vec4(centreOf(*d) + offset, 1.0f);
                EXPECT_GT(clip.w, 0.0f);
                EXPECT_LE(std::abs(clip.x), clip.w) << "aspect " << aspect;
                EXPECT_LE(std::abs(clip.y), clip.w) << "aspect " << aspect;
                EXPECT_GE(clip.z, 0.0f);
                EXPECT_LE(clip.z, clip.w);
            }
        }
    }
}

TEST(DefaultScene, IsModestInSizeWithBoundsLightsAndSource) {
    const Scene& s = defaultScene();
    EXPECT_LT(s.vertices.size(), 10000u);  // one shared sphere mesh + the ground
    EXPECT_EQ(s.source, "built-in sphere grid");
    EXPECT_EQ(makeDefaultScene().source, "built-in default scene");
    EXPECT_LE(s.bounds.min.y, 0.0f);        // ground at y = 0
    EXPECT_GE(s.bounds.max.y, 2.8f);        // top row of spheres
    EXPECT_GE(s.bounds.max.x - s.bounds.min.x, 6.0f);
    ASSERT_GE(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, LightType::Directional);
    for (const Light& l : s.lights) EXPECT_NEAR(glm::length(l.direction), 1.0f, 1e-5f);
    for (const Draw& d : s.draws) {
        ASSERT_LE(size_t(d.firstIndex) + d.indexCount, s.indices.size());
        ASSERT_LT(size_t(d.material), s.materials.size());
    }
}

// The default scene = the grid + what fills the frame around it (issue 11 item 6). Each property
// below is one a layout can lose.
TEST(DefaultScene, SurroundingsStressChromaMetalEdgesEmissiveCutOutsAndDepth) {
    const Scene s = makeDefaultScene();
    const Scene grid = makeSphereGridScene();
    EXPECT_GT(s.draws.size(), grid.draws.size() + 10);
    auto texel = [](const Texture& t, int x, int y, int c) { return int(t.rgba[(size_t(y) * t.width + x) * 4 + c]); };
    bool chroma = false, metalEdges = false, emissive = false, cutOut = false;
    for (const Material& m : s.materials) {
        if (m.baseColorTexture != kNoTexture && !m.alphaMask && m.metallicRoughnessTexture == kNoTexture) {
            // Saturated: max - min channel over 100 on most texels, and the hue changes within 8 texels.
            const Texture& t = s.textures[size_t(m.baseColorTexture)];
            size_t saturated = 0, changes = 0;
            for (int y = 0; y < t.height; ++y)
                for (int x = 0; x + 1 < t.width; ++x) {
                    const int r = texel(t, x, y, 0), g = texel(t, x, y, 1), b = texel(t, x, y, 2);
                    saturated += std::max({r, g, b}) - std::min({r, g, b}) > 100;
                    changes += std::abs(r - texel(t, x + 1, y, 0)) + std::abs(g - texel(t, x + 1, y, 1)) > 100;
                }
            const double n = double(t.width) * t.height;
            chroma = chroma || (saturated > 0.5 * n && changes > n / 8.0);
        }
        if (m.metallicRoughnessTexture != kNoTexture) {
            // Sharp: a texel that is fully metal beside one fully dielectric (B = 255 vs 0).
            const Texture& t = s.textures[size_t(m.metallicRoughnessTexture)];
            for (int y = 0; y < t.height && !metalEdges; ++y)
                for (int x = 0; x + 1 < t.width; ++x)
                    if (std::abs(texel(t, x, y, 2) - texel(t, x + 1, y, 2)) == 255) metalEdges = true;
        }
        if (m.emissiveTexture != kNoTexture && glm::length(m.emissiveFactor) > 0.0f) emissive = true;
        if (m.alphaMask && m.baseColorTexture != kNoTexture) {
            const Texture& t = s.textures[size_t(m.baseColorTexture)];
            size_t holes = 0;
            for (size_t i = 3; i < t.rgba.size(); i += 4) holes += t.rgba[i] < 255.0f * m.alphaCutoff;
            cutOut = holes > t.rgba.size() / 8 && holes < t.rgba.size() / 4;  // most of it, not all
        }
    }
    EXPECT_TRUE(chroma);
    EXPECT_TRUE(metalEdges);
    EXPECT_TRUE(emissive);
    EXPECT_TRUE(cutOut);
    // Depth precision: geometry 100 m and more from the camera, inside its far plane.
    float farthest = 0.0f;
    for (const Draw& d : s.draws) farthest = std::max(farthest, glm::length(glm::vec3(d.model[3]) - s.camera.position));
    EXPECT_GE(farthest, 100.0f);
    EXPECT_LT(farthest, s.camera.zFar);
}

// Occlusion maps as real assets carry them: the ground's, baked from the spheres above it, and the
// tiles', packed with their roughness and metallic (R, G, B of one texture, as FlightHelmet and
// WaterBottle pack theirs). Neither is constant, so a layout that drops occlusion (UE with static
// lighting decodes AO = 1) loses on the built-in scene as on real content.
TEST(DefaultScene, CarriesOcclusionMapsThatAreNotConstant) {
    const Scene s = makeDefaultScene();
    auto red = [](const Texture& t, int x, int y) { return int(t.rgba[(size_t(y) * size_t(t.width) + size_t(x)) * 4]); };
    int maps = 0;
    bool packed = false;
    const Texture* ground = nullptr;
    for (const Material& m : s.materials) {
        if (m.occlusionTexture == kNoTexture) continue;
        ++maps;
        const Texture& t = s.textures[size_t(m.occlusionTexture)];
        EXPECT_FALSE(t.srgb) << m.name;  // linear data, as glTF's occlusionTexture
        EXPECT_EQ(m.occlusionStrength, 1.0f) << m.name;
        int lo = 255, hi = 0;
        for (int y = 0; y < t.height; ++y)
            for (int x = 0; x < t.width; ++x) lo = std::min(lo, red(t, x, y)), hi = std::max(hi, red(t, x, y));
        EXPECT_LT(lo, 100) << m.name;
        EXPECT_GE(hi, 250) << m.name;  // open sky: the ground far from every sphere, a tile away from its grooves
        packed = packed || m.occlusionTexture == m.metallicRoughnessTexture;
        if (m.name.rfind("ground", 0) == 0) ground = &t;
    }
    EXPECT_EQ(maps, 2);
    EXPECT_TRUE(packed);
    ASSERT_NE(ground, nullptr);
    // The 14 m ground, uv 0..1 across it: black where the large sphere (centre (-2.6, 0.8, 2.0),
    // radius 0.8) touches it, open sky at its corner, far from every sphere.
    const auto at = [&](float x, float z) {
        return red(*ground, int((x / 14.0f + 0.5f) * float(ground->width)), int((z / 14.0f + 0.5f) * float(ground->height)));
    };
    EXPECT_LE(at(-2.6f, 2.0f), 5);
    EXPECT_GE(at(-6.9f, -6.9f), 250);
    EXPECT_LT(at(0.0f, 0.0f), at(0.0f, 3.0f));  // under the grid's middle, darker than in front of it
    // The grid's columns do not touch the ground (their lowest point is 0.1 m above it): grey, not black.
    EXPECT_GT(at(-2.5f, 0.0f), 40);
}

// The occlusion a baker writes: one sphere of radius r, its centre h above the ground and d from a
// texel, hides h r^2 / d^3 of the texel's cosine-weighted sky; several multiply what they leave.
TEST(DefaultScene, GroundOcclusionIsTheSpheresFormFactor) {
    // 101 texels over 10.1 m: texel 50's centre is the origin, texel 60's is 1 m along +X.
    const Texture t = makeGroundOcclusion(101, 10.1f, {{glm::vec3(0.0f, 1.0f, 0.0f), 0.5f}});
    auto red = [&](int x, int y) { return int(t.rgba[(size_t(y) * 101 + size_t(x)) * 4]); };
    EXPECT_EQ(red(50, 50), 191);  // 1 - 0.25, in 8 bits
    const double d = std::sqrt(2.0);
    EXPECT_EQ(red(60, 50), int(std::lround((1.0 - 0.25 / (d * d * d)) * 255.0)));
    EXPECT_EQ(red(60, 50), red(40, 50));
    EXPECT_EQ(red(60, 50), red(50, 60));
    for (size_t i = 1; i < t.rgba.size(); i += 4) ASSERT_EQ(t.rgba[i], 255);  // G, B, A
    const Texture two = makeGroundOcclusion(101, 10.1f, {{glm::vec3(0.0f, 1.0f, 0.0f), 0.5f},
                                                         {glm::vec3(0.0f, 2.0f, 0.0f), 0.5f}});
    EXPECT_EQ(two.rgba[(50 * 101 + 50) * 4], std::lround(0.75 * (1.0 - 2.0 * 0.25 / 8.0) * 255.0));
    const Texture touching = makeGroundOcclusion(101, 10.1f, {{glm::vec3(0.0f, 0.5f, 0.0f), 0.5f}});
    EXPECT_EQ(touching.rgba[(50 * 101 + 50) * 4], 0);
}

}  // namespace
}  // namespace gbl
