// The converged ground truth of the lighting pass on lavapipe (IblMode::GroundTruth: per-pixel MIS of
// the GGX lobe and the environment, run until its noise target) and its environment-sampling table,
// checked against the split sum where that is exact, against its own noise estimate, and against its
// CPU twin (src/shading/ibl_math.cpp). The pre-computation and the cache are ibl_gpu_test.cpp's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ibl_gpu_test_support.h"
#include "ibl_brdf_lut.h"
#include "ibl_math.h"
#include "ibl_precompute.h"
#include "procedural_sky.h"
#include "renderer.h"
#include "shader_compiler.h"
#include "vk_test_support.h"

namespace gbl {
namespace {

using namespace ibl_test;

// On a constant environment every mode's split is exact, so ground truth (per-pixel importance
// sampling) and split-sum-shader must converge to split-sum (LUT) up to MC and LUT error.
TEST_F(IblGpuTest, GroundTruthConvergesToSplitSumOnAConstantEnvironment) {
    const EnvironmentMap white = constantEnvironment(1.0f);
    const IblMaps maps = computeIblMaps(ctx(), white, iblSizes(32, 32));
    Scene scene = makeSphereGridScene();
    scene.lights.clear();
    Renderer renderer(ctx(), scene, white, maps);
    RenderSettings rs = specularOnly(160, 90, IblMode::SplitSum);
    rs.groundTruthSamples = 64;  // per batch; batches run until the noise target
    const RenderOutput split = renderer.render(makeReferenceWiring(), rs);
    for (IblMode mode : {IblMode::GroundTruth, IblMode::SplitSumShader}) {
        rs.specularIbl = mode;
        const RenderOutput gt = renderer.render(makeReferenceWiring(), rs);
        double sumAbs = 0.0, maxAbs = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < gt.hdr.pixelCount(); ++i) {
            if (gt.hdr.pixels[i * 4 + 3] < 0.5f) continue;
            for (int c = 0; c < 3; ++c) {
                const double d = std::abs(double(gt.hdr.pixels[i * 4 + c]) - split.hdr.pixels[i * 4 + c]);
                sumAbs += d;
                maxAbs = std::max(maxAbs, d);
                ++n;
            }
        }
        std::printf("  %s vs split-sum on white: mean abs %.5f, max abs %.5f\n", iblModeName(mode).c_str(),
                    sumAbs / n, maxAbs);
        EXPECT_LT(sumAbs / n, 5e-3) << iblModeName(mode);
        EXPECT_LT(maxAbs, 0.05) << iblModeName(mode);
    }
}

// The environment-sampling table is a normalised pdf over the sphere that follows luminance.
TEST(EnvironmentSampling, PdfIsNormalisedAndFollowsLuminance) {
    SkyParameters sky;
    const EnvironmentMap env = makeProceduralSky(128, sky);
    const std::vector<float> table = buildEnvironmentSampling(env.image);
    // Integrate the pdf over the sphere on a grid finer than the texels.
    const int nu = 1024, nv = 512;
    double integral = 0.0;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const glm::vec2 uv((i + 0.5f) / nu, (j + 0.5f) / nv);
            const double theta = M_PI * uv.y;
            integral += environmentSamplingPdf(table, equirectUvToDirection(uv)) * std::sin(theta) *
                        (M_PI / nv) * (2.0 * M_PI / nu);
        }
    EXPECT_NEAR(integral, 1.0, 2e-3);
    // Towards the sun the pdf is thousands of times the sky's.
    const double sun = environmentSamplingPdf(table, sky.sunDirection);
    const double zenith = environmentSamplingPdf(table, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_GT(sun / zenith, 1000.0);
}

// White furnace for the converged ground truth: under a constant environment of radiance 1, F0 = 1
// metal spheres reflect their directional albedo A + B (the split-sum LUT, converged to 3e-4
// against a quadrature in brdf_lut_test; the pre-filtered white cube is exactly 1), so the MIS
// estimator (GGX + environment samples) must land on it within its own reported noise.
TEST_F(IblGpuTest, GroundTruthFurnaceGivesDirectionalAlbedoWithinItsNoise) {
    const EnvironmentMap white = constantEnvironment(1.0f);
    const IblMaps maps = computeIblMaps(ctx(), white, iblSizes(32, 32));
    Scene scene = furnaceScene(makeDefaultScene());
    for (Material& m : scene.materials) m.normalTexture = -1;
    Renderer renderer(ctx(), scene, white, maps);
    RenderSettings rs = specularOnly(96, 54, IblMode::SplitSum);
    const RenderOutput split = renderer.render(makeReferenceWiring(), rs);
    rs.specularIbl = IblMode::GroundTruth;
    rs.groundTruthSamples = 32;
    rs.groundTruthNoiseTarget = 0.005;
    const RenderOutput gt = renderer.render(makeReferenceWiring(), rs);
    EXPECT_TRUE(gt.groundTruth.targetMet) << gt.groundTruth.meanRelativeNoise;
    EXPECT_GE(gt.groundTruth.batches, 8);
    double sumAbs = 0.0, sumSe = 0.0, sumSigned = 0.0, sumVar = 0.0;
    size_t n = 0, outside = 0;
    for (size_t i = 0; i < gt.hdr.pixelCount(); ++i) {
        if (gt.hdr.pixels[i * 4 + 3] < 0.5f) continue;
        const double d = std::abs(double(gt.hdr.pixels[i * 4 + 1]) - split.hdr.pixels[i * 4 + 1]);
        const double se = gt.noise.pixels[i];
        sumAbs += d;
        sumSe += se;
        sumSigned += double(gt.hdr.pixels[i * 4 + 1]) - split.hdr.pixels[i * 4 + 1];
        sumVar += se * se;
        outside += d > 5.0 * se + 5e-3 ? 1 : 0;  // 5e-3: the LUT's bilinear interpolation over 128 x 128
        ++n;
    }
    std::printf("  furnace: %zu pixels, mean |GT - (A+B)| %.5f, mean noise (SE) %.5f, %d batches, %.0f ms GPU\n", n,
                sumAbs / n, sumSe / n, gt.groundTruth.batches, gt.groundTruth.lightingMs);
    ASSERT_GT(n, 500u);
    // No bias: the mean signed difference is within 4 standard errors of a mean (+ the LUT's 3e-4).
    EXPECT_LT(std::abs(sumSigned / n), 4.0 * std::sqrt(sumVar) / n + 3e-4) << sumSigned / n;
    EXPECT_LT(sumAbs / n, 1.2 * sumSe / n + 5e-4);  // |error| ~ 0.8 SE when the noise estimate is right
    EXPECT_LE(outside, n / 100);
}

// The noise a ground truth reports is its real noise: two renders with different seeds differ
// by about what their standard errors say (E|a - b| = sqrt(2/pi) sqrt(se_a^2 + se_b^2) ~ 0.8 for
// Gaussian errors), on the built-in sky's 20000-nit sun, where sampling the GGX lobe alone
// does not converge.
TEST_F(IblGpuTest, GroundTruthNoiseEstimateMatchesTheSpreadOfIndependentRuns) {
    const EnvironmentMap sky = makeProceduralSky(256);
    const IblMaps maps = computeIblMaps(ctx(), sky, iblSizes(32));
    Scene scene = makeDefaultScene();
    scene.lights.clear();
    Renderer renderer(ctx(), scene, sky, maps);
    RenderSettings rs = specularOnly(64, 36, IblMode::GroundTruth);
    rs.groundTruthSamples = 32;
    rs.groundTruthNoiseTarget = 0.01;
    const RenderOutput a = renderer.render(makeReferenceWiring(), rs);
    rs.groundTruthSeed = 1;
    const RenderOutput b = renderer.render(makeReferenceWiring(), rs);
    EXPECT_TRUE(a.groundTruth.targetMet);
    EXPECT_TRUE(b.groundTruth.targetMet);
    double ratio = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < a.hdr.pixelCount(); ++i) {
        if (a.hdr.pixels[i * 4 + 3] < 0.5f) continue;
        const float* pa = &a.hdr.pixels[i * 4];
        const float* pb = &b.hdr.pixels[i * 4];
        const double ya = 0.2126 * pa[0] + 0.7152 * pa[1] + 0.0722 * pa[2];
        const double yb = 0.2126 * pb[0] + 0.7152 * pb[1] + 0.0722 * pb[2];
        const double se = std::hypot(double(a.noise.pixels[i]), double(b.noise.pixels[i]));
        if (se <= 0.0) continue;
        ratio += std::abs(ya - yb) / se;
        ++n;
    }
    ASSERT_GT(n, 200u);
    std::printf("  sun sky: mean |a - b| / sqrt(se_a^2 + se_b^2) = %.3f over %zu pixels (Gaussian: 0.80); "
                "%d + %d batches\n", ratio / n, n, a.groundTruth.batches, b.groundTruth.batches);
    EXPECT_GT(ratio / n, 0.4);
    EXPECT_LT(ratio / n, 1.3);
}

