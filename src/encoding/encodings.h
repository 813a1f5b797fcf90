#pragma once
// Encoding primitives, C++ mirror of shaders/encodings.glsl (same names, same expressions, same
// order, float only). Each function's range, bits, error bound and source is stated above its
// definition in both files. GPU-written codes and these functions' codes agree to the bit for
// every encoder (quantise with floor(x * s + 0.5), only IEEE-exact operations); decoders are
// compared with a tolerance. The layout-language names live in encoding_registry.h.
#include <cmath>

#include <glm/glm.hpp>

#include "best_fit_normals.h"

namespace gbl::enc {

// GLSL spellings, so that the mirror reads like the shader.
using glm::ivec2;
using glm::mat4;
using glm::uint;
using glm::uvec2;
using glm::uvec3;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using glm::abs;
using glm::clamp;
using glm::dot;
using glm::floatBitsToUint;
using glm::floor;
using glm::max;
using glm::min;
using glm::normalize;
using glm::sqrt;
using glm::step;
using glm::uintBitsToFloat;

// Defined out of line in encodings.cpp: the sRGB tables, the searches and the projections no seed
// layout uses. Everything else is defined inline below (moved from encodings.cpp unchanged), so
// that the CPU codec's per-pixel loops (src/cpu_codec*.cpp) inline and vectorise them.
extern const float kSrgbDecode[256];
extern const float kSrgbEncodeThresholds[255];
extern const float kGamma22Decode[256];
extern const float kGamma22EncodeThresholds[255];
uvec3 encodeNormalBestFitSearch(vec3 n);  // the reference search behind the best-fit table
uvec2 encodeNormalSpheremap(vec3 n, uint bits);
vec3 decodeNormalSpheremap(uvec2 code, uint bits);
uvec2 encodeNormalStereographic(vec3 n, uint bits);
vec3 decodeNormalStereographic(uvec2 code, uint bits);
uvec2 encodeNormalOctahedralPrecise(vec3 n, uint bits);
vec3 decodeNormalOctahedralPrecise(uvec2 code, uint bits);
vec3 positionFromDepth(vec2 uv, float depth, mat4 invViewProj);

// 6. Chroma checkerboard (Mavridis & Papaioannou 2012).
// The paper's THRESH is 30/255: lumas 30 or more 8-bit codes apart are an edge. Compared in
// float, |k/255 - j/255| for codes exactly 30 apart falls below 30/255 for 134 of the 226 pairs
// and not for the other 92 (float32, any IEEE machine), and a driver whose UNORM conversion or
// division rounds otherwise decides other pairs otherwise: on an NVIDIA H200 the decode disagreed
// with this mirror on 0.75% of crysis3-thin's values. Half a code lower, every pair of 8-bit codes
// is decided as the integers are (color_encodings_test), with room for a few ulp of error.
inline constexpr float kChromaEdgeThreshold = 0.115686275f;  // 29.5/255

// ---------------------------------------------------------------------------------------------
// 1. Fixed point. Source: Vulkan spec, "Fixed-Point Data Conversions" (but ties round up).
// ---------------------------------------------------------------------------------------------

// quantizeUnorm: x in [0,1] (clamped) -> code in [0, 2^bits-1]; bits 1..24.
// Error: |dequantizeUnorm(code) - x| <= (0.5 + 2^(bits-24)) / (2^bits - 1): half a step, plus
// float's rounding of x * s (which can also turn a near-tie into a tie: the code may differ by
// one from rounding the exact product, e.g. x = 0.54705882f, 8 bits: 140, exact 139.4999..).
// The min() keeps 24 bits from overflowing (1.0 * 16777215 + 0.5 rounds to 2^24).
inline uint quantizeUnorm(float x, uint bits) {
    float s = float((1u << bits) - 1u);
    float q = floor(clamp(x, 0.0f, 1.0f) * s + 0.5f);
    return min(uint(q), (1u << bits) - 1u);
}

// dequantizeUnorm: code in [0, 2^bits-1] -> [0,1]; exact inverse at every code.
inline float dequantizeUnorm(uint code, uint bits) {
    float s = float((1u << bits) - 1u);
    return float(code) / s;
}

// quantizeChroma: an offset chroma x in [0,1] (Cb + 0.5, Cr + 0.5; 0.5 = neutral) -> code in
// [0, 2^bits - 2]; bits 2..16. The codes are spread over 2^bits - 2 steps, so that the neutral
// chroma 0.5 has a code of its own, the midpoint 2^(bits-1) - 1 (127 at 8 bits), and decodes to
// exactly 0.5: grey (and every metal's diffuse colour, 0) reads back without a tint. The top code
// 2^bits - 1 is unused (it decodes to just above 1). The midpoint 127 is CryEngine's
// MIDPOINT_8_BIT = 127/255, but not its range: CryEngine V (CRYTEK/CRYENGINE @232227c5
// Engine/Shaders/HWScripts/CryFX/CommonMath.cfi:4,138-163) stores Cb * MIDPOINT_8_BIT +
// MIDPOINT_8_BIT, Cb in [-0.5, 0.5], i.e. 127 (1 + Cb) / 255: codes 63.5 .. 190.5, about half the
// chroma codes used here, and its DecodeColorYCC (value / MIDPOINT_8_BIT - 1) gives back Cb.
// CryEngine V is a later engine than Crysis 3, whose code is not public: the crysis3 and ryse
// rows follow the talk (Sousa et al., GDC 2013), which names no quantiser; spreading Cb + 0.5
// over 2^bits - 2 steps is gbufferlab's choice.
// quantizeUnorm's 0.5 falls between codes 127 and 128 and rounds to 128: +0.002 of chroma.
// Error: |dequantizeChroma(code) - x| <= (0.5 + 2^(bits-24)) / (2^bits - 2).
inline uint quantizeChroma(float x, uint bits) {
    float s = float((1u << bits) - 2u);
    float q = floor(clamp(x, 0.0f, 1.0f) * s + 0.5f);
    return uint(q);
}

// dequantizeChroma: code in [0, 2^bits - 2] -> [0,1]; the midpoint decodes to exactly 0.5.
inline float dequantizeChroma(uint code, uint bits) {
    float s = float((1u << bits) - 2u);
    return float(code) / s;
}

// quantizeSnorm: x in [-1,1] (clamped) -> two's complement code in the low `bits` bits,
// symmetric: -1 -> -(2^(bits-1)-1), +1 -> 2^(bits-1)-1; bits 2..24.
// Error: |dequantizeSnorm(code) - x| <= (0.5 + 2^(bits-24)) / (2^(bits-1) - 1).
inline uint quantizeSnorm(float x, uint bits) {
    float s = float((1u << (bits - 1u)) - 1u);
    float q = floor(clamp(x, -1.0f, 1.0f) * s + 0.5f);
    return uint(int(q)) & ((1u << bits) - 1u);
}

// dequantizeSnorm: low `bits` bits, two's complement -> [-1,1]; -2^(bits-1) decodes to -1.
inline float dequantizeSnorm(uint code, uint bits) {
    float s = float((1u << (bits - 1u)) - 1u);
    int c = int(code << (32u - bits)) >> (32u - bits);
    return max(float(c) / s, -1.0f);
}

// ---------------------------------------------------------------------------------------------
// 2. Small floats, integer bit operations on the IEEE 754 binary32 pattern, round to nearest
//    even. Source: IEEE 754-2008; Vulkan spec, "Unsigned 11-Bit / 10-Bit Floating-Point
//    Numbers" (B10G11R11_UFLOAT). Overflow clamps to the largest finite value (our choice;
//    no Inf is produced from finite input), Inf and NaN input also give the largest finite.
// ---------------------------------------------------------------------------------------------

// encodeSmallFloatMagnitude: a = bits of a float >= 0 (sign clear) -> 5-bit exponent (bias 15) |
// mantissaBits mantissa, subnormals included; mantissaBits 1..10.
inline uint encodeSmallFloatMagnitude(uint a, uint mantissaBits) {
    uint shift = 23u - mantissaBits;
    uint maxFinite = (30u << mantissaBits) | ((1u << mantissaBits) - 1u);
    uint overflow = 0x47000000u | (((2u << mantissaBits) - 1u) << (shift - 1u));
    if (a >= overflow) return maxFinite;
    if (a >= 0x38800000u) {
        uint odd = (a >> shift) & 1u;
        return (a - 0x38000000u + ((1u << (shift - 1u)) - 1u) + odd) >> shift;
    }
    uint e = a >> 23u;
    uint sub = 136u - mantissaBits - e;
    if (sub > 24u) return 0u;
    uint m = (a & 0x7fffffu) | 0x800000u;
    uint q = m >> sub;
    uint rem = m & ((1u << sub) - 1u);
    uint halfway = 1u << (sub - 1u);
    if (rem > halfway || (rem == halfway && (q & 1u) == 1u)) q += 1u;
    return q;
}

// decodeSmallFloatMagnitude: inverse of the above (exponent 31 gives Inf / NaN); exact.
inline float decodeSmallFloatMagnitude(uint code, uint mantissaBits) {
    uint e = code >> mantissaBits;
    uint mant = code & ((1u << mantissaBits) - 1u);
    if (e == 0u) return float(mant) * uintBitsToFloat((113u - mantissaBits) << 23u);
    if (e == 31u) return uintBitsToFloat(0x7f800000u | (mant << (23u - mantissaBits)));
    return uintBitsToFloat(((e + 112u) << 23u) | (mant << (23u - mantissaBits)));
}

// encodeFloat16: IEEE binary16 (16 bits), |x| <= 65504 exact-rounded, beyond clamps to +-65504.
// Error: relative <= 2^-11 for |x| >= 2^-14, absolute <= 2^-25 below. Bit-identical to a
// correctly rounded (RNE) conversion for all finite |x| < 65520.
inline uint encodeFloat16(float x) {
    uint a = floatBitsToUint(x);
    uint sign = (a >> 16u) & 0x8000u;
    return sign | encodeSmallFloatMagnitude(a & 0x7fffffffu, 10u);
}

// decodeFloat16: exact.
inline float decodeFloat16(uint code) {
    float m = decodeSmallFloatMagnitude(code & 0x7fffu, 10u);
    return (code & 0x8000u) != 0u ? -m : m;
}

// encodeFloat11: unsigned 11 bits (5e6m), [0, 65024]; negative (and -0) -> 0; above clamps.
// Error: relative <= 2^-7 for x >= 2^-14, absolute <= 2^-21 below.
inline uint encodeFloat11(float x) {
    uint a = floatBitsToUint(x);
    if (a >= 0x80000000u) return 0u;
    return encodeSmallFloatMagnitude(a, 6u);
}

// decodeFloat11: exact.
inline float decodeFloat11(uint code) { return decodeSmallFloatMagnitude(code & 0x7ffu, 6u); }

// encodeFloat10: unsigned 10 bits (5e5m), [0, 64512]; negative (and -0) -> 0; above clamps.
// Error: relative <= 2^-6 for x >= 2^-14, absolute <= 2^-20 below.
inline uint encodeFloat10(float x) {
    uint a = floatBitsToUint(x);
    if (a >= 0x80000000u) return 0u;
    return encodeSmallFloatMagnitude(a, 5u);
}

// decodeFloat10: exact.
inline float decodeFloat10(uint code) { return decodeSmallFloatMagnitude(code & 0x3ffu, 5u); }

// encodeFloat32 / decodeFloat32: the binary32 bits, lossless.
inline uint encodeFloat32(float x) { return floatBitsToUint(x); }
inline float decodeFloat32(uint code) { return uintBitsToFloat(code); }

// ---------------------------------------------------------------------------------------------
// 3. sRGB 8-bit (the tables and their source are in encodings.cpp).
// ---------------------------------------------------------------------------------------------

// encodeSrgb8: linear x (any float, clamps) -> 8-bit sRGB code = number of thresholds <= x.
// Exact: equals floor(255 * srgb(x) + 0.5) evaluated in exact arithmetic, for every float x.
// Cost: 8 steps of binary search, no pow.
inline uint encodeSrgb8(float x) {
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (kSrgbEncodeThresholds[mid] <= x) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

// Error of the round trip over linear [0,1]: max abs 0.0045, CIEDE2000 mean 0.14, max 0.82.
// decodeSrgb8: exact sRGB -> linear, correctly rounded to float.
inline float decodeSrgb8(uint code) { return kSrgbDecode[code & 255u]; }

// ---------------------------------------------------------------------------------------------
// 4. Unit normals. All take and return unit vectors (decoders normalise).
// ---------------------------------------------------------------------------------------------

// encodeNormalXyz: 3 x unorm(n*0.5+0.5), bits 2..16 per component.
// Error (angle, mean / max): 8 bits 0.17 / 0.39 deg, 10 bits 0.042 / 0.096, 16 bits 0.00066 / 0.0015.
inline uvec3 encodeNormalXyz(vec3 n, uint bits) {
    vec3 h = n * 0.5f + 0.5f;
    return uvec3(quantizeUnorm(h.x, bits), quantizeUnorm(h.y, bits), quantizeUnorm(h.z, bits));
}

inline vec3 decodeNormalXyz(uvec3 code, uint bits) {
    vec3 v = vec3(dequantizeUnorm(code.x, bits), dequantizeUnorm(code.y, bits), dequantizeUnorm(code.z, bits));
    return normalize(v * 2.0f - 1.0f);
}

// encodeNormalBestFit: CryEngine 3 best-fit normals by table look-up (Kaplanyan 2010); the
// statement-for-statement mirror of shaders/encodings.glsl, which explains it. `table` is
// bestFitNormalTable().data() (best_fit_normals.h), the words the GPU reads.
inline uvec3 encodeNormalBestFit(vec3 n, const uint32_t* table) {
    float m = max(abs(n.x), max(abs(n.y), abs(n.z)));
    if (!(m > 0.0f) || std::isinf(m) || std::isnan(n.x) || std::isnan(n.y) || std::isnan(n.z))
        return uvec3(128u, 128u, 255u);
    vec3 q = vec3(n.x / m, n.y / m, n.z / m);
    vec3 a = abs(q);
    float lo = min(a.x, min(a.y, a.z));
    float mid = max(min(a.x, a.y), min(max(a.x, a.y), a.z));
    uint i = min(uint(mid * float(kBestFitTableSize)), kBestFitTableSize - 1u);
    uint j = min(uint(lo * float(kBestFitTableSize)), kBestFitTableSize - 1u);
    uint t = i * (i + 1u) / 2u + j;
    uint entry = (table[t >> 2u] >> ((t & 3u) * 8u)) & 0xffu;
    float k = float(255u - 2u * entry);
    float dx = 2.0f * floor(q.x * k * 0.5f) + 1.0f;
    float dy = 2.0f * floor(q.y * k * 0.5f) + 1.0f;
    float dz = 2.0f * floor(q.z * k * 0.5f) + 1.0f;
    return uvec3(uint(dx + 255.0f) >> 1u, uint(dy + 255.0f) >> 1u, uint(dz + 255.0f) >> 1u);
}
inline uvec3 encodeNormalBestFit(vec3 n) { return encodeNormalBestFit(n, bestFitNormalTable().data()); }

// decodeNormalBestFit.
inline vec3 decodeNormalBestFit(uvec3 code) {
    return normalize(vec3(code) / 255.0f * 2.0f - 1.0f);
}

// encodeNormalXyZSign: unorm x, y (bits 2..16 each) + z-sign bit (code.z: 1 when n.z < 0).
// Source: Sousa et al., "The Rendering Technologies of Crysis 3", GDC 2013 (N.xy + Zsign).
// Error: poor near the equator (z ~ 0, where z = sqrt(1 - x^2 - y^2) is ill-conditioned):
// mean / max 8 bits 0.47 / 5.8 deg, 10 bits 0.14 / 2.9, 16 bits 0.0030 / 0.35.
inline uvec3 encodeNormalXyZSign(vec3 n, uint bits) {
    vec2 h = vec2(n.x * 0.5f + 0.5f, n.y * 0.5f + 0.5f);
    return uvec3(quantizeUnorm(h.x, bits), quantizeUnorm(h.y, bits), n.z < 0.0f ? 1u : 0u);
}

inline vec3 decodeNormalXyZSign(uvec3 code, uint bits) {
    float x = dequantizeUnorm(code.x, bits) * 2.0f - 1.0f;
    float y = dequantizeUnorm(code.y, bits) * 2.0f - 1.0f;
    float z = sqrt(max(0.0f, 1.0f - x * x - y * y));
    return normalize(vec3(x, y, code.z != 0u ? -z : z));
}

// (encodeNormalSpheremap, encodeNormalStereographic and their decoders: encodings.cpp.)

// Octahedral helpers. Source: Cigolle, Donow, Evangelakos, Mara, McGuire, Meyer, "A Survey of
// Efficient Representations for Independent Unit Vectors", JCGT 3(2), 2014, listings 1-2.
inline vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f); }

