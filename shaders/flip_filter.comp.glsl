#version 450
#extension GL_GOOGLE_include_directive : require
// FLIP's separable filters, one 1D pass (twin of flip.cpp filterRows / filterCols, correlation
// order, clamp-to-edge): planes[u1] = planes[u0] filtered with the mode taps at kernels[u2..],
// along rows (flags 0) or columns (flags 1).
#include "eval_common.glsl"

// Eight outputs per invocation, side by side along the filter's direction, with a sliding
// window of the eight inputs the current tap t meets (w0 .. w7: input t + k for output k): each
// input is loaded once and each tap weight once for all eight, so an output costs about
// (taps + 7) / 8 loads instead of 2 taps. Each output's sum still runs over its taps in order
// 0 .. taps-1, the same products added in the same order: bit for bit the one-output loop. (On
// llvmpipe a storage-buffer load at a per-lane address is a loop over the lanes, by far the
// dearest step of these passes; the registers are named, not an array, as an array indexed at
// run time is another of its slow paths.)
#define OUTS 8
#define ZERO8(a) float a##0 = 0.0, a##1 = 0.0, a##2 = 0.0, a##3 = 0.0, a##4 = 0.0, a##5 = 0.0, a##6 = 0.0, a##7 = 0.0
#define FMA8(a, kw) a##0 += kw * w0; a##1 += kw * w1; a##2 += kw * w2; a##3 += kw * w3; \
                    a##4 += kw * w4; a##5 += kw * w5; a##6 += kw * w6; a##7 += kw * w7
#define SHIFT8 w0 = w1; w1 = w2; w2 = w3; w3 = w4; w4 = w5; w5 = w6; w6 = w7
#define PUT(k) if (k < n) planes[dst].v[at + k * step] = a##k

void main() {
    const int taps = int(pc.mode), r = taps / 2;
    const int w = int(pc.width), h = int(pc.height);
    const uint src = pc.u0, dst = pc.u1;
    if (pc.flags == 0u) {
        // Rows: tasks of one row by EVAL_GROUP * OUTS columns, a workgroup per task (grid-stride).
        const int span = EVAL_GROUP * OUTS;
        const uint segments = uint((w + span - 1) / span);
        for (uint task = gl_WorkGroupID.x; task < segments * uint(h); task += gl_NumWorkGroups.x) {
            const int y = int(task / segments);
            const int x0 = int(task % segments) * span + int(gl_LocalInvocationID.x) * OUTS;
            if (x0 >= w) continue;
            const int row = y * w, first = x0 - r;
#define IN(j) planes[src].v[row + clamp(first + (j), 0, w - 1)]
            float w0 = IN(0), w1 = IN(1), w2 = IN(2), w3 = IN(3), w4 = IN(4), w5 = IN(5), w6 = IN(6), w7;
            ZERO8(a);
            for (int t = 0; t < taps; ++t) {
                w7 = IN(t + 7);
                const float kw = kernels[pc.u2 + t];
                FMA8(a, kw);
                SHIFT8;
            }
#undef IN
            const int at = row + x0, n = min(OUTS, w - x0), step = 1;
            PUT(0); PUT(1); PUT(2); PUT(3); PUT(4); PUT(5); PUT(6); PUT(7);
        }
        return;
    }
    // Columns (eval_common.glsl columnTasks): each invocation walks its column down the strip,
    // OUTS rows at a time.
    for (uint task = gl_WorkGroupID.x; task < columnTasks(); task += gl_NumWorkGroups.x) {
        const int x = int(columnTaskX(task)), yStrip = int(columnTaskY(task));
        if (x >= w) continue;
        for (int y0 = yStrip; y0 < min(yStrip + int(EVAL_COLUMN_STRIP), h); y0 += OUTS) {
            const int first = y0 - r;
#define IN(j) planes[src].v[clamp(first + (j), 0, h - 1) * w + x]
            float w0 = IN(0), w1 = IN(1), w2 = IN(2), w3 = IN(3), w4 = IN(4), w5 = IN(5), w6 = IN(6), w7;
            ZERO8(a);
            for (int t = 0; t < taps; ++t) {
                w7 = IN(t + 7);
                const float kw = kernels[pc.u2 + t];
                FMA8(a, kw);
                SHIFT8;
            }
#undef IN
            const int at = y0 * w + x, n = min(OUTS, h - y0), step = w;
            PUT(0); PUT(1); PUT(2); PUT(3); PUT(4); PUT(5); PUT(6); PUT(7);
        }
    }
}
