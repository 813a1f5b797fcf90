// Geometry helpers of the scene: generated tangents, replaced normals, the camera framing, bounds.
#include "scene_test_support.h"

namespace gbl {
namespace {

using namespace scene_test;

// ---------------------------------------------------------------------------------------------
// Tangent and normal generation

// A unit quad facing +Z with glTF uvs (v = 0 at the top), optionally mirrored in u.
std::vector<Vertex> uvQuad(bool mirrorU) {
    std::vector<Vertex> v(4);
    const glm::vec3 p[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const glm::vec2 uv[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    for (int i = 0; i < 4; ++i) {
        v[size_t(i)].position = p[i];
        v[size_t(i)].normal = glm::vec3(0, 0, 1);
        v[size_t(i)].uv = mirrorU ? glm::vec2(1.0f - uv[i].x, uv[i].y) : uv[i];
    }
    return v;
}

const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

TEST(Tangents, TangentFollowsUAndBitangentPointsUpTheImage) {
    std::vector<Vertex> v = uvQuad(false);
    generateTangents(v, kQuadIndices);
    for (const Vertex& x : v) {
        EXPECT_NEAR(glm::dot(glm::vec3(x.tangent), glm::vec3(1, 0, 0)), 1.0f, 1e-6f);
        EXPECT_EQ(x.tangent.w, 1.0f);  // B = cross(+Z, +X) = +Y: decreasing v, up the image
    }
    std::vector<Vertex> mirrored = uvQuad(true);
    generateTangents(mirrored, kQuadIndices);
    for (const Vertex& x : mirrored) {
        EXPECT_NEAR(glm::dot(glm::vec3(x.tangent), glm::vec3(-1, 0, 0)), 1.0f, 1e-6f);
        EXPECT_EQ(x.tangent.w, -1.0f);  // cross(+Z, -X) = -Y, but up the image is still +Y
    }
}

TEST(Tangents, GeneratedMatchAnalyticSphereTangents) {
    const ShapeMesh sphere = makeUvSphere(1.0f, 64, 32);
    std::vector<Vertex> generated = sphere.vertices;
    generateTangents(generated, sphere.indices);
    for (size_t i = 0; i < generated.size(); ++i) {
        if (std::abs(generated[i].normal.y) > 0.999f) continue;  // poles: u direction is undefined
        EXPECT_GT(glm::dot(glm::vec3(generated[i].tangent), glm::vec3(sphere.vertices[i].tangent)), 0.99f) << i;
        EXPECT_EQ(generated[i].tangent.w, sphere.vertices[i].tangent.w) << i;
    }
}

TEST(Tangents, DegenerateUvsGiveAUnitPerpendicularTangent) {
    std::vector<Vertex> v = uvQuad(false);
    for (Vertex& x : v) {
        x.uv = glm::vec2(0.5f);
        x.normal = glm::normalize(glm::vec3(1, 2, 3));
    }
    generateTangents(v, kQuadIndices);
    for (const Vertex& x : v) {
        EXPECT_TRUE(isUnit(glm::vec3(x.tangent), 1e-5f));
        EXPECT_LT(std::abs(glm::dot(glm::vec3(x.tangent), x.normal)), 1e-5f);
        EXPECT_EQ(std::abs(x.tangent.w), 1.0f);
    }
}

TEST(Tangents, SuppliedTangentIsOrthonormalizedOrRejected) {
    glm::vec4 t(2, 0, 1, 0.3f);  // not unit, not orthogonal to +Z, w not +-1
    ASSERT_TRUE(orthonormalizeTangent(glm::vec3(0, 0, 1), t));
    EXPECT_EQ(t, glm::vec4(1, 0, 0, 1));
    glm::vec4 parallel(0, 0, 5, 1);
    EXPECT_FALSE(orthonormalizeTangent(glm::vec3(0, 0, 1), parallel));
    glm::vec4 nan(NAN, 0, 0, 1);
    EXPECT_FALSE(orthonormalizeTangent(glm::vec3(0, 0, 1), nan));
}

TEST(Normals, ZeroAndNanNormalsAreReplacedByTheFaceNormal) {
    std::vector<Vertex> v = uvQuad(false);
    v[0].normal = glm::vec3(0);
    v[1].normal = glm::vec3(NAN);
    v[2].normal = glm::vec3(0, 0, 7);  // usable, just not unit
    EXPECT_EQ(repairNormals(v, kQuadIndices), 2u);
    for (const Vertex& x : v) EXPECT_EQ(x.normal, glm::vec3(0, 0, 1));
}

// ---------------------------------------------------------------------------------------------
// Framing and bounds

TEST(Camera, FrameBoundsSeesEveryCornerAndScalesNearFarWithTheScene) {
    for (float scale : {0.05f, 1.0f, 500.0f}) {
        const Bounds b{glm::vec3(-1, 0, -0.5f) * scale + glm::vec3(3), glm::vec3(1, 2, 0.5f) * scale + glm::vec3(3)};
        for (float aspect : {0.5f, 1.0f, 16.0f / 9.0f}) {
            SCOPED_TRACE("scale " + std::to_string(scale) + " aspect " + std::to_string(aspect));
            const Camera c = frameBounds(b, aspect);
            expectCameraSeesBounds(c, b, aspect);
            EXPECT_FALSE(c.fromFile);
            EXPECT_LT(c.zFar / scale, 40.0f);   // proportional to the scene's size
            EXPECT_GT(c.zNear / scale, 0.05f);  // not a fixed tiny near plane
        }
    }
    const Camera point = frameBounds(Bounds{glm::vec3(1), glm::vec3(1)}, 1.0f);  // degenerate: still usable
    EXPECT_GT(point.zNear, 0.0f);
    EXPECT_GT(point.zFar, point.zNear);
}

// The tightest fit of a perspective frame to points along a fixed direction: every point inside
// the frame shrunk by the 5% margin, the binding axis touching that margin on both sides (so no
// camera closer, or moved sideways, holds them all), the other axis centred in the image. Checked through glm's own projection, on random clouds, shapes and views.
TEST(Camera, FitPointsInViewIsTheTightestCentredFit) {
    uint32_t state = 12345u;
    auto uniform = [&] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24);
    };
    for (int trial = 0; trial < 40; ++trial) {
        const glm::vec3 stretch(0.02f + 3.0f * uniform(), 0.02f + 3.0f * uniform(), 0.02f + 3.0f * uniform());
        const glm::vec3 offset(100.0f * (uniform() - 0.5f), 10.0f * uniform(), -50.0f * uniform());
        std::vector<glm::vec3> points;
        for (int i = 0; i < 200; ++i)
            points.push_back(offset + stretch * glm::vec3(uniform() - 0.5f, uniform() - 0.5f, uniform() - 0.5f));
        const glm::vec3 toward(uniform() - 0.5f, uniform(), uniform() - 0.5f);
        const float aspect = trial % 3 == 0 ? 16.0f / 9.0f : trial % 3 == 1 ? 1.0f : 0.5f;
        SCOPED_TRACE("trial " + std::to_string(trial));
        const Camera c = fitPointsInView(points, toward, glm::vec3(0, 1, 0), aspect, 0.7f);
        EXPECT_NEAR(glm::dot(glm::normalize(c.position - c.target), glm::normalize(toward)), 1.0f, 1e-4f);
        float loX = 1e9f, hiX = -1e9f, loY = 1e9f, hiY = -1e9f;
        for (const glm::vec3& p : points) {
            const glm::vec4 clip = toClip(c, aspect, p);
            ASSERT_TRUE(insideFrustum(clip));
            loX = std::min(loX, clip.x / clip.w), hiX = std::max(hiX, clip.x / clip.w);
            loY = std::min(loY, clip.y / clip.w), hiY = std::max(hiY, clip.y / clip.w);
        }
        const float edge = 1.0f / 1.05f;
        EXPECT_LE(std::max({hiX, -loX, hiY, -loY}), edge + 1e-4f);
        const bool xBinds = hiX - loX > hiY - loY;
        EXPECT_NEAR(xBinds ? hiX : hiY, edge, 2e-3f);
        EXPECT_NEAR(xBinds ? loX : loY, -edge, 2e-3f);
        EXPECT_NEAR(xBinds ? hiY + loY : hiX + loX, 0.0f, 2e-3f);
    }
}

TEST(SceneBounds, WorldBoundsAppliesEachDrawsModelMatrix) {
    Scene s;
    const ShapeMesh sphere = makeUvSphere(1.0f, 16, 8);
    s.vertices = sphere.vertices;
    s.indices = sphere.indices;
    Draw a;
    a.indexCount = uint32_t(s.indices.size());
    Draw b = a;
    b.model = glm::translate(glm::mat4(1), glm::vec3(10, 0, 0)) * glm::scale(glm::mat4(1), glm::vec3(2));
    s.draws = {a, b};
    const Bounds bounds = worldBounds(s);
    EXPECT_NEAR(bounds.min.x, -1.0f, 1e-5f);
    EXPECT_NEAR(bounds.max.x, 12.0f, 1e-5f);
    EXPECT_NEAR(bounds.max.y, 2.0f, 1e-5f);
    EXPECT_EQ(worldBounds(Scene{}).min, glm::vec3(0));
}



}  // namespace
}  // namespace gbl
