// zeux/niagara's G-buffer encodings, GLSL twin of src/encoding/niagara_encodings.h (same names,
// same expressions, same order; the sources and error bounds are stated there). Included by
// encodings.glsl. Float intermediates are `precise`: no driver may fuse or reassociate them, so
// the codes equal the C++ mirror's to the bit (tests/codec/gpu_cpu_bits_test.cpp).

#ifndef GBL_NIAGARA_ENCODINGS_GLSL
#define GBL_NIAGARA_ENCODINGS_GLSL

float lumaNiagara(vec3 c) {
    precise float l = c.x * 0.3 + c.y * 0.6 + c.z * 0.1;
    return l;
}

// log2(y), y in [1, 32], with + - * / only (GLSL's log2 precision is implementation-defined).
float log2Series(float y) {
    uint bits = floatBitsToUint(y);
    precise float e = float(int(bits >> 23u) - 127);
    precise float m = uintBitsToFloat((bits & 0x007fffffu) | 0x3f800000u);
    precise float t = (m - 1.0) / (m + 1.0);
    precise float t2 = t * t;
    precise float p = 0.19235934;
    p = p * t2 + 0.22195308;
    p = p * t2 + 0.26230819;
    p = p * t2 + 0.32059890;
    p = p * t2 + 0.41219858;
    p = p * t2 + 0.57707802;
    p = p * t2 + 0.96179669;
    p = p * t2 + 2.88539008;
    precise float r = e + t * p;
    return r;
}

// 2^x, x in [0, 5]: 2^floor(x) times the degree-10 Taylor series of e^(f ln 2).
float exp2Series(float x) {
    precise float i = floor(x);
    precise float f = x - i;
    precise float p = 7.0549116e-09;
    p = p * f + 1.0178086e-07;
    p = p * f + 1.3215487e-06;
    p = p * f + 1.5252734e-05;
    p = p * f + 1.5403530e-04;
    p = p * f + 1.3333558e-03;
    p = p * f + 9.6181291e-03;
    p = p * f + 5.5504109e-02;
    p = p * f + 2.4022651e-01;
    p = p * f + 6.9314718e-01;
    p = p * f + 1.0;
    precise float r = p * float(1u << uint(i));
    return r;
}

uint encodeEmissiveAlbedoRatio(vec3 emissive, vec3 albedo, uint bits) {
    precise float ratio = lumaNiagara(emissive) / (lumaNiagara(albedo) + 0.001);
    precise float y = clamp(ratio, 0.0, 31.0) + 1.0;
    precise float x = log2Series(y) / 5.0;
    return quantizeUnorm(x, bits);
}

vec3 decodeEmissiveAlbedoRatio(uint code, uint bits, vec3 albedo) {
    precise float k = exp2Series(dequantizeUnorm(code, bits) * 5.0) - 1.0;
    return albedo * k;
}

float gradientNoise(ivec2 pixel) {
    precise float x = float(pixel.x) + 0.5;
    precise float y = float(pixel.y) + 0.5;
    precise float d = x * 0.06711056 + y * 0.00583715;
    precise float f = d - floor(d);
    precise float g = 52.9829189 * f;
    precise float r = g - floor(g);
    return r;
}

// niagara's encodeOct (math.h:52-58): a multiply by the reciprocal of |n|_1.
vec2 octEncodeNiagara(vec3 n) {
    precise float r = 1.0 / (abs(n.x) + abs(n.y) + abs(n.z));
    precise float px = n.x * r;
    precise float py = n.y * r;
    float sx = n.x >= 0.0 ? 1.0 : -1.0;
    float sy = n.y >= 0.0 ? 1.0 : -1.0;
    precise vec2 folded = vec2((1.0 - abs(py)) * sx, (1.0 - abs(px)) * sy);
    return n.z <= 0.0 ? folded : vec2(px, py);
}

uvec2 encodeNormalOctahedralDithered(vec3 n, uint bits, ivec2 pixel) {
    vec2 p = octEncodeNiagara(n);
    precise float s = float((1u << bits) - 1u);
    precise float d = (gradientNoise(pixel) * 2.0 - 1.0) * (0.5 / s);
    precise float ux = p.x * 0.5 + 0.5 + d;
    precise float uy = p.y * 0.5 + 0.5 + d;
    return uvec2(quantizeUnorm(ux, bits), quantizeUnorm(uy, bits));
}

// A dither that moves with time (a field's dither_per_frame): the gradient noise advanced by
// 5.588238 pixels per frame, cycling every 64 frames (Wolfe, "Interleaved Gradient Noise: A
// Different Kind of Low Discrepancy Sequence", 2022, as Bevy and others animate Jimenez's noise).
// Frame 0 is gradientNoise's value bit for bit (+ 0.0 is exact).
float gradientNoiseAtFrame(ivec2 pixel, uint frameIndex) {
    precise float offset = 5.588238 * float(frameIndex % 64u);
    precise float x = float(pixel.x) + 0.5 + offset;
    precise float y = float(pixel.y) + 0.5 + offset;
    precise float d = x * 0.06711056 + y * 0.00583715;
    precise float f = d - floor(d);
    precise float g = 52.9829189 * f;
    precise float r = g - floor(g);
    return r;
}

uvec2 encodeNormalOctahedralDitheredAtFrame(vec3 n, uint bits, ivec2 pixel, uint frameIndex) {
    vec2 p = octEncodeNiagara(n);
    precise float s = float((1u << bits) - 1u);
    precise float d = (gradientNoiseAtFrame(pixel, frameIndex) * 2.0 - 1.0) * (0.5 / s);
    precise float ux = p.x * 0.5 + 0.5 + d;
    precise float uy = p.y * 0.5 + 0.5 + d;
    return uvec2(quantizeUnorm(ux, bits), quantizeUnorm(uy, bits));
}

#endif  // GBL_NIAGARA_ENCODINGS_GLSL
