// light_buffer_encodings.glsl -- how deferred lighting's light buffers quantise light.
// Include file (GLSL 450, no #version). The C++ mirror is src/encoding/light_buffer_encodings.h,
// the same functions with the same expressions: the words agree to the bit (light_buffer_bits_test).
// Which encoding a light buffer uses is declared by its layout ([[light_buffer]] encoding = ...,
// layouts/README.md). float16 (RGBA16F, PC) and float11_11_10 (R11G11B10F) are encodings.glsl's
// encodeFloat16 / encodeFloat11 / encodeFloat10; this file adds the consoles':
//   float7e3  the Xbox 360's A2B10G10R10F (EDRAM "7e3") colour channels;
//   rgbk      the PS3's RGBK (RGBM) in RGBA8.
// Sources: Sousa, Kasyan, Schulz, "Secrets of CryENGINE 3 Graphics Technology", SIGGRAPH 2011
// (light buffers: PC A16B16G16R16F, X360 A2B10G10R10F, PS3 A8B8G8R8 RGBK); RGBM/RGBK as in
// Karis, "RGBM color encoding" (2009): rgb / M in RGB, M = ceil(max(rgb) / range * 255) / 255 in A.
// Only IEEE-exact operations decide a code (integer bit operations, one rounded product per
// comparison); divisions only give first guesses that exact comparisons then correct.
#ifndef GBL_LIGHT_BUFFER_ENCODINGS_GLSL
#define GBL_LIGHT_BUFFER_ENCODINGS_GLSL
#include "encodings.glsl"

// encodeFloat7e3: unsigned 10-bit float, 3-bit exponent (bias 3) | 7-bit mantissa, denormals at
// exponent 0, no Inf/NaN codes: range [0, 31.875]; round to nearest even. Negative (and -0,
// negative NaN) -> 0; x >= 31.9375 (which would round past the top), +Inf, +NaN -> 31.875.
// Error: relative <= 2^-8 for x >= 0.25 (normal), absolute <= 2^-10 below (denormal step 2^-9).
uint encodeFloat7e3(float x) {
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
float decodeFloat7e3(uint code) {
    uint e = (code >> 7u) & 7u;
    uint m = code & 0x7fu;
    if (e == 0u) return float(m) * uintBitsToFloat(118u << 23u);
    return uintBitsToFloat(((e + 124u) << 23u) | (m << 16u));
}

// RGBK in 8:8:8:8 with a declared range R (the largest value a channel holds), unit = R / 255^2
// (a float constant): value = c * k * unit, c the 8-bit channel code, k the 8-bit multiplier.
// k is the smallest in [1, 255] with 255 k unit >= max(rgb) (255 when the brightest channel
// exceeds R: it then clamps), each channel the nearest c (halves round up).
// Error per channel: |decoded - x| <= max(r, g, b) / 510 + R / 130050 for max(r, g, b) <= R.
uint rgbkMultiplier(float m, float unit) {
    uint k = uint(clamp(ceil(m / (255.0 * unit)), 1.0, 255.0));
    while (k < 255u && float(255u * k) * unit < m) k += 1u;
    while (k > 1u && float(255u * (k - 1u)) * unit >= m) k -= 1u;
    return k;
}

uint rgbkChannel(float x, uint k, float halfUnit) {
    uint c = uint(clamp(floor(x / (float(2u * k) * halfUnit) + 0.5), 0.0, 255.0));
    while (c < 255u && x >= float((2u * c + 1u) * k) * halfUnit) c += 1u;
    while (c > 0u && x < float((2u * c - 1u) * k) * halfUnit) c -= 1u;
    return c;
}

// encodeRgbk: rgb (negative and NaN read as 0) -> (r, g, b, k) codes.
uvec4 encodeRgbk(vec3 rgb, float unit) {
    float r = rgb.x > 0.0 ? rgb.x : 0.0;
    float g = rgb.y > 0.0 ? rgb.y : 0.0;
    float b = rgb.z > 0.0 ? rgb.z : 0.0;
    uint k = rgbkMultiplier(max(r, max(g, b)), unit);
    float halfUnit = unit * 0.5;
    return uvec4(rgbkChannel(r, k, halfUnit), rgbkChannel(g, k, halfUnit), rgbkChannel(b, k, halfUnit), k);
}

// decodeRgbk: exact products c * k, one rounding by unit.
vec3 decodeRgbk(uvec4 c, float unit) {
    return vec3(float(c.x * c.w) * unit, float(c.y * c.w) * unit, float(c.z * c.w) * unit);
}

// Rec. 709 luminance of linear light, without fused multiply-adds (bit-exact with the mirror):
// what Engel's light pre-pass keeps of specular light.
float lightLuminance(vec3 c) {
    precise float r = c.x * 0.2126;
    precise float g = c.y * 0.7152;
    precise float b = c.z * 0.0722;
    precise float rg = r + g;
    precise float l = rg + b;
    return l;
}

#endif  // GBL_LIGHT_BUFFER_ENCODINGS_GLSL
