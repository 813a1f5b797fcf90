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
// Each texel is integrateBRDF(roughness, NoV, samples) (float, Hammersley, Smith-Schlick with
// k = alpha/2), so texel (x, y) equals that call bit for bit.
#include <glm/glm.hpp>

#include "image.h"

namespace gbl::shading {

// size >= 1, samples >= 1 (throws std::invalid_argument otherwise).
Image computeBrdfLutCpu(int size, int samples);

// Bilinear lookup with clamp-to-edge, texel centres as above: the CPU stand-in for sampling the
// LUT texture at uv = (NoV, roughness) with a linear sampler.
glm::vec2 sampleBrdfLut(const Image& lut, float NoV, float roughness);

}  // namespace gbl::shading