// octEncode: unit n -> [-1,1]^2 (lower hemisphere folded over the diagonals).
inline vec2 octEncode(vec3 n) {
    float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    vec2 p = l1 > 0.0f ? vec2(n.x / l1, n.y / l1) : vec2(0.0f);  // a zero vector: normal_encodings.glsl
    vec2 folded = vec2(1.0f - abs(p.y), 1.0f - abs(p.x)) * signNotZero(p);
    return n.z <= 0.0f ? folded : p;
}

// octDecode: [-1,1]^2 -> direction (not normalised).
inline vec3 octDecode(vec2 e) {
    vec3 v = vec3(e.x, e.y, 1.0f - abs(e.x) - abs(e.y));
    vec2 folded = vec2(1.0f - abs(v.y), 1.0f - abs(v.x)) * signNotZero(vec2(v.x, v.y));
    return v.z < 0.0f ? vec3(folded, v.z) : v;
}

// encodeNormalOctahedral: octahedral, 2 x snorm bits (bits 2..16; Cigolle's "oct" 2*bits).
// Error (angle, mean / max): 8 bits 0.34 / 0.95 deg, 10 bits 0.084 / 0.24, 12 bits 0.021 / 0.059,
// 16 bits 0.0013 / 0.0037. Edge codes (x or y = +-max) pair up: (1, t) and (1, -t) are one direction.
inline uvec2 encodeNormalOctahedral(vec3 n, uint bits) {
    vec2 p = octEncode(n);
    return uvec2(quantizeSnorm(p.x, bits), quantizeSnorm(p.y, bits));
}

