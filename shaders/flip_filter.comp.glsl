#version 450
#extension GL_GOOGLE_include_directive : require
// FLIP's separable filters, one 1D pass (twin of flip.cpp filterRows / filterCols, correlation
// order, clamp-to-edge): planes[u1] = planes[u0] filtered with the mode taps at kernels[u2..],
// along rows (flags 0) or columns (flags 1).
#include "eval_common.glsl"

void main() {
    const uint n = pc.width * pc.height;
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    const int taps = int(pc.mode), r = taps / 2;
    const int w = int(pc.width), h = int(pc.height);
    for (uint i = invocation(); i < n; i += total) {
        int x = int(i % pc.width), y = int(i / pc.width);
        float acc = 0.0;
        if (pc.flags == 0u) {
            for (int j = 0; j < taps; ++j) acc += kernels[pc.u2 + j] * planes[pc.u0].v[y * w + clamp(x + j - r, 0, w - 1)];
        } else {
            for (int j = 0; j < taps; ++j) acc += kernels[pc.u2 + j] * planes[pc.u0].v[clamp(y + j - r, 0, h - 1) * w + x];
        }
        planes[pc.u1].v[i] = acc;
    }
}
