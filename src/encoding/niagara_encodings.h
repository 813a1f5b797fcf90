#pragma once
// zeux/niagara's G-buffer encodings (src/shaders/mesh.frag.glsl and final.comp.glsl @95f289b7),
// C++ mirror of shaders/niagara_encodings.glsl (same names, same expressions, same order):
//
// - emissive_albedo_ratio: emissive stored as a scale of the albedo's luminance, one unorm code
//   x = log2(1 + L(emissive) / (L(albedo) + 0.001)) / 5 with L = (0.3, 0.6, 0.1) (niagara's weights,
//   not Rec. 709), decoded emissive = albedo * (2^(5 x) - 1), albedo being the *decoded* base
//   colour. It reads a second attribute of the pixel (base_color), so the layout must store
//   base_color in a field before it (layout_validate.cpp). Only emissive of the albedo's own hue
//   survives: a red glow on a white surface reads back white.
// - normal_octahedral_dithered: octahedral, unorm of p * 0.5 + 0.5 with niagara's "deband" noise
//   added before the rounding: + (2 g - 1) * 0.5 / (2^bits - 1), g = Jimenez's interleaved gradient
//   noise of the pixel centre (Jimenez, "Next Generation Post Processing in Call of Duty: Advanced
//   Warfare", SIGGRAPH 2014): fract(52.9829189 fract(0.06711056 x + 0.00583715 y)). The noise is a
//   function of the pixel coordinate only, so GPU and CPU write the same codes. Error per code up
//   to one step (the noise moves the rounding point by up to half a step).
//
// Why no log2/exp2: their GLSL precision is implementation-defined (3 ulp), and a last-ulp
// difference flips a rounding; log2 and exp2 are evaluated here with + - * / only (the contract of
// encodings.h), accurate to about 1e-7, far below a code step.
#include "encodings.h"