inline vec3 decodeNormalOctahedral(uvec2 code, uint bits) {
    return normalize(octDecode(vec2(dequantizeSnorm(code.x, bits), dequantizeSnorm(code.y, bits))));
}

// ---------------------------------------------------------------------------------------------
// 5. Colour transforms (float -> float; quantise Y with quantizeUnorm, the chroma of the YCbCr
//    family with quantizeChroma, YCoCg's with quantizeUnorm as the paper does).
// ---------------------------------------------------------------------------------------------

// rgbToYCbCr: ITU-R BT.601 full range (JPEG/JFIF), rgb in [0,1]^3 -> (Y, Cb+0.5, Cr+0.5) in
// [0,1]^3. Cb = (B - Y) / 1.772, Cr = (R - Y) / 1.402. Used by Crysis 3 for albedo and specular
// (Sousa et al., "The Rendering Technologies of Crysis 3", GDC 2013).
// Error: the pair is exact up to float rounding (max 2.6e-7); 8 bits per code: max abs 0.0054,
// CIEDE2000 mean 0.17, max 6.3 (darks; ycbcr_sqrt: max 1.3).
inline vec3 rgbToYCbCr(vec3 c) {
    float y = 0.299f * c.r + 0.587f * c.g + 0.114f * c.b;
    float cb = (c.b - y) * 0.5643341f + 0.5f;
    float cr = (c.r - y) * 0.7132668f + 0.5f;
    return vec3(y, cb, cr);
}

