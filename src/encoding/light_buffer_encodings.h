#pragma once
// Light-buffer encodings, C++ mirror of shaders/light_buffer_encodings.glsl (same names, same
// expressions, same order): the codes agree with the GPU's to the bit (light_buffer_bits_test).
// Ranges, errors and sources are stated in the GLSL file.
#include <cmath>

#include "encodings.h"

namespace gbl::enc {

// encodeFloat7e3: unsigned 3e7 float (bias 3, denormals, no Inf/NaN), [0, 31.875], RNE.
inline uint encodeFloat7e3(float x) {
    uint a = floatBitsToUint(x);
    if (a >= 0x80000000u) return 0u;
    if (a >= 0x41ff8000u) return 0x3ffu;
    if (a >= 0x3e800000u) {
        uint odd = (a >> 16u) & 1u;
        return (a - 0x3e000000u + 0x7fffu + odd) >> 16u;
    }
    uint e = a >> 23u;
    uint sub = 141u - e;
    if (sub > 24u) return 0u;
    uint m = (a & 0x7fffffu) | 0x800000u;
    uint q = m >> sub;
    uint rem = m & ((1u << sub) - 1u);
    uint halfway = 1u << (sub - 1u);
    if (rem > halfway || (rem == halfway && (q & 1u) == 1u)) q += 1u;
    return q;
}

// decodeFloat7e3: exact.
inline float decodeFloat7e3(uint code) {
    uint e = (code >> 7u) & 7u;
    uint m = code & 0x7fu;
    if (e == 0u) return float(m) * uintBitsToFloat(118u << 23u);
    return uintBitsToFloat(((e + 124u) << 23u) | (m << 16u));
}

inline uint rgbkMultiplier(float m, float unit) {
    uint k = uint(glm::clamp(std::ceil(m / (255.0f * unit)), 1.0f, 255.0f));
    while (k < 255u && float(255u * k) * unit < m) k += 1u;
    while (k > 1u && float(255u * (k - 1u)) * unit >= m) k -= 1u;
    return k;
}

inline uint rgbkChannel(float x, uint k, float halfUnit) {
    uint c = uint(glm::clamp(std::floor(x / (float(2u * k) * halfUnit) + 0.5f), 0.0f, 255.0f));
    while (c < 255u && x >= float((2u * c + 1u) * k) * halfUnit) c += 1u;
    while (c > 0u && x < float((2u * c - 1u) * k) * halfUnit) c -= 1u;
    return c;
}

// encodeRgbk: rgb (negative and NaN read as 0) -> (r, g, b, k) codes; unit = range / 255^2.
inline glm::uvec4 encodeRgbk(vec3 rgb, float unit) {
    float r = rgb.x > 0.0f ? rgb.x : 0.0f;
    float g = rgb.y > 0.0f ? rgb.y : 0.0f;
    float b = rgb.z > 0.0f ? rgb.z : 0.0f;
    uint k = rgbkMultiplier(std::max(r, std::max(g, b)), unit);
    float halfUnit = unit * 0.5f;
    return glm::uvec4(rgbkChannel(r, k, halfUnit), rgbkChannel(g, k, halfUnit), rgbkChannel(b, k, halfUnit), k);
}

inline vec3 decodeRgbk(glm::uvec4 c, float unit) {
    return vec3(float(c.x * c.w) * unit, float(c.y * c.w) * unit, float(c.z * c.w) * unit);
}

// Rec. 709 luminance, no fused multiply-add (the project compiles with -ffp-contract=off).
inline float lightLuminance(vec3 c) {
    float r = c.x * 0.2126f;
    float g = c.y * 0.7152f;
    float b = c.z * 0.0722f;
    float rg = r + g;
    return rg + b;
}

}  // namespace gbl::enc
