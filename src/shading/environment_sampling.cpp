// C++ twin of shaders/environment_sampling.glsl (piecewise-constant 2D distribution over the
// equirect texels, [PBRT3 sec. 14.2.4 "Infinite Area Lights"]). Keep in step with the shader.
#include "environment_sampling.h"

#include <algorithm>
#include <cmath>

#include "brdf.h"
#include "environment_map.h"

namespace gbl::shading {

uint32_t environmentCdfSearch(const std::vector<float>& table, uint32_t base, uint32_t n, float u) {
    uint32_t lo = 0u, hi = n;  // invariant: cdf[lo] <= u < cdf[hi] (as far as rounding allows)
    while (hi - lo > 1u) {
        uint32_t mid = (lo + hi) >> 1u;
        if (table[base + mid] <= u) lo = mid; else hi = mid;
    }
    return lo;
}

glm::vec3 sampleEnvironmentDirection(const std::vector<float>& table, glm::vec2 u, float& pdf) {
    uint32_t W = uint32_t(table[0]);
    uint32_t H = uint32_t(table[1]);
    uint32_t marginal = 4u;
    uint32_t j = environmentCdfSearch(table, marginal, H, u.y);
    float c0 = table[marginal + j], c1 = table[marginal + j + 1u];
    float dv = c1 > c0 ? std::clamp((u.y - c0) / (c1 - c0), 0.0f, 1.0f) : 0.5f;
    uint32_t conditional = marginal + H + 1u + j * (W + 1u);
    uint32_t i = environmentCdfSearch(table, conditional, W, u.x);
    float d0 = table[conditional + i], d1 = table[conditional + i + 1u];
    float du = d1 > d0 ? std::clamp((u.x - d0) / (d1 - d0), 0.0f, 1.0f) : 0.5f;
    glm::vec2 uv((float(i) + du) / float(W), (float(j) + dv) / float(H));
    glm::vec3 dir = equirectUvToDirection(uv);
    float sinTheta = std::sin(uv.y * kPi);
    float pUv = table[marginal + H + 1u + H * (W + 1u) + j * W + i];
    pdf = sinTheta > 0.0f ? pUv / (2.0f * kPi * kPi * sinTheta) : 0.0f;
    return dir;
}

float environmentDirectionPdf(const std::vector<float>& table, glm::vec3 dir) {
    uint32_t W = uint32_t(table[0]);
    uint32_t H = uint32_t(table[1]);
    glm::vec2 uv = directionToEquirectUv(dir);
    uint32_t i = std::min(uint32_t(uv.x * float(W)), W - 1u);
    uint32_t j = std::min(uint32_t(uv.y * float(H)), H - 1u);
    float sinTheta = std::sqrt(std::max(1.0f - dir.y * dir.y, 0.0f));
    float pUv = table[4u + H + 1u + H * (W + 1u) + j * W + i];
    return sinTheta > 0.0f ? pUv / (2.0f * kPi * kPi * sinTheta) : 0.0f;
}

}  // namespace gbl::shading