inline vec3 yCbCrToRgb(vec3 c) {
    float r = c.x + (c.z - 0.5f) * 1.402f;
    float b = c.x + (c.y - 0.5f) * 1.772f;
    float g = (c.x - 0.299f * r - 0.114f * b) / 0.587f;
    return vec3(r, g, b);
}

// lumaBt601: the Y of rgbToYCbCr (Crysis 3 stores only the specular colour's luminance).
inline float lumaBt601(vec3 c) {
    float y = 0.299f * c.r + 0.587f * c.g + 0.114f * c.b;
    return y;
}

// rgbToYCbCrSqrt: YCbCr of sqrt(rgb) (a gamma-2 pre-transform that spends codes on darks);
// yCbCrSqrtToRgb squares after the inverse matrix. Source: Sousa et al., Crysis 3, GDC 2013;
// Schulz, "Moving to the Next Generation - The Rendering Technology of Ryse", GDC 2014.
// Error, 8 bits per code: max abs 0.011 (brights), but darks (< 0.05) 0.0024 vs YCbCr's 0.0054;
// CIEDE2000 mean 0.20, max 1.3.
inline vec3 rgbToYCbCrSqrt(vec3 c) {
    vec3 s = vec3(sqrt(max(c.r, 0.0f)), sqrt(max(c.g, 0.0f)), sqrt(max(c.b, 0.0f)));
    return rgbToYCbCr(s);
}

