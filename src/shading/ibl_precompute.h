#pragma once
// Image-based lighting pre-computation on the GPU: the environment as a cube map (with a box-
// filtered mip chain), the pre-filtered specular cube (one roughness per mip), the diffuse
// irradiance as 9 spherical-harmonic coefficients, and the split-sum BRDF LUT.
// The maths are in shaders/ibl_math.glsl (CPU mirror src/shading/ibl_math.h); the shaders are
// shaders/ibl_*.comp.glsl. The disk cache is src/shading/ibl_cache.h.
//
// Conventions:
//   Cube layers: 0 +X, 1 -X, 2 +Y, 3 -Y, 4 +Z, 5 -Z (Vulkan's), texel (x, y) of face f looks along
//   cubeTexelDirection(f, x, y, size).
//   Pre-filtered mip m has roughness m / (mipCount - 1) (ibl_math.glsl mipFromRoughness).
//   Irradiance: E(n) = sum_i sh[i] Y_i(n), Y_i the real SH basis of order 2 (evalIrradianceSh),
//   the cosine-lobe convolution (pi, 2pi/3, pi/4 per band [Ramamoorthi & Hanrahan 2001]) already
//   folded into sh; Lambert diffuse radiance = diffuseColor / pi * max(E, 0).
#include <array>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "ibl_brdf_lut.h"
#include "environment_map.h"
#include "image.h"
#include "vk_resources.h"