// The converged ground truth's estimator, GPU (shaders/ibl_math.glsl specularIBLGroundTruthMis with
// shaders/environment_sampling.glsl) vs its CPU twin (src/shading/ibl_math.cpp, environment_sampling.cpp):
// same sampling table (the built-in sky with its 20000-nit sun), same shifts, 20 cases (roughness
// 0.01 to 1, the sun in and out of the mirror direction, metal and dielectric F0), 256 steps.
// Two radiance look-ups, identical on both sides:
//  - smooth: an analytic function of the direction. Then only the float transcendentals of the two
//    sides differ (by ulps): every case agrees to 1e-5 relative at roughness >= 0.2 (measured worst
//    1.3e-6) and to 5e-4 below, where GGX's D is so steep that an ulp of the half vector moves a
//    sample's weight by ~1e-4 (measured worst 1.2e-4, roughness 0.01 and 0.1).
//  - the sky itself, mip 0 by nearest texel (a storage buffer: no sampler filtering to differ). A
//    sample direction within an ulp of a texel edge can then land in different texels on the two
//    sides; next to the sun that moves one sample's radiance by up to 20000. So: at least half of
//    the cases agree to 1e-4, and every case to 2e-2 (measured: 16 of 20 within 1e-4, the worst 9.3e-3,
//    roughness 1 with the sun off the mirror direction).
TEST_F(IblGpuTest, GroundTruthMisMatchesCpuTwin) {
    const EnvironmentMap sky = makeProceduralSky(256);
    const std::vector<float> table = buildEnvironmentSampling(sky.image);
    std::vector<float> radiance(sky.image.pixelCount() * 3);
    for (size_t i = 0; i < sky.image.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) radiance[i * 3 + c] = sky.image.pixels[i * sky.image.channels + c];
    struct Case {
        glm::vec3 N, V, f0;
        float roughness;
    };
    std::vector<Case> cases;
    const glm::vec3 sun = SkyParameters{}.sunDirection;
    for (float r : {0.01f, 0.1f, 0.3f, 0.6f, 1.0f})
        for (int d = 0; d < 4; ++d) {
            const glm::vec3 N = glm::normalize(glm::vec3(std::sin(1.3f * d), 0.8f + 0.3f * d, std::cos(2.1f * d)));
            // d 0, 1: the sun in the mirror direction; d 2, 3: elsewhere (sky and ground)
            const glm::vec3 L = d < 2 ? sun : glm::normalize(glm::vec3(0.7f, -0.2f + 0.4f * d, -0.3f));
            glm::vec3 V = glm::normalize(2.0f * glm::dot(N, L) * N - L);
            if (glm::dot(N, V) < 0.05f) V = N;
            cases.push_back({N, V, d % 2 ? glm::vec3(0.04f) : glm::vec3(0.95f, 0.64f, 0.54f), r});
        }
    const uint32_t samples = 256, n = uint32_t(cases.size());
    std::vector<glm::vec4> in;
    for (uint32_t c = 0; c < n; ++c) {
        in.push_back(glm::vec4(cases[c].N, cases[c].roughness));
        in.push_back(glm::vec4(cases[c].V, 0.0f));
        in.push_back(glm::vec4(cases[c].f0, 0.0f));
        in.push_back(glm::vec4(shading::randomShift(c, 7u, 0u), shading::randomShift(c, 7u, 1u)));
    }
    const std::string text = R"(#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
layout(std430, set = 0, binding = 0) readonly buffer EnvironmentSampling { float environmentSampling[]; };
layout(std430, set = 0, binding = 1) readonly buffer Radiance { float radiance[]; };
layout(std430, set = 0, binding = 2) readonly buffer Cases { vec4 cases[]; };
layout(std430, set = 0, binding = 3) writeonly buffer Results { vec4 results[]; };
layout(push_constant) uniform Push { uint samples; uint smoothRadiance; } pc;
#include "brdf.glsl"
#include "environment_map.glsl"
vec3 sampleEnvironmentLod(vec3 dir, float lod) {
    if (pc.smoothRadiance != 0u) return vec3(1.0 + 0.5 * dir.x + 0.3 * dir.y * dir.y, 0.8 + 0.2 * dir.z, 1.2 - 0.4 * dir.y);
    uint W = uint(environmentSampling[0]), H = uint(environmentSampling[1]);
    vec2 uv = directionToEquirectUv(dir);
    uint i = min(uint(uv.x * float(W)), W - 1u), j = min(uint(uv.y * float(H)), H - 1u);
    uint o = (j * W + i) * 3u;
    return vec3(radiance[o], radiance[o + 1u], radiance[o + 2u]);
}
#define GBL_IBL_HAS_ENVIRONMENT
#include "environment_sampling.glsl"
#define GBL_IBL_HAS_ENVIRONMENT_SAMPLING
#include "ibl_math.glsl"
void main() {
    uint c = gl_GlobalInvocationID.x;
    vec4 a = cases[4u * c], b = cases[4u * c + 1u], f = cases[4u * c + 2u], s = cases[4u * c + 3u];
    results[c] = vec4(specularIBLGroundTruthMis(f.xyz, a.w, a.xyz, b.xyz, pc.samples, s.xy, s.zw), 0.0);
}
)";
    VulkanContext& c = ctx();
    const test::TestBuffer tableBuf = test::TestBuffer::holding(c, table);
    const test::TestBuffer radianceBuf = test::TestBuffer::holding(c, radiance);
    const test::TestBuffer casesBuf = test::TestBuffer::holding(c, in);
    const test::TestBuffer out(c, n * sizeof(glm::vec4));
    const test::ComputeKernel kernel(
        c, ShaderSource{"ibl_mis_twin.comp", text, VK_SHADER_STAGE_COMPUTE_BIT, {}, {}},
        {{test::storage(tableBuf), test::storage(radianceBuf), test::storage(casesBuf), test::storage(out)}}, 8);
    const shading::EnvironmentLodFn texel = [&](glm::vec3 dir, float) {
        const glm::vec2 uv = directionToEquirectUv(dir);
        const uint32_t W = uint32_t(sky.image.width), H = uint32_t(sky.image.height);
        const uint32_t i = std::min(uint32_t(uv.x * float(W)), W - 1u), j = std::min(uint32_t(uv.y * float(H)), H - 1u);
        const size_t o = (size_t(j) * W + i) * 3;
        return glm::vec3(radiance[o], radiance[o + 1], radiance[o + 2]);
    };
    const shading::EnvironmentLodFn smooth = [](glm::vec3 dir, float) {
        return glm::vec3(1.0f + 0.5f * dir.x + 0.3f * dir.y * dir.y, 0.8f + 0.2f * dir.z, 1.2f - 0.4f * dir.y);
    };
    for (uint32_t smoothRadiance : {1u, 0u}) {
        const uint32_t push[2] = {samples, smoothRadiance};
        kernel.dispatch(n, 1, 1, push);
        const glm::vec4* gpu = out.mapped<const glm::vec4>();
        const char* what = smoothRadiance ? "smooth radiance" : "sky, nearest texel";
        double worst = 0.0;
        uint32_t close = 0;
        for (uint32_t k = 0; k < n; ++k) {
            const Case& cs2 = cases[k];
            const glm::vec3 cpu = shading::specularIBLGroundTruthMis(
                smoothRadiance ? smooth : texel, table, cs2.f0, cs2.roughness, cs2.N, cs2.V, samples,
                glm::vec2(in[4 * k + 3].x, in[4 * k + 3].y), glm::vec2(in[4 * k + 3].z, in[4 * k + 3].w));
            const glm::vec3 g(gpu[k]);
            const double yc = 0.2126 * cpu.x + 0.7152 * cpu.y + 0.0722 * cpu.z;
            const double yg = 0.2126 * g.x + 0.7152 * g.y + 0.0722 * g.z;
            const double rel = std::abs(yg - yc) / std::max(yc, 1e-6);
            worst = std::max(worst, rel);
            close += rel < (smoothRadiance && cs2.roughness < 0.2f ? 5e-4 : 1e-4) ? 1u : 0u;
            std::printf("  %s, roughness %.2f case %u: CPU %.6g GPU %.6g, rel. diff %.2e\n", what, cs2.roughness, k % 4,
                        yc, yg, rel);
            EXPECT_TRUE(std::isfinite(yg)) << k;
            EXPECT_GT(yc, 0.0) << k;
            const double tolerance = smoothRadiance ? (cs2.roughness < 0.2f ? 5e-4 : 1e-5) : 2e-2;
            EXPECT_LT(rel, tolerance) << what << ", case " << k << " roughness " << cs2.roughness;
        }
        std::printf("  %s: %u of %u cases within 1e-4 (smooth, roughness < 0.2: 5e-4), worst relative difference GPU vs CPU %.2e (%u steps)\n", what,
                    close, n, worst, samples);
        EXPECT_GE(close, smoothRadiance ? n : n / 2) << what;
    }
}

}  // namespace
}  // namespace gbl
