// Importance sampling of the equirectangular environment by luminance (piecewise-constant 2D
// distribution, [PBRT3 sec. 14.2.4 "Infinite Area Lights"]). Include file (no #version); the
// includer declares, before including it,
//     layout(std430, ...) readonly buffer EnvironmentSampling { float environmentSampling[]; };
// and includes environment_map.glsl. The table is built on the CPU by
// src/shading/ibl_precompute.cpp buildEnvironmentSampling (same layout, documented there); the C++
// twin of these functions (same names) is src/shading/environment_sampling.cpp:
//   [0] W, [1] H (as floats), [2], [3] unused,
//   [4 .. 4+H]                     marginal CDF over rows (H + 1 values, 0 .. 1),
//   [5+H .. 5+H+H(W+1))            per row j, the conditional CDF over columns (W + 1 values),
//   then W*H texel pdfs with respect to uv area: p(i, j) W H (sums to W H over the map).
// A direction's solid-angle pdf is p_uv / (2 pi^2 sin(theta)).
#ifndef GBL_ENVIRONMENT_SAMPLING_GLSL
#define GBL_ENVIRONMENT_SAMPLING_GLSL

// Largest k in [0, n) with cdf[base + k] <= u (cdf[base] = 0, cdf[base + n] = 1).
uint environmentCdfSearch(uint base, uint n, float u) {
    uint lo = 0u, hi = n;  // invariant: cdf[lo] <= u < cdf[hi] (as far as rounding allows)
    while (hi - lo > 1u) {
        uint mid = (lo + hi) >> 1u;
        if (environmentSampling[base + mid] <= u) lo = mid; else hi = mid;
    }
    return lo;
}

// Samples a direction with probability ~ luminance x texel solid angle; pdf: per steradian
// (0 for a sample on a pole, which the caller skips).
vec3 sampleEnvironmentDirection(vec2 u, out float pdf) {
    uint W = uint(environmentSampling[0]);
    uint H = uint(environmentSampling[1]);
    uint marginal = 4u;
    uint j = environmentCdfSearch(marginal, H, u.y);
    float c0 = environmentSampling[marginal + j], c1 = environmentSampling[marginal + j + 1u];
    float dv = c1 > c0 ? clamp((u.y - c0) / (c1 - c0), 0.0, 1.0) : 0.5;
    uint conditional = marginal + H + 1u + j * (W + 1u);
    uint i = environmentCdfSearch(conditional, W, u.x);
    float d0 = environmentSampling[conditional + i], d1 = environmentSampling[conditional + i + 1u];
    float du = d1 > d0 ? clamp((u.x - d0) / (d1 - d0), 0.0, 1.0) : 0.5;
    vec2 uv = vec2((float(i) + du) / float(W), (float(j) + dv) / float(H));
    vec3 dir = equirectUvToDirection(uv);
    float sinTheta = sin(uv.y * kPi);
    float pUv = environmentSampling[marginal + H + 1u + H * (W + 1u) + j * W + i];
    pdf = sinTheta > 0.0 ? pUv / (2.0 * kPi * kPi * sinTheta) : 0.0;
    return dir;
}

// Solid-angle pdf with which sampleEnvironmentDirection picks the unit direction `dir`.
float environmentDirectionPdf(vec3 dir) {
    uint W = uint(environmentSampling[0]);
    uint H = uint(environmentSampling[1]);
    vec2 uv = directionToEquirectUv(dir);
    uint i = min(uint(uv.x * float(W)), W - 1u);
    uint j = min(uint(uv.y * float(H)), H - 1u);
    float sinTheta = sqrt(max(1.0 - dir.y * dir.y, 0.0));
    float pUv = environmentSampling[4u + H + 1u + H * (W + 1u) + j * W + i];
    return sinTheta > 0.0 ? pUv / (2.0 * kPi * kPi * sinTheta) : 0.0;
}

#endif  // GBL_ENVIRONMENT_SAMPLING_GLSL