namespace gbl {

// Specular IBL modes: the rows of the seed's comparison figure (+ the two analytic fits).
enum class IblMode { GroundTruth = 0, SplitSumShader = 1, SplitSum = 2, EnvBrdfApprox = 3, Bo2 = 4 };
// "ground-truth", "split-sum-shader", "split-sum", "envbrdf-approx", "bo2" (in enum order).
std::vector<std::string> iblModeNames();
std::string iblModeName(IblMode mode);
// Throws UserError naming `text` and listing the known modes.
IblMode parseIblMode(const std::string& text);

struct IblSettings {
    uint32_t sourceFaceSize = 0;        // environment cube mip-0 face; 0 = auto (equirect width / 4, 32..512)
    uint32_t prefilteredFaceSize = 128;  // pre-filtered cube mip-0 face (clamped to the source's)
    uint32_t prefilteredMips = 6;       // roughness levels (clamped so the last face is >= 1 texel)
    uint32_t prefilterSamples = 64;     // per texel, filtered importance sampling
    bool bruteForce = false;            // the seed's PrefilterEnvMap: bruteForceSamples, source mip 0 only
    uint32_t bruteForceSamples = 1024;
    // The converged LUT by default (brdf_lut.h); {Seed, 1024} is the seed's estimator.
    uint32_t lutSize = uint32_t(shading::BrdfLutDefaults{}.size);
    shading::BrdfLutEstimator lutEstimator = shading::BrdfLutDefaults{}.estimator;
    uint32_t lutSamples = shading::BrdfLutDefaults{}.samples;
};

// Fills in the automatic sizes and clamps (what is actually computed, and what the cache keys).
IblSettings resolveIblSettings(const IblSettings& settings, const EnvironmentMap& environment);

// The BRDF LUT variants a command can pick (--brdf-lut): "converged" (visible-normal sampling,
// 4096 samples, the default) and "seed" (the seed's IntegrateBRDF, 1024 samples).
std::vector<std::string> brdfLutVariantNames();
// Sets settings.lutEstimator and lutSamples; throws UserError naming `text` otherwise.
void applyBrdfLutVariant(const std::string& text, IblSettings& settings);
std::string brdfLutVariantName(const IblSettings& settings);

// One mip of a cube: 6 faces of size x size RGBA float, face after face, rows top to bottom.
struct CubeMip {
    uint32_t size = 0;
    std::vector<float> rgba;
};

// The pre-computed IBL, on the CPU (what the cache stores and `gbufferlab ibl` writes).
struct IblMaps {
    IblSettings settings;                  // resolved
    std::vector<CubeMip> prefiltered;      // settings.prefilteredMips levels
    std::array<glm::vec3, 9> irradianceSh{};
    Image brdfLut;                         // 2 channels (A, B), layout of src/brdf_lut.h
    // GPU times of this computation (0 when loaded from the cache).
    double cubeMs = 0.0, prefilterMs = 0.0, lutMs = 0.0;
};

// The IBL on the GPU, as the lighting pass binds it. All images in SHADER_READ_ONLY_OPTIMAL.
struct IblGpu {
    GpuImage environmentCube;  // source cube, full box-filtered mip chain
    GpuImage prefiltered;
    GpuImage brdfLut;          // RG32F
    Buffer environmentSampling;  // buildEnvironmentSampling's table (storage buffer)
    std::array<glm::vec3, 9> irradianceSh{};
    uint32_t sourceFaceSize = 0;
    uint32_t prefilteredMips = 0;
    VkSampler cubeSampler = VK_NULL_HANDLE;  // trilinear, clamp
    VkSampler lutSampler = VK_NULL_HANDLE;   // bilinear, clamp
};

// The ground truth's environment importance sampling (shaders/environment_sampling.glsl reads it):
// a piecewise-constant 2D distribution over the equirect texels, p(i, j) ~ (Y_max(i, j) + eps) sin(theta_j),
// Y_max the largest luminance of the 3x3 texels around (i, j) (so the bilinear spread of a bright
// texel into the cube map stays inside the distribution), eps = 1e-3 x the mean luminance (so no
// lit texel has pdf 0). Layout, floats: W, H, 0, 0; the marginal CDF over rows (H + 1); each
// row's conditional CDF (W + 1 per row); the texel pdfs with respect to uv area, p(i, j) W H.
std::vector<float> buildEnvironmentSampling(const Image& equirect);
// Solid-angle pdf of `direction` under that table, in double (the float twin of the GLSL's
// environmentDirectionPdf, same name, is in environment_sampling.h).
double environmentSamplingPdf(const std::vector<float>& table, glm::vec3 direction);

// Direction (not normalised) of texel (x, y) of `face` in a cube of face width `size`.
glm::vec3 cubeTexelDirection(uint32_t face, float x, float y, uint32_t size);

// ---- the GPU steps (each submits and waits; gpuMs, when given, gets the timestamp-query time) ----
// Equirect -> cube (mip 0) + box mip chain down to 1x1. Returned in SHADER_READ_ONLY_OPTIMAL.
GpuImage createEnvironmentCube(const VulkanContext& ctx, const EnvironmentMap& environment, uint32_t faceSize,
                               double* gpuMs = nullptr);
struct PrefilterParams {
    uint32_t faceSize = 128;
    uint32_t mipCount = 6;
    uint32_t samples = 64;
    bool filtered = true;  // false: the seed's brute force (source mip 0 only)
    // Filtered only: added to each sample's lod. 0: KC08 suggest +1, but measured against a
    // 16384-sample brute force on three 1k HDR maps, every bias > 0 raised the error (over-blur).
    float lodBias = 0.0f;
};
GpuImage prefilterEnvironment(const VulkanContext& ctx, const GpuImage& sourceCube, const PrefilterParams& params,
                              double* gpuMs = nullptr);
GpuImage computeBrdfLutGpu(const VulkanContext& ctx, uint32_t size, uint32_t samples,
                           shading::BrdfLutEstimator estimator = shading::BrdfLutEstimator::Seed,
                           double* gpuMs = nullptr);

// Reads back every mip of a cube image in SHADER_READ_ONLY_OPTIMAL.
std::vector<CubeMip> downloadCube(const VulkanContext& ctx, const GpuImage& cube);
Image downloadBrdfLut(const VulkanContext& ctx, const GpuImage& lut);
// Projects a cube mip's radiance onto SH9 (texel solid angles) and convolves with the cosine lobe.
std::array<glm::vec3, 9> projectIrradianceSh(const CubeMip& mip);
glm::vec3 evalIrradianceSh(const std::array<glm::vec3, 9>& sh, glm::vec3 n);

// Everything, on the GPU, read back (no cache: see loadOrComputeIbl in ibl_cache.h).
IblMaps computeIblMaps(const VulkanContext& ctx, const EnvironmentMap& environment, const IblSettings& settings);
// Uploads the maps and rebuilds the environment cube from `environment` (cheap).
IblGpu createIblGpu(const VulkanContext& ctx, const EnvironmentMap& environment, const IblMaps& maps);
void destroyIblGpu(const VulkanContext& ctx, IblGpu& ibl);

}  // namespace gbl
