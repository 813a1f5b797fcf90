#pragma once
// Packings of shipped engines (Bevy, Unity; niagara's are in niagara_encodings.h): the C++
// twin of shaders/engine_encodings.glsl, split from encodings.h, which includes it at its end so
// that every includer of encodings.h still sees them. Same contract as encodings.h: the same names,
// expressions and order as the GLSL; encoders agree with the GPU to the bit.
#include "encodings.h"

namespace gbl::enc {

// ---------------------------------------------------------------------------------------------
// 8. Packings of shipped engines (the GLSL twin carries the sources and error bounds).
// ---------------------------------------------------------------------------------------------

// encodeRgb9e5: RGB >= 0 -> (9-bit mantissas r, g, b; 5-bit shared exponent), Vulkan's
// E5B9G9R9_UFLOAT_PACK32 ("Shared Exponent", N = 9, B = 15), as Bevy stores emissive.
inline uvec4 encodeRgb9e5(vec3 c) {
    vec3 rgb = clamp(c, vec3(0.0f), vec3(65408.0f));
    float m = max(rgb.x, max(rgb.y, rgb.z));
    int e = max(-16, int((floatBitsToUint(m) >> 23u) & 0xffu) - 127) + 16;
    float scale = uintBitsToFloat(uint(151 - e) << 23u);  // 2^(B + N - exp)
    float top = floor(m * scale + 0.5f);
    if (top >= 512.0f) {
        e += 1;
        scale *= 0.5f;
    }
    vec3 q = floor(rgb * scale + 0.5f);
    return uvec4(uint(q.x), uint(q.y), uint(q.z), uint(e));
}

// decodeRgb9e5: mantissa * 2^(exp - B - N); exact.
inline vec3 decodeRgb9e5(uvec4 code) {
    float scale = uintBitsToFloat(uint(int(code.w & 31u) + 103) << 23u);
    return vec3(float(code.x & 511u), float(code.y & 511u), float(code.z & 511u)) * scale;
}

// Gamma 2.2 (not sRGB), 8 bits, table based (tables in encodings.cpp): Bevy's base colour.
inline uint encodeGamma22(float x) {
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (kGamma22EncodeThresholds[mid] <= x) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

inline float decodeGamma22(uint code) { return kGamma22Decode[code & 255u]; }

// sRGB 8-bit as HDRP writes fresnel0 into its UNORM GBuffer2: the power segment without the linear
// toe, decoded with HDRP's cubic (the GLSL twin carries the sources). Table based like srgb8: the
// code = number of thresholds <= |x| (tables in encodings.cpp).
extern const float kSrgbFastHdrpEncodeThresholds[255];
inline uint encodeSrgb8FastHdrp(float x) {
    float a = abs(x);
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (kSrgbFastHdrpEncodeThresholds[mid] <= a) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

inline float decodeSrgb8FastHdrp(uint code) {
    float c = dequantizeUnorm(code & 255u, 8u);
    float l = c * (c * (c * 0.305306011f + 0.682171111f) + 0.012522878f);
    return l;
}

// HDRP's GBuffer3 (R11G11B10F) with its AO tag: emissive as float11, float11, float10, except
// where emissive is exactly (0, 0, 0): then the codes of (2048, ambient occlusion, 1024). The
// decoders read the tag back: emissive 0 and occlusion from g, else the floats and occlusion 1.
// Sources and the word it makes: shaders/engine_encodings.glsl.
inline constexpr uint kHdrpAoTagR = 0x680u;  // encodeFloat11(2048.0f)
inline constexpr uint kHdrpAoTagB = 0x320u;  // encodeFloat10(1024.0f)

inline uvec3 encodeFloat111110HdrpAoTag(vec3 e, float ao) {
    if (e.x == 0.0f && e.y == 0.0f && e.z == 0.0f) return uvec3(kHdrpAoTagR, encodeFloat11(ao), kHdrpAoTagB);
    return uvec3(encodeFloat11(e.x), encodeFloat11(e.y), encodeFloat10(e.z));
}

inline bool isHdrpAoTag(uvec3 code) { return (code.x & 2047u) == kHdrpAoTagR && (code.z & 1023u) == kHdrpAoTagB; }

inline vec3 decodeFloat111110HdrpAoTag(uvec3 code) {
    if (isHdrpAoTag(code)) return vec3(0.0f);
    return vec3(decodeFloat11(code.x), decodeFloat11(code.y), decodeFloat10(code.z));
}

inline float decodeHdrpAoTagOcclusion(uvec3 code) { return isHdrpAoTag(code) ? decodeFloat11(code.y) : 1.0f; }

// Octahedral normals as two unorm codes of u = p * 0.5 + 0.5, each engine's arithmetic written out
// (float only, in its order), decoded by decodeNormalOctahedralUnorm. Sources and error bounds:
// shaders/engine_encodings.glsl.

// octEncodeBevy: Bevy's octahedral_encode, without its final * 0.5 + 0.5.
inline vec2 octEncodeBevy(vec3 n) {
    float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    float x = n.x / l1;
    float y = n.y / l1;
    float z = n.z / l1;
    float sx = x > 0.0f ? 1.0f : -1.0f;
    float sy = y > 0.0f ? 1.0f : -1.0f;
    vec2 wrap = vec2((1.0f - abs(y)) * sx, (1.0f - abs(x)) * sy);
    return z >= 0.0f ? vec2(x, y) : wrap;
}

// encodeNormalOctahedralBevy: octEncodeBevy, then u32(saturate(u) * (2^bits - 1) + 0.5).
inline uvec2 encodeNormalOctahedralBevy(vec3 n, uint bits) {
    vec2 p = octEncodeBevy(n);
    float ux = p.x * 0.5f + 0.5f;
    float uy = p.y * 0.5f + 0.5f;
    return uvec2(quantizeUnorm(ux, bits), quantizeUnorm(uy, bits));
}

// octEncodeUnity: Unity's PackNormalOctQuadEncode.
inline vec2 octEncodeUnity(vec3 n) {
    float r = 1.0f / (abs(n.x) + abs(n.y) + abs(n.z));
    float x = n.x * r;
    float y = n.y * r;
    float z = n.z * r;
    float t = clamp(-z, 0.0f, 1.0f);
    return vec2(x + (x >= 0.0f ? t : -t), y + (y >= 0.0f ? t : -t));
}

// encodeNormalOctahedralUnity: octEncodeUnity, saturate(p * 0.5 + 0.5), truncated with the scale
// 2^bits - 0.5 (PackFloat2To888's 4095.5 at 12 bits).
inline uvec2 encodeNormalOctahedralUnity(vec3 n, uint bits) {
    vec2 p = octEncodeUnity(n);
    float s = float((1u << bits) - 1u) + 0.5f;
    float ux = clamp(p.x * 0.5f + 0.5f, 0.0f, 1.0f);
    float uy = clamp(p.y * 0.5f + 0.5f, 0.0f, 1.0f);
    float qx = floor(ux * s);
    float qy = floor(uy * s);
    return min(uvec2(uint(qx), uint(qy)), uvec2((1u << bits) - 1u));
}

// encodeNormalOctahedralHdrp: HDRP's normal buffer, |n.z| raised to at least 1/1024 (its sign
// kept, -0 counting as +) before encodeNormalOctahedralUnity; n is not renormalised.
inline uvec2 encodeNormalOctahedralHdrp(vec3 n, uint bits) {
    float az = max(1.0f / 1024.0f, abs(n.z));
    float z = n.z >= 0.0f ? az : -az;
    return encodeNormalOctahedralUnity(vec3(n.x, n.y, z), bits);
}

// decodeNormalOctahedralUnorm: code / (2^bits - 1) * 2 - 1, octahedral unfold, normalise.
inline vec3 decodeNormalOctahedralUnorm(uvec2 code, uint bits) {
    vec2 u = vec2(dequantizeUnorm(code.x, bits), dequantizeUnorm(code.y, bits));
    return normalize(octDecode(u * 2.0f - 1.0f));
}

// kz2_log_power: Killzone 2's specular power, stored as log2(power) / 10.5 in 8 bits (RT2.b):
// n = 2^(10.5 g), 1 .. 1448, converted to roughness as cry_gloss_power does, (2 / (n + 2))^(1/4).
// Table based (tables in encodings.cpp): the code = the number of thresholds >= roughness
// (decreasing with the code, as in encodeCryGlossPower). The GLSL twin carries the sources.
extern const float kKz2PowerRoughness[256];
extern const float kKz2PowerEncodeThresholds[255];
inline uint encodeKz2LogPower(float r) {
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (kKz2PowerEncodeThresholds[mid] >= r) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

inline float decodeKz2LogPower(uint code) { return kKz2PowerRoughness[code & 255u]; }

// View-space x, y as half floats, z = +sqrt(1 - x^2 - y^2) (Killzone 2's RT1).
inline uvec2 encodeNormalXyFloat16(vec3 n) { return uvec2(encodeFloat16(n.x), encodeFloat16(n.y)); }

inline vec3 decodeNormalXyFloat16(uvec2 code) {
    float x = decodeFloat16(code.x);
    float y = decodeFloat16(code.y);
    float z = sqrt(max(0.0f, 1.0f - x * x - y * y));
    return normalize(vec3(x, y, z));
}

// ---------------------------------------------------------------------------------------------
// Material layers as the engines store them (issue 40; the GLSL twin carries the sources).
// ---------------------------------------------------------------------------------------------

// roundEvenF: to the nearest integer, ties to even (GLSL roundEven, WGSL round); std::nearbyint
// in the default rounding mode, which no code here changes.
inline float roundEvenF(float x) { return std::nearbyint(x); }

// unorm_round_even: saturate(x) * (2^bits - 1) rounded with ties to even (Bevy's clear-coat
// strength); decoded as unorm.
inline uint quantizeUnormRoundEven(float x, uint bits) {
    float s = float((1u << bits) - 1u);
    float q = roundEvenF(clamp(x, 0.0f, 1.0f) * s);
    return min(uint(q), (1u << bits) - 1u);
}

// coat_roughness_bevy: clamp(r, 0, 0.5) * 2 (2^bits - 1), ties to even; decoded code / (2 (2^bits - 1)).
inline uint encodeCoatRoughnessBevy(float r, uint bits) {
    float s = float(((1u << bits) - 1u) * 2u);
    float q = roundEvenF(clamp(r, 0.0f, 0.5f) * s);
    return min(uint(q), (1u << bits) - 1u);
}

inline float decodeCoatRoughnessBevy(uint code, uint bits) { return float(code) / float(((1u << bits) - 1u) * 2u); }

// unorm_signed: x * 0.5 + 0.5 as unorm (x in [-1, 1]); decoded code / (2^bits - 1) * 2 - 1.
inline uint quantizeUnormSigned(float x, uint bits) { return quantizeUnorm(x * 0.5f + 0.5f, bits); }

inline float dequantizeUnormSigned(uint code, uint bits) { return dequantizeUnorm(code, bits) * 2.0f - 1.0f; }

// unorm_sqrt (8 bits): code = round(255 sqrt(saturate(x))) by thresholds, decoded (code / 255)^2:
// UE's EncodeSubsurfaceColor / ExtractSubsurfaceColor (the Cloth model's fuzz colour).
extern const float kUnormSqrtEncodeThresholds[255];
inline uint encodeUnormSqrt(float x) {
    uint lo = 0u;
    uint hi = 255u;
    for (int i = 0; i < 8; ++i) {
        uint mid = (lo + hi) >> 1u;
        if (kUnormSqrtEncodeThresholds[mid] <= x) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

inline float decodeUnormSqrt(uint code) {
    float d = dequantizeUnorm(code & 255u, 8u);
    return d * d;
}

// UE's clear-coat bottom normal (CLEAR_COAT_BOTTOM_NORMAL): the octahedral point of the bottom
// normal minus that of the pixel's (top) normal, * 0.25 + 128/255, as two unorm codes; decoded
// code / (2^bits - 1) * 4 - 512/255 + oct(top), unfolded and normalised. UE's octahedron
// (UnitVectorToOctahedron: the fold where z <= 0, select(n >= 0, 1, -1)). A zero vector (a
// coat_normal no pixel of the ClearCoat model holds, read on the pixels of other models whose
// codes are dropped) is the point (0, 0) before the fold, as octEncode's: UE divides 0 by 0 there.
inline vec2 octEncodeUe(vec3 n) {
    float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    float x = l1 > 0.0f ? n.x / l1 : 0.0f;
    float y = l1 > 0.0f ? n.y / l1 : 0.0f;
    if (n.z <= 0.0f) {
        float fx = (1.0f - abs(y)) * (x >= 0.0f ? 1.0f : -1.0f);
        float fy = (1.0f - abs(x)) * (y >= 0.0f ? 1.0f : -1.0f);
        return vec2(fx, fy);
    }
    return vec2(x, y);
}

// OctahedronToUnitVector: z = 1 - |x| - |y|; where z < 0, xy -= sign-select(t) with t = -z.
inline vec3 octDecodeUe(vec2 o) {
    vec3 n = vec3(o.x, o.y, 1.0f - abs(o.x) - abs(o.y));
    float t = max(-n.z, 0.0f);
    n.x += n.x >= 0.0f ? -t : t;
    n.y += n.y >= 0.0f ? -t : t;
    return normalize(n);
}

inline uvec2 encodeNormalOctahedralDeltaUe(vec3 bottom, vec3 top, uint bits) {
    vec2 o1 = octEncodeUe(bottom);
    vec2 o2 = octEncodeUe(top);
    float dx = (o1.x - o2.x) * 0.25f + 128.0f / 255.0f;
    float dy = (o1.y - o2.y) * 0.25f + 128.0f / 255.0f;
    return uvec2(quantizeUnorm(dx, bits), quantizeUnorm(dy, bits));
}

inline vec3 decodeNormalOctahedralDeltaUe(uvec2 code, vec3 top, uint bits) {
    vec2 o2 = octEncodeUe(top);
    float ox = (dequantizeUnorm(code.x, bits) * 4.0f - 512.0f / 255.0f) + o2.x;
    float oy = (dequantizeUnorm(code.y, bits) * 4.0f - 512.0f / 255.0f) + o2.y;
    return octDecodeUe(vec2(ox, oy));
}

// anisotropy_angle_hdrp: HDRP Lit's anisotropic feature in GBuffer2.rgb, codes (angle
// GBuffer2.g, signed anisotropy GBuffer2.r, storeSin GBuffer2.b bit 5); the decode hands back the
// strength |a| and the axis the lobe stretches along (the bitangent where a < 0). The GLSL twin
// carries the sources (Lit.hlsl:575-634, 880-905 @c667268a; CommonLighting.hlsl:442-459).
inline void hdrpLocalFrame(vec3 n, vec3& fx, vec3& fy) {
    float sz = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = 1.0f / (sz + n.z);
    float ya = n.y * a;
    float b = n.x * ya;
    float c = n.x * sz;
    fx = vec3(c * n.x * a - 1.0f, sz * b, c);
    fy = vec3(b, n.y * ya - sz, n.y);
}

// Evaluated in float step by step; the GLSL twin writes the same values as literals
// (the GPU = CPU bit tests, tests/codec/gpu_cpu_bits_test.cpp, would see them part).
inline constexpr float kHdrpAngleScale = 1.41421354f * 256.0f / 255.0f;
inline constexpr float kHdrpAngleStart = 0.5f / 255.0f;
inline constexpr float kHdrpAngleBias = 0.5f / 256.0f * 0.707106769f;
inline constexpr float kHdrpAngleStep = 255.0f / 256.0f * 0.707106769f;

// t must lie across n, as HDRP makes it (LitData.hlsl:293 Orthonormalize(tangentWS, normalWS)) and
// as gbufferlab's surfaces hold it (material_eval.glsl: Gram-Schmidt against the shading normal):
// the stored min(|sin|, |cos|) is decoded as a unit vector's.
inline uvec3 encodeAnisotropyHdrp(vec3 t, float anisotropy, vec3 n) {
    vec3 fx, fy;
    hdrpLocalFrame(n, fx, fy);
    float sinFrame = t.x * fy.x + t.y * fy.y + t.z * fy.z;
    float cosFrame = t.x * fx.x + t.y * fx.y + t.z * fx.z;
    float product = sinFrame * cosFrame;
    bool quad2or4 = product < 0.0f;
    float u = roundEvenF(clamp(anisotropy, -1.0f, 1.0f) * 127.5f + 127.5f);
    uint strength = quad2or4 ? 255u - uint(u) : uint(u);
    bool storeSin = (abs(sinFrame) < abs(cosFrame)) != quad2or4;
    float sinOrCos = min(abs(sinFrame), abs(cosFrame));
    float remapped = clamp(sinOrCos * kHdrpAngleScale - kHdrpAngleStart, 0.0f, 1.0f);
    return uvec3(quantizeUnorm(remapped, 8u), strength, storeSin ? 1u : 0u);
}

inline float decodeAnisotropyHdrpStrength(uvec3 code) {
    float a = dequantizeUnorm(code.y & 255u, 8u) * 2.0f - 1.0f;
    return abs(a);
}

inline vec3 decodeAnisotropyHdrp(uvec3 code, vec3 n) {
    vec3 fx, fy;
    hdrpLocalFrame(n, fx, fy);
    float sinOrCos = kHdrpAngleBias + kHdrpAngleStep * dequantizeUnorm(code.x & 255u, 8u);
    float cosOrSin = sqrt(1.0f - sinOrCos * sinOrCos);
    bool storeSin = (code.z & 1u) != 0u;
    float s = storeSin ? sinOrCos : cosOrSin;
    float c = storeSin ? cosOrSin : sinOrCos;
    vec3 t = vec3(s * fy.x + c * fx.x, s * fy.y + c * fx.y, s * fy.z + c * fx.z);
    if ((code.y & 255u) >= 128u) return t;
    return vec3(n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x);
}

}  // namespace gbl::enc