inline vec3 yCbCrSqrtToRgb(vec3 c) {
    vec3 s = max(yCbCrToRgb(c), vec3(0.0f));
    return s * s;
}

// rgbToYCoCg: YCoCg with Co, Cg offset by 0.5, all in [0,1] for rgb in [0,1]^3.
// Source: Malvar & Sullivan, JVT-I014 (2003); Mavridis & Papaioannou, "The Compact YCoCg Frame
// Buffer", JCGT 1(1), 2012. Exact inverse in real arithmetic (float: max 1.5e-7); 8 bits per
// code: max abs 0.0058, CIEDE2000 mean 0.17, max 5.3.
inline vec3 rgbToYCoCg(vec3 c) {
    float y = 0.25f * c.r + 0.5f * c.g + 0.25f * c.b;
    float co = 0.5f * c.r - 0.5f * c.b + 0.5f;
    float cg = -0.25f * c.r + 0.5f * c.g - 0.25f * c.b + 0.5f;
    return vec3(y, co, cg);
}

inline vec3 yCoCgToRgb(vec3 c) {
    float co = c.y - 0.5f;
    float cg = c.z - 0.5f;
    float t = c.x - cg;
    return vec3(t + co, c.x + cg, t - co);
}

// ---------------------------------------------------------------------------------------------
// 6. Chroma checkerboard. Source: Mavridis & Papaioannou, "The Compact YCoCg Frame Buffer",
// JCGT 1(1), 2012, section 3 and listing 1. Each pixel stores Y and one chroma: the first
// (Cb / Co) where (x+y) is even, the second (Cr / Cg) where it is odd.
// ---------------------------------------------------------------------------------------------

