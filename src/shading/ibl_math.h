#pragma once
// Image-based lighting maths on the CPU: the C++ mirror of shaders/ibl_math.glsl (same names, same
// math; the sources of each formula are cited there and in ibl_math.cpp). Namespace gbl::shading.
//
// Conventions (identical to the GLSL):
//   G in every IBL integral: Smith-Schlick with k = alpha/2 (gSmithSchlickIbl) [Karis13 p.3];
//   analytic lights use k = (roughness+1)^2/8 (brdf.h).
//   Pre-filtered cube mips: linear, roughness = mip / (mipCount - 1), mip 0 = mirror.
//   Black Ops 2 gloss: through the Blinn-Phong power, g = log2(2/alpha^2 - 2)/13 clamped to [0,1]
//   (bo2GlossFromRoughness), chosen by the measurements below.
//   BRDF LUT (ibl_brdf_lut.h): u = NoV, v = roughness.
//   Environment access: where the GLSL calls the includer's sampleEnvironmentLod(dir, lod), the
//   C++ takes it as the first argument (an EnvironmentLodFn).
//
// Measured bounds (ibl_math_test asserts each within 0.95x..1.05x, so they cannot go stale).
// "LUT" = our split-sum environment BRDF, integrateBRDFDouble with 4096 samples, on the 64 x 64
// grid NoV = (i+0.5)/64, roughness = (j+0.5)/64; error = |approx - (f0 A + B)|:
//                                        max abs (where)              max, NoV>=0.25   rms
//   envBRDFApprox, f0 = 0.04             0.245 (r 0.086, NoV 0.008)   0.042            0.029
//   envBRDFApprox, f0 = 1                0.332 (r 0.086, NoV 0.008)   0.178            0.079
//   environmentBRDF (BO2), Blinn-Phong g
//                  f0 = 0.04             0.438 (r 0.008, NoV 0.008)   0.030            0.028
//                  f0 = 1                0.435 (r 0.992, NoV 0.992)   0.435            0.162
//   environmentBRDF (BO2), g = 1 - r
//                  f0 = 0.04             0.446 (r 0.008, NoV 0.008)   0.041            0.032
//                  f0 = 1                0.437 (r 0.992, NoV 0.992)   0.437            0.176
// The worst cases sit at the smooth grazing corner (our LUT -> 1 there: a mirror at grazing
// reflects everything) and, for BO2 at f0 = 1, at full roughness: a1vf = 0.25 g + 0.75 knows
// nothing of the energy Smith-Schlick loses (our A + B is 0.31..0.38 at roughness 1).
// Gloss mapping: the Blinn-Phong one wins on every aggregate (rms, NoV >= 0.25) at both f0, so
// bo2GlossFromRoughness uses it. (BO2's power 2^(13 g), range 1..8192, is quoted from memory of
// [Lazarov13]; the measurement, not the citation, is what justifies the choice.)
// envBRDFApproxNonmetal = envBRDFApprox(0.04) up to 1.6e-3 (its constants are rounded);
// envBRDFApprox(f0, roughness 1, NoV) = 0.4524 f0 - 0.0024, hence UE4's 0.45 f0 shortcut.
// White furnace (f0 = 1): A + B <= 1 everywhere; cosine-weighted average E_avg 0.990 / 0.964 /
// 0.923 / 0.802 / 0.547 / 0.377 at roughness 0.1 / 0.2 / 0.3 / 0.5 / 0.8 / 1 (full table in
// ibl_math_test, WhiteFurnace). Smith-Schlick with k = alpha/2 is the loss: at low roughness and
// grazing NoV its G1 falls like 1 - alpha/(2 NoV) where exact Smith-GGX falls like
// 1 - alpha^2/(4 NoV^2), e.g. E = 0.84 at roughness 0.1, NoV 0.05.
// Monte Carlo error of the 1024-sample float LUT against an independent quadrature: up to
// 1.05e-2 at NoV 0.1, 4.3e-3 at NoV 0.25, 3.4e-3 at NoV >= 0.5 (Hammersley's left-endpoint
// y = k/N also biases A by +5e-4 at NoV = 1).
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

