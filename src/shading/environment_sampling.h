#pragma once
// Importance sampling of the equirectangular environment by luminance on the CPU: the C++ twin of
// shaders/environment_sampling.glsl (same names, same float maths). Where the GLSL reads the
// storage buffer `environmentSampling[]`, the C++ takes the table as its first argument. The table
// is buildEnvironmentSampling's (ibl_precompute.h documents its layout). Namespace gbl::shading.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace gbl::shading {

// Largest k in [0, n) with table[base + k] <= u (table[base] = 0, table[base + n] = 1).
uint32_t environmentCdfSearch(const std::vector<float>& table, uint32_t base, uint32_t n, float u);
// A direction with probability ~ luminance x texel solid angle; pdf per steradian (0 on a pole).
glm::vec3 sampleEnvironmentDirection(const std::vector<float>& table, glm::vec2 u, float& pdf);
// Solid-angle pdf with which sampleEnvironmentDirection picks the unit direction `dir`.
float environmentDirectionPdf(const std::vector<float>& table, glm::vec3 dir);

}  // namespace gbl::shading
