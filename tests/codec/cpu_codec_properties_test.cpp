// Properties of the CPU codec (src/codec/cpu_codec.h) that need no reference codec: neutral chroma
// has a code of its own, mismatched sizes are refused, and the stored normal spaces
// (src/codec/normal_space.h) are undone. Its equality with the per-pixel reference codec, for every
// layout and thread count, is cpu_codec_test.cpp's.
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "cpu_codec.h"
#include "encodings.h"
#include "layout_catalog.h"
#include "layout_files.h"
#include "normal_space.h"

namespace gbl {
namespace {

// The YCbCr family's neutral chroma has a code of its own (CryEngine's 127/255 midpoint): black
// and grey, a metal's diffuse colour among them, decode without a tint.
TEST(CpuCodec, NeutralChromaDecodesWithoutTint) {
    EXPECT_EQ(enc::quantizeChroma(0.5f, 8), 127u);
    EXPECT_EQ(enc::dequantizeChroma(127u, 8), 0.5f);
    for (const char* name : {"crysis3-thin", "ryse"}) {
        SCOPED_TRACE(name);
        const Layout layout = test::shippedLayout(name);
        std::vector<Surface> in(16);
        for (Surface& s : in) {
            s.normal = glm::vec3(0, 0, 1);
            s.roughness = 0.3f;
            s.diffuseColor = glm::vec3(0.0f);  // a metal
            s.specularColor = glm::vec3(0.5f);  // grey F0
        }
        const std::vector<Surface> out = decodeGBuffer(layout, encodeGBuffer(layout, in, 4, 4));
        for (const Surface& s : out) {
            EXPECT_LT(glm::length(s.diffuseColor), 1e-6f);
            EXPECT_LT(std::abs(s.specularColor.x - s.specularColor.z), 1e-6f);
            EXPECT_LT(std::abs(s.specularColor.y - s.specularColor.z), 1e-6f);
        }
    }
}

TEST(CpuCodec, RejectsMismatchedSizes) {
    const Layout layout = test::shippedLayout("ue4");
    const CpuCodec codec(layout);
    EXPECT_THROW(codec.encode(std::vector<Surface>(5), 2, 2), std::invalid_argument);
    CpuGBuffer g = codec.encode(std::vector<Surface>(4), 2, 2);
    g.targetWords[0].pop_back();
    EXPECT_THROW(codec.decode(g), std::invalid_argument);
}

// The CPU mirror of shaders/normal_space.glsl (issue 11 item 4): the world Z-up swap is
// right-handed, puts the ground's normal (+Y) on +Z and is undone exactly (bit for bit, as the
// GLSL's component shuffle and negation); view space is undone within float rounding.
TEST(NormalSpace, TransformsAreUndoneAndZUpIsRightHanded) {
    EXPECT_EQ(yUpToZUp(glm::vec3(0, 1, 0)), glm::vec3(0, 0, 1));
    EXPECT_EQ(yUpToZUp(glm::vec3(0, 0, 1)), glm::vec3(0, -1, 0));
    const glm::vec3 x = yUpToZUp({1, 0, 0}), y = yUpToZUp({0, 1, 0}), z = yUpToZUp({0, 0, 1});
    EXPECT_EQ(glm::cross(x, y), z);  // right-handed: a rotation, not a reflection
    const glm::mat4 view = glm::lookAt(glm::vec3(3.0f, 2.0f, 5.0f), glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(0, 1, 0));
    std::mt19937 rng(11);
    std::normal_distribution<float> g;
    for (int i = 0; i < 10000; ++i) {
        const glm::vec3 n = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
        const glm::vec3 z2 = directionFromStored(directionToStored(n, StoredSpace::WorldZUp, view), StoredSpace::WorldZUp, view);
        ASSERT_EQ(std::memcmp(&z2, &n, sizeof n), 0);
        const glm::vec3 v = directionFromStored(directionToStored(n, StoredSpace::View, view), StoredSpace::View, view);
        ASSERT_LT(glm::length(v - n), 1e-6f);
        const glm::vec3 p = n * 40.0f;
        const glm::vec3 pv = pointFromStored(pointToStored(p, StoredSpace::View, view), StoredSpace::View, view);
        ASSERT_LT(glm::length(pv - p), 1e-4f);
    }
    // View space: the camera looks down -Z, so a normal facing the camera has z > 0.
    const glm::vec3 toCamera = glm::normalize(glm::vec3(3.0f, 1.5f, 5.0f));
    EXPECT_GT(directionToStored(toCamera, StoredSpace::View, view).z, 0.999f);
}

}  // namespace
}  // namespace gbl
