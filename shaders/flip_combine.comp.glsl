#version 450
#extension GL_GOOGLE_include_directive : require
// FLIP of two prepared images, eqs. (5)-(10) of Andersson et al. 2020 (twin of flip.cpp
// combineRange): reference planes u0..u0+4 (L, a, b, edge, point), test planes u1..u1+4, into
// planes[u2]; f0 = c_max. mode 0 writes the value; mode 1 keeps the per-pixel maximum (HDR-FLIP's
// maximum over exposures, Andersson et al. 2021).
#include "eval_common.glsl"

void main() {
    const uint n = pc.width * pc.height;
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    const float cMax = pc.f0;
    const float pcCmax = 0.4 * cMax;
    const float lowScale = 0.95 / pcCmax;
    const float highScale = float(1.0LF - 0.95LF) / (cMax - pcCmax);
    const float invSqrt2 = float(0.70710678118654752440LF);
    const uint r = pc.u0, t = pc.u1;
    for (uint i = invocation(); i < n; i += total) {
        float dL = planes[r].v[i] - planes[t].v[i];
        float da = planes[r + 1u].v[i] - planes[t + 1u].v[i], db = planes[r + 2u].v[i] - planes[t + 2u].v[i];
        float dE = abs(dL) + sqrt(da * da + db * db);  // HyAB, eq. (5)
        float dEq = pow(dE, 0.7);
        float dEc = dEq < pcCmax ? dEq * lowScale : 0.95 + (dEq - pcCmax) * highScale;  // eq. (8)
        dEc = min(dEc, 1.0);
        float de = abs(planes[r + 3u].v[i] - planes[t + 3u].v[i]);
        float dp = abs(planes[r + 4u].v[i] - planes[t + 4u].v[i]);
        float dEf = min(1.0, sqrt(invSqrt2 * max(de, dp)));  // eq. (9), q_f = 0.5
        float f = dEf == 0.0 ? dEc : pow(dEc, 1.0 - dEf);     // eq. (10)
        if (pc.mode == 0u) planes[pc.u2].v[i] = f;
        else planes[pc.u2].v[i] = max(planes[pc.u2].v[i], f);
    }
}
