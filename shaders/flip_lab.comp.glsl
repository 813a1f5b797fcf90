#version 450
#extension GL_GOOGLE_include_directive : require
// FLIP, per image, after the CSF filters (twin of flip.cpp opponentToClampedRgb + rgbToHuntLab):
// filtered YyCxCz (planes u0, u1 and the blue-yellow channel f0 * planes[u2] + f1 * planes[u3]
// when flags bit 0, else planes[u2]) -> XYZ -> linear RGB clamped to [0,1] -> Hunt-adjusted CIELAB
// (FLIP eq. (4)), into planes u4 (L), u5 (a), u6 (b).
#include "eval_common.glsl"
#include "flip_common.glsl"

float cubeRoot(float t) {  // flip.cpp cubeRoot: bit-level guess, two Halley steps in double
    uint bits = floatBitsToUint(t) / 3u + 0x2A514067u;
    double x = t, y = uintBitsToFloat(bits);
    double y3 = y * y * y;
    y = y * (y3 + 2.0 * x) / (2.0 * y3 + x);
    y3 = y * y * y;
    y = y * (y3 + 2.0 * x) / (2.0 * y3 + x);
    return float(y);
}
float labF(float t) {
    const float d3 = float((6.0LF / 29.0LF) * (6.0LF / 29.0LF) * (6.0LF / 29.0LF));
    const float s = float(1.0LF / (3.0LF * (6.0LF / 29.0LF) * (6.0LF / 29.0LF)));
    const float o = float(4.0LF / 29.0LF);
    return t > d3 ? cubeRoot(t) : t * s + o;
}

void main() {
    const uint n = pc.width * pc.height;
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    for (uint i = invocation(); i < n; i += total) {
        float yy = planes[pc.u0].v[i], cx = planes[pc.u1].v[i];
        float cz = (pc.flags & 1u) != 0u ? pc.f0 * planes[pc.u2].v[i] + pc.f1 * planes[pc.u3].v[i] : planes[pc.u2].v[i];
        float Yr = (yy + 16.0) * float(1.0LF / 116.0LF);
        vec3 xyz = vec3((cx * (1.0 / 500.0) + Yr) * kernels[KC_W], Yr * kernels[KC_W + 1],
                        (Yr - cz * (1.0 / 200.0)) * kernels[KC_W + 2]);
        vec3 rgb = clamp(vec3(dot(flipMi(0), xyz), dot(flipMi(1), xyz), dot(flipMi(2), xyz)), 0.0, 1.0);
        float X = dot(flipM(0), rgb), Y = dot(flipM(1), rgb), Z = dot(flipM(2), rgb);
        float fx = labF(X * kernels[KC_IW]), fy = labF(Y * kernels[KC_IW + 1]), fz = labF(Z * kernels[KC_IW + 2]);
        float L = 116.0 * fy - 16.0;
        planes[pc.u4].v[i] = L;
        planes[pc.u5].v[i] = 0.01 * L * (500.0 * (fx - fy));
        planes[pc.u6].v[i] = 0.01 * L * (200.0 * (fy - fz));
    }
}