inline bool chromaIsSecond(ivec2 pixel) { return ((pixel.x + pixel.y) & 1) != 0; }

// chromaForPixel: the chroma this pixel stores, from (first, second) = (Cb, Cr) or (Co, Cg).
inline float chromaForPixel(ivec2 pixel, vec2 chroma) { return chromaIsSecond(pixel) ? chroma.y : chroma.x; }

// reconstructChroma: the paper's edge-directed filter. The 4 direct neighbours (order: +x, -x,
// +y, -y) hold the other chroma; each gets weight 1 - step(29.5/255, |Yn - Yc|) (1 when its luma
// is fewer than 30 codes away: kChromaEdgeThreshold), times `covered` (1 where the neighbour has geometry, 0 where it holds
// only the clear value: a silhouette never takes its chroma from the background). Their weighted
// mean is the missing chroma; when all 4 weights are 0 the first covered neighbour in that order
// is used alone (the paper's listing takes +x alone), and when no neighbour is covered the
// chroma is neutral (0.5). Returns (centre's own chroma, reconstructed other chroma). At image
// borders fetch the missing neighbour mirrored (x = -1 reads x = 1): a replicated (clamped)
// fetch would read the centre's own chroma kind.
// CryEngine 3 reconstructs the same way, edge-directed on luminance (Sousa et al., "The
// Rendering Technologies of Crysis 3", GDC 2013, after Mavridis & Papaioannou 2012); the sky and
// other pixels without G-buffer data are excluded as here.
inline vec2 reconstructChroma(float lumaCentre, float chromaCentre, vec4 lumaNeighbours, vec4 chromaNeighbours,
                       vec4 covered) {
    vec4 w = covered * (vec4(1.0f) - step(vec4(kChromaEdgeThreshold), abs(lumaNeighbours - vec4(lumaCentre))));
    float total = w.x + w.y + w.z + w.w;
    if (total == 0.0f) {
        float nx = 1.0f - covered.x, ny = 1.0f - covered.y, nz = 1.0f - covered.z;
        w = covered * vec4(1.0f, nx, nx * ny, nx * ny * nz);
        total = w.x + w.y + w.z + w.w;
        if (total == 0.0f) return vec2(chromaCentre, 0.5f);
    }
    float other = (w.x * chromaNeighbours.x + w.y * chromaNeighbours.y + w.z * chromaNeighbours.z +
                   w.w * chromaNeighbours.w) / total;
    return vec2(chromaCentre, other);
}

