#version 450
#extension GL_GOOGLE_include_directive : require
// FLIP's feature detection on the normalised luminance (twin of the feature half of flip.cpp
// prepare; FLIP eq. (9)'s edge and point magnitudes). flags 0: rows, planes[u0] -> u1 (edge
// taps), u2 (point taps), u3 (Gaussian). flags 1: columns, u1 (Gaussian), u3 (edge) -> the edge
// magnitude |(e_x, e_y)| into u4, and u2 (Gaussian), u3 (point) -> |(p_x, p_y)| into u5.
// Taps: mode each, edge at kernels[u6], point at kernels[u6 + mode], Gaussian at kernels[u7].
#include "eval_common.glsl"

void main() {
    const uint n = pc.width * pc.height;
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    const int taps = int(pc.mode), r = taps / 2;
    const int w = int(pc.width), h = int(pc.height);
    const uint ke = pc.u6, kp = pc.u6 + pc.mode, kg = pc.u7;
    for (uint i = invocation(); i < n; i += total) {
        int x = int(i % pc.width), y = int(i / pc.width);
        if (pc.flags == 0u) {
            float e = 0.0, p = 0.0, g = 0.0;
            for (int j = 0; j < taps; ++j) {
                float v = planes[pc.u0].v[y * w + clamp(x + j - r, 0, w - 1)];
                e += kernels[ke + j] * v;
                p += kernels[kp + j] * v;
                g += kernels[kg + j] * v;
            }
            planes[pc.u1].v[i] = e;
            planes[pc.u2].v[i] = p;
            planes[pc.u3].v[i] = g;
        } else {
            float ex = 0.0, ey = 0.0, px = 0.0, py = 0.0;
            for (int j = 0; j < taps; ++j) {
                uint k = uint(clamp(y + j - r, 0, h - 1) * w + x);
                float hg = planes[pc.u3].v[k];
                ex += kernels[kg + j] * planes[pc.u1].v[k];
                ey += kernels[ke + j] * hg;
                px += kernels[kg + j] * planes[pc.u2].v[k];
                py += kernels[kp + j] * hg;
            }
            planes[pc.u4].v[i] = sqrt(ex * ex + ey * ey);
            planes[pc.u5].v[i] = sqrt(px * px + py * py);
        }
    }
}
