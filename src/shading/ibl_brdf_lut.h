#pragma once
// The split-sum environment-BRDF LUT ("PreIntegratedGF", [Karis13]) on the CPU: the reference
// the GPU version is compared against.
//
// Layout: 2-channel float image (R = A, the f0 scale; G = B, the bias), size x size.
//   column x <-> NoV       = (x + 0.5) / size   (left = grazing, right = normal incidence)
//   row    y <-> roughness = (y + 0.5) / size   (row 0, the top, = smoothest)
// so with Vulkan texture coordinates (v = 0 at row 0) the LUT is sampled at uv = (NoV, roughness),
// exactly as UE4's EnvBRDF does. Texel centres only: NoV = 0 and roughness = 0 are never
// evaluated (integrateBRDF clamps NoV to kMinIblNoV anyway).
// Each texel is one call of the estimator (float, Smith-Schlick with k = alpha/2, exact Schlick
// Fresnel), so texel (x, y) equals that call bit for bit:
//   VisibleNormals (the default, 4096 samples): integrateBRDFVisible, GGX visible-normal sampling
//     [Heitz18]. Converged: max |error| 3.1e-4 in A and B over the whole 128 x 128 grid, grazing
//     NoV included, against an adaptive double-precision quadrature written in brdf_lut_test
//     (BrdfLut.ConvergedOverWholeGrid asserts < 1e-3); measured 3.08e-4 at roughness 0.035, NoV 0.012.
//   Seed (1024 samples): integrateBRDF, the seed's IntegrateBRDF ([Karis13], D(H) NoH sampling,
//     Hammersley). Off from the converged integral by up to 0.0415 (roughness 0.23, NoV 0.004; weights
//     ~ 1/NoV), 1.05e-2 at NoV 0.1 (ibl_math.h); kept as a variant to compare its noise.
#include <cstdint>

#include <glm/glm.hpp>

#include "image.h"

namespace gbl::shading {

// The estimator of each texel; the value is what the GPU kernel's push constant carries.
enum class BrdfLutEstimator : uint32_t { Seed = 0, VisibleNormals = 1 };
inline constexpr uint32_t kBrdfLutConvergedSamples = 4096;  // VisibleNormals' default
inline constexpr uint32_t kBrdfLutSeedSamples = 1024;       // the seed's NumSamples
// The renderer's default LUT (IblSettings): estimator, samples, size.
struct BrdfLutDefaults {
    BrdfLutEstimator estimator = BrdfLutEstimator::VisibleNormals;
    uint32_t samples = kBrdfLutConvergedSamples;
    int size = 128;
};

// size >= 1, samples >= 1 (throws std::invalid_argument otherwise).
Image computeBrdfLutCpu(int size, int samples, BrdfLutEstimator estimator = BrdfLutEstimator::Seed);

// Bilinear lookup with clamp-to-edge, texel centres as above: the CPU stand-in for sampling the
// LUT texture at uv = (NoV, roughness) with a linear sampler.
glm::vec2 sampleBrdfLut(const Image& lut, float NoV, float roughness);

}  // namespace gbl::shading