namespace gbl::shading {

inline constexpr uint32_t kIblDefaultSamples = 1024;  // the seed's NumSamples
inline constexpr float kMinIblNoV = 1e-4f;             // NoV floor in the IBL integrals

// Radiance along a world direction at a mip level (the GLSL includer's sampleEnvironmentLod).
using EnvironmentLodFn = std::function<glm::vec3(glm::vec3 dir, float lod)>;

// Base-2 radical inverse by bit reversal, top 24 bits times 2^-24: exact for i < 2^24, in [0,1).
float radicalInverseVdC(uint32_t bits);
// Double variant: all 32 reversed bits times 2^-32 (exact), in [0,1).
double radicalInverseVdCDouble(uint32_t bits);
// (i/N, radicalInverseVdC(i)); in [0,1)^2 for i < N <= 2^24.
glm::vec2 hammersley(uint32_t i, uint32_t N);
glm::dvec2 hammersleyDouble(uint32_t i, uint32_t N);

// GGX half vector around N (unit N), tangent frame from up = |N.z| < 0.999 ? +z : +x.
glm::vec3 importanceSampleGGX(glm::vec2 Xi, float roughness, glm::vec3 N);
// GLSL fract: x - floor(x), per component (the Cranley-Patterson shifts of the ground truth).
inline glm::vec2 fractGlsl(glm::vec2 x) { return x - glm::floor(x); }
glm::dvec3 importanceSampleGGXDouble(glm::dvec2 Xi, double roughness, glm::dvec3 N);

// D NoH / (4 VoH): solid-angle pdf of the reflected L.
float pdfGgxReflection(float NoH, float VoH, float roughness);

// [KC08]: lod = max(0.5 log2(Os/Op), 0), Os = 1/(N pdf), Op = 4 pi / (6 faceSize^2).
float filteredSampleLod(float pdf, float numSamples, float faceSize);
// mip = roughness (mipCount - 1); roughness = mip / (mipCount - 1).
float mipFromRoughness(float roughness, float mipCount);
float roughnessFromMip(float mip, float mipCount);

// Split-sum environment BRDF (A, B), f0 A + B = integral of f cos [Karis13 IntegrateBRDF].
glm::vec2 integrateBRDF(float roughness, float NoV, uint32_t numSamples = kIblDefaultSamples);
// The same estimator in double precision throughout (double Hammersley, sampling, G, Fresnel).
glm::dvec2 integrateBRDFDouble(double roughness, double NoV, uint32_t numSamples = kIblDefaultSamples);

// Exact Smith G1 of GGX: 2 NoV / (NoV + sqrt(a^2 + (1 - a^2) NoV^2)), a = roughness^2.
float g1SmithGgxExact(float NoV, float roughness);
// GGX visible-normal sample [Heitz18] in the frame N = +z, V in the xz plane with V.x >= 0.
glm::vec3 importanceSampleVisibleGGX(glm::vec2 Xi, float roughness, glm::vec3 V);
// integrateBRDF's (A, B) estimated with visible-normal sampling (bounded weights F G / G1(V));
// the default BRDF LUT's estimator (brdf_lut.h).
glm::vec2 integrateBRDFVisible(float roughness, float NoV, uint32_t numSamples);

// UE4: f0 AB.x + saturate(50 f0.g) AB.y (the 2% rule).
glm::vec3 envBRDF(glm::vec3 specularColor, glm::vec2 AB);
// UE4 mobile fits.
glm::vec3 envBRDFApprox(glm::vec3 specularColor, float roughness, float NoV);
float envBRDFApproxNonmetal(float roughness, float NoV);
// UE4 mobile, roughness == 1: diffuse += 0.45 specular; specular = 0.
void envBRDFApproxFullyRough(glm::vec3& diffuseColor, glm::vec3& specularColor);

// Black Ops 2 fits, g = gloss in [0,1].
float bo2A0(float g, float NoV);
float bo2A1(float g, float NoV);
float bo2A0f(float g, float NoV);
float bo2A1f(float g, float NoV);
float bo2A004(float g, float NoV);
float bo2A1vf(float g);
float bo2A0r(float g, float NoV);
// saturate(a0r + rf0 (a1vf - a0r)), folded as in the seed.
glm::vec3 environmentBRDF(float g, float NoV, glm::vec3 rf0);
// g = 1 - roughness.
float glossFromRoughnessLinear(float roughness);
// g = log2(2/alpha^2 - 2) / 13 clamped to [0,1] (BO2 power 2^(13 g) matched to GGX alpha).
float glossFromRoughnessBlinnPhong(float roughness);
// The mapping used with environmentBRDF: glossFromRoughnessBlinnPhong.
float bo2GlossFromRoughness(float roughness);

// Ground truth [Karis13 SpecularIBL]: F = (1-Fc) f0 + Fc, Fc = (1-VoH)^5, G with k = alpha/2.
glm::vec3 specularIBLGroundTruth(const EnvironmentLodFn& sampleEnvironmentLod, glm::vec3 specularColor,
                                 float roughness, glm::vec3 N, glm::vec3 V,
                                 uint32_t numSamples = kIblDefaultSamples);
// [Karis13 PrefilterEnvMap], n = v = r, NoL weights / total weight, mip 0.
glm::vec3 prefilterEnvMap(const EnvironmentLodFn& sampleEnvironmentLod, float roughness, glm::vec3 R,
                          uint32_t numSamples = kIblDefaultSamples);
// The same, each sample at filteredSampleLod(D/4, numSamples, faceSize).
glm::vec3 prefilterEnvMapFiltered(const EnvironmentLodFn& sampleEnvironmentLod, float roughness, glm::vec3 R,
                                  uint32_t numSamples, float faceSize);


// ---- the converged ground truth (environment importance sampling + GGX, combined by MIS) ----
// Below this roughness the MIS estimator uses the GGX samples alone (weight 1).
inline constexpr float kMinMisRoughness = 0.02f;
// PCG hash (RXS-M-XS output), as in the GLSL.
uint32_t pcgHash(uint32_t v);
// Cranley-Patterson shift in [0,1)^2 from three integers: pcgHash(a ^ pcgHash(b ^ pcgHash(c))), 24 bits each.
glm::vec2 randomShift(uint32_t a, uint32_t b, uint32_t c);
// Power heuristic, beta = 2: a^2 / (a^2 + b^2) (0 when both are 0).
float powerHeuristic(float a, float b);
// specularIBLGroundTruthMis of shaders/ibl_math.glsl: the integral of specularIBLGroundTruth
// estimated by MIS of one GGX and one environment sample per step (power heuristic), Hammersley
// points shifted by shiftGgx / shiftEnv. `environmentSampling` is the GLSL's storage buffer of the
// same name (buildEnvironmentSampling's table, read through environment_sampling.h).
glm::vec3 specularIBLGroundTruthMis(const EnvironmentLodFn& sampleEnvironmentLod,
                                    const std::vector<float>& environmentSampling, glm::vec3 specularColor,
                                    float roughness, glm::vec3 N, glm::vec3 V, uint32_t numSamples,
                                    glm::vec2 shiftGgx, glm::vec2 shiftEnv);

}  // namespace gbl::shading