namespace gbl::enc {

// Niagara's luminance weights (mesh.frag.glsl: dot(c, vec3(0.3, 0.6, 0.1))).
inline float lumaNiagara(vec3 c) { return c.x * 0.3f + c.y * 0.6f + c.z * 0.1f; }

// log2(y) for y in [1, 32]: exponent from the bits (exact), mantissa m in [1, 2) by the atanh
// series 2/ln2 (t + t^3/3 + ... + t^15/15), t = (m - 1) / (m + 1) <= 1/3: truncation < 2e-9.
inline float log2Series(float y) {
    uint bits = floatBitsToUint(y);
    float e = float(int(bits >> 23u) - 127);
    float m = uintBitsToFloat((bits & 0x007fffffu) | 0x3f800000u);
    float t = (m - 1.0f) / (m + 1.0f);
    float t2 = t * t;
    float p = 0.19235934f;     // 2 / (15 ln 2)
    p = p * t2 + 0.22195308f;  // 2 / (13 ln 2)
    p = p * t2 + 0.26230819f;  // 2 / (11 ln 2)
    p = p * t2 + 0.32059890f;  // 2 / (9 ln 2)
    p = p * t2 + 0.41219858f;  // 2 / (7 ln 2)
    p = p * t2 + 0.57707802f;  // 2 / (5 ln 2)
    p = p * t2 + 0.96179669f;  // 2 / (3 ln 2)
    p = p * t2 + 2.88539008f;  // 2 / ln 2
    return e + t * p;
}

// 2^x for x in [0, 5]: 2^floor(x) (exact) times the Taylor series of e^(f ln 2), f in [0, 1), to
// degree 10: truncation < 1e-9 relative.
inline float exp2Series(float x) {
    float i = floor(x);
    float f = x - i;
    float p = 7.0549116e-09f;
    p = p * f + 1.0178086e-07f;
    p = p * f + 1.3215487e-06f;
    p = p * f + 1.5252734e-05f;
    p = p * f + 1.5403530e-04f;
    p = p * f + 1.3333558e-03f;
    p = p * f + 9.6181291e-03f;
    p = p * f + 5.5504109e-02f;
    p = p * f + 2.4022651e-01f;
    p = p * f + 6.9314718e-01f;
    p = p * f + 1.0f;
    return p * float(1u << uint(i));
}

// emissive_albedo_ratio (niagara mesh.frag.glsl: gbuffer[0].a = log2(1 + emissivef) / 5). The
// ratio is clamped to [0, 31] first: log2(32) / 5 = 1, the top code, as the UNORM target clamps.
inline uint encodeEmissiveAlbedoRatio(vec3 emissive, vec3 albedo, uint bits) {
    float ratio = lumaNiagara(emissive) / (lumaNiagara(albedo) + 0.001f);
    float y = clamp(ratio, 0.0f, 31.0f) + 1.0f;
    return quantizeUnorm(log2Series(y) / 5.0f, bits);
}

// niagara final.comp.glsl: emissive = albedo * (exp2(gbuffer0.a * 5) - 1), albedo decoded.
inline vec3 decodeEmissiveAlbedoRatio(uint code, uint bits, vec3 albedo) {
    float k = exp2Series(dequantizeUnorm(code, bits) * 5.0f) - 1.0f;
    return albedo * k;
}

// Jimenez's interleaved gradient noise at the pixel's centre (gl_FragCoord.xy = pixel + 0.5, as
// niagara's mesh.frag.glsl:60 calls gradientNoise(gl_FragCoord.xy); math.h:99-102), in [0, 1).
inline float gradientNoise(ivec2 pixel) {
    float x = float(pixel.x) + 0.5f;
    float y = float(pixel.y) + 0.5f;
    float d = x * 0.06711056f + y * 0.00583715f;
    float f = d - floor(d);
    float g = 52.9829189f * f;
    return g - floor(g);
}

// octEncodeNiagara: niagara's encodeOct (math.h:52-58): p = n.xy * (1 / |n|_1) -- a multiply by
// the reciprocal, where octEncode divides, so a last-ulp difference can move a code (about 1 in
// 10^5 normals at 10 bits) -- folded for n.z <= 0 to (1 - |p.y|, 1 - |p.x|) with the signs of
// n.x, n.y (+1 for >= 0, -0 included), as octEncode.
inline vec2 octEncodeNiagara(vec3 n) {
    float r = 1.0f / (abs(n.x) + abs(n.y) + abs(n.z));
    float px = n.x * r;
    float py = n.y * r;
    float sx = n.x >= 0.0f ? 1.0f : -1.0f;
    float sy = n.y >= 0.0f ? 1.0f : -1.0f;
    vec2 folded = vec2((1.0f - abs(py)) * sx, (1.0f - abs(px)) * sy);
    return n.z <= 0.0f ? folded : vec2(px, py);
}

// normal_octahedral_dithered (niagara mesh.frag.glsl:60,86: encodeOct(nrm) * 0.5 + 0.5 + deband *
// (0.5 / 1023) into A2B10G10R10_UNORM's r, g, deband = gradientNoise(gl_FragCoord.xy) * 2 - 1).
// Decoded as normal_octahedral_bevy / _unity are: decodeNormalOctahedralUnorm (code / (2^bits - 1)
// * 2 - 1, octahedral unfold, normalise), the same direction as niagara's decodeOct (math.h:60-67:
// its Stubbesaurus unfold is the same fold written as v.xy -= sign(v.xy) * max(-v.z, 0)).
// The UNORM conversion is modelled as quantizeUnorm (round to nearest, ties up: Vulkan leaves
// the tie open).
inline uvec2 encodeNormalOctahedralDithered(vec3 n, uint bits, ivec2 pixel) {
    vec2 p = octEncodeNiagara(n);
    float s = float((1u << bits) - 1u);
    float d = (gradientNoise(pixel) * 2.0f - 1.0f) * (0.5f / s);
    float ux = p.x * 0.5f + 0.5f + d;
    float uy = p.y * 0.5f + 0.5f + d;
    return uvec2(quantizeUnorm(ux, bits), quantizeUnorm(uy, bits));
}

// A dither that moves with time (a field's dither_per_frame; niagara_encodings.glsl): the
// gradient noise advanced by 5.588238 pixels per frame, cycling every 64 frames (Wolfe,
// "Interleaved Gradient Noise: A Different Kind of Low Discrepancy Sequence", 2022). Frame 0 is
// gradientNoise(pixel) bit for bit.
inline float gradientNoiseAtFrame(ivec2 pixel, uint32_t frameIndex) {
    float offset = 5.588238f * float(frameIndex % 64u);
    float x = float(pixel.x) + 0.5f + offset;
    float y = float(pixel.y) + 0.5f + offset;
    float d = x * 0.06711056f + y * 0.00583715f;
    float f = d - floor(d);
    float g = 52.9829189f * f;
    return g - floor(g);
}

inline uvec2 encodeNormalOctahedralDitheredAtFrame(vec3 n, uint bits, ivec2 pixel, uint32_t frameIndex) {
    vec2 p = octEncodeNiagara(n);
    float s = float((1u << bits) - 1u);
    float d = (gradientNoiseAtFrame(pixel, frameIndex) * 2.0f - 1.0f) * (0.5f / s);
    float ux = p.x * 0.5f + 0.5f + d;
    float uy = p.y * 0.5f + 0.5f + d;
    return uvec2(quantizeUnorm(ux, bits), quantizeUnorm(uy, bits));
}

}  // namespace gbl::enc