// Every neighbour covered (the paper's filter as published).
inline vec2 reconstructChroma(float lumaCentre, float chromaCentre, vec4 lumaNeighbours, vec4 chromaNeighbours) {
    return reconstructChroma(lumaCentre, chromaCentre, lumaNeighbours, chromaNeighbours, vec4(1.0f));
}

// reconstructChroma with the pixel: returns (first, second) = (Cb, Cr) or (Co, Cg).
// Error, 8 bits per code, on a synthetic image of 16x16 random flat blocks (3:1 with a ramp):
// CIEDE2000 mean 0.6, p99 9, max 42 (block corners, where no neighbour shares the centre's hue).
inline vec2 reconstructChroma(ivec2 pixel, float lumaCentre, float chromaCentre, vec4 lumaNeighbours,
                       vec4 chromaNeighbours, vec4 covered) {
    vec2 c = reconstructChroma(lumaCentre, chromaCentre, lumaNeighbours, chromaNeighbours, covered);
    return chromaIsSecond(pixel) ? vec2(c.y, c.x) : c;
}
inline vec2 reconstructChroma(ivec2 pixel, float lumaCentre, float chromaCentre, vec4 lumaNeighbours,
                              vec4 chromaNeighbours) {
    return reconstructChroma(pixel, lumaCentre, chromaCentre, lumaNeighbours, chromaNeighbours, vec4(1.0f));
}

// ---------------------------------------------------------------------------------------------
// 7. Roughness maps (scalar transforms, quantise with quantizeUnorm).
// ---------------------------------------------------------------------------------------------

// glossFromRoughness / roughnessFromGloss: gloss = 1 - roughness (CryEngine glossiness).
inline float glossFromRoughness(float r) {
    float g = 1.0f - r;
    return g;
}
inline float roughnessFromGloss(float g) { return 1.0f - g; }

// reflectanceFromSpecular: Filament / Bevy reflectance r = sqrt(s / 2) (F0 = 0.16 r^2 = 0.08 s).
inline float reflectanceFromSpecular(float s) {
    float h = clamp(s, 0.0f, 1.0f) * 0.5f;
    return sqrt(h);
}
inline float specularFromReflectance(float r) { return 2.0f * r * r; }
// specularFromReflectanceBevyWebgl2: Bevy's WebGL2 read of its 4-bit reflectance, biased down by
// half a 4-bit step, saturate(r - 0.03333333333) ("Bias to 0.5 since that's the value for almost
// all materials": code 8 reads 0.5, not 8/15; bevyengine/bevy v0.16.0 pbr_deferred_functions.wgsl:
// 104-106). The write is plain `reflectance` (:36-40), so every code reads half a step low.
inline float specularFromReflectanceBevyWebgl2(float r) {
    return specularFromReflectance(clamp(r - 0.03333333333f, 0.0f, 1.0f));
}

// smoothnessFromRoughnessCry: s = 1 - sqrt(r); roughnessFromSmoothnessCry: r = (1 - s)^2.
// Source: Schulz, "Moving to the Next Generation - The Rendering Technology of Ryse", GDC 2014.
// With 8-bit unorm s: max roughness error 0.0039 (near r = 1), 0.5/255^2 near r = 0.
inline float smoothnessFromRoughnessCry(float r) {
    float s = 1.0f - sqrt(max(r, 0.0f));
    return s;
}
inline float roughnessFromSmoothnessCry(float s) { return (1.0f - s) * (1.0f - s); }

// cry_gloss_power: CryENGINE 3's gloss, read as the engine used it (Crysis 2's slim G-buffer,
// RT1.a). The engine turns the 8-bit gloss g into a normalised Blinn-Phong power
//     n = exp2(10 g + 1)                 (2 .. 2048)
// -- the mapping used in CryENGINE 3-era deferred-lighting shaders; the seed (DIGEST.md) gives no
// gloss-to-power formula and Sousa et al. 2011 name gloss without one, so this is an assumption
// stated here and in layouts/crysis2-slim*.toml. gbufferlab's BRDF is GGX with alpha =
// roughness^2 (UE4), so the power is converted with the Phong / Beckmann equivalence of Walter
// et al. 2007 ("Microfacet Models for Refraction through Rough Surfaces", EGSR: n = 2/alpha^2 - 2),
// taking Beckmann's alpha as GGX's (the usual approximation; the lobes differ in their tails):
//     alpha = sqrt(2 / (n + 2)),  roughness = sqrt(alpha),
// and encoding inverts it: g = (log2(2 / roughness^4 - 2) - 1) / 10, rounded to 8 bits.
// Range: code 255 (g = 1, n = 2048) decodes to roughness 0.17673357, code 0 (g = 0, n = 2) to
// 0.84089643; roughness outside [0.1767, 0.8409] clamps to those ends (the engine's range: a
// mirror or a fully rough surface cannot be stored). Inside it the round trip's error is at most
// 0.0018 in roughness (half a gloss step; measured over 200001 roughnesses). Table based and
// exact, like sRGB: kCryGlossRoughness[k] = float(roughness(k / 255)); kCryGlossEncodeThresholds[i]
// = the largest float <= the roughness whose gloss is (i + 0.5) / 255 (both in double; they
// decrease with i). The code = the number of thresholds >= roughness = round(255 g) with ties up,
// exactly, for every float. Tables in encodings.cpp; tests/encoding/color_encodings_test.cpp
// (CryGlossPower.TablesMatchTheMapping) recomputes every entry. 8 bits only.
extern const float kCryGlossRoughness[256];
extern const float kCryGlossEncodeThresholds[255];
inline uint encodeCryGlossPower(float r) {
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (kCryGlossEncodeThresholds[mid] >= r) lo = mid + 1u; else hi = mid;
    }
    return lo;
}
inline float decodeCryGlossPower(uint code) { return kCryGlossRoughness[code & 255u]; }

// ---------------------------------------------------------------------------------------------
// 8. UE4 specular colour and depth.
// ---------------------------------------------------------------------------------------------

// specularColorUE4: F0 = mix(0.08 * specular, baseColor, metallic), written out as
// a * (1 - t) + b * t. Source: Epic Games, UE4 DeferredShadingCommon.ush, ComputeF0
// (Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013).
inline vec3 specularColorUE4(vec3 baseColor, float metallic, float specular) {
    vec3 f0 = vec3(0.08f * specular) * (1.0f - metallic) + baseColor * metallic;
    return f0;
}

// quantizeDepth24: depth in [0,1] (clamped) -> 24-bit unorm code (D24), in float only.
// quantizeUnorm(d, 24) would be off by one for ~25% of depths (half of those in [0.5,1)):
// float32 holds 24 significant bits, so d * (2^24-1) + 0.5 rounds. Instead split exactly:
// h = d * 2^24 (exact), hi = floor(h) (exact), r = (h - hi) - d in (-1,1) (error <= 2^-25), and
// code = hi + floor(r + 0.5) = round(d * (2^24-1)), ties up. Error: |dequantizeDepth24(code) - d|
// <= 0.5 / (2^24-1) = 3.0e-8; the code equals exact rounding for every float in [2^-8, 1]
// (tested exhaustively) and every code survives decode + encode.
inline uint quantizeDepth24(float d) {
    float c = clamp(d, 0.0f, 1.0f);
    float h = c * 16777216.0f;
    float hi = floor(h);
    float r = (h - hi) - c;
    float up = floor(r + 0.5f);
    return uint(int(hi) + int(up));
}
inline float dequantizeDepth24(uint code) { return dequantizeUnorm(code & 0xffffffu, 24u); }

}  // namespace gbl::enc

// 8. Packings of shipped engines: engine_encodings.h (twin of shaders/engine_encodings.glsl).
#include "engine_encodings.h"
