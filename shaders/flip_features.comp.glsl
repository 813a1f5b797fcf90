#version 450
#extension GL_GOOGLE_include_directive : require
// FLIP's feature detection on the normalised luminance (twin of the feature half of flip.cpp
// prepare; FLIP eq. (9)'s edge and point magnitudes). flags 0: rows, planes[u0] -> u1 (edge
// taps), u2 (point taps), u3 (Gaussian). flags 1: columns, u1 (Gaussian), u3 (edge) -> the edge
// magnitude |(e_x, e_y)| into u4, and u2 (Gaussian), u3 (point) -> |(p_x, p_y)| into u5.
// Taps: mode each, edge at kernels[u6], point at kernels[u6 + mode], Gaussian at kernels[u7].
#include "eval_common.glsl"

// Eight outputs per invocation along the filter's direction, a sliding window of inputs, each
// input and tap weight loaded once for all eight, every output's sums over its taps in order: as
// flip_filter.comp.glsl (which says why).
#define OUTS 8
#define ZERO8(a) float a##0 = 0.0, a##1 = 0.0, a##2 = 0.0, a##3 = 0.0, a##4 = 0.0, a##5 = 0.0, a##6 = 0.0, a##7 = 0.0
#define FMA8(a, kw, in) a##0 += kw * in##0; a##1 += kw * in##1; a##2 += kw * in##2; a##3 += kw * in##3; \
                        a##4 += kw * in##4; a##5 += kw * in##5; a##6 += kw * in##6; a##7 += kw * in##7
#define SHIFT8(in) in##0 = in##1; in##1 = in##2; in##2 = in##3; in##3 = in##4; in##4 = in##5; in##5 = in##6; in##6 = in##7
#define ROW_PUT(k) if (k < n) { planes[pc.u1].v[at + k] = e##k; planes[pc.u2].v[at + k] = p##k; planes[pc.u3].v[at + k] = g##k; }
#define COL_PUT(k) if (k < n) { planes[pc.u4].v[at + k * w] = sqrt(ex##k * ex##k + ey##k * ey##k); \
                                planes[pc.u5].v[at + k * w] = sqrt(px##k * px##k + py##k * py##k); }

void main() {
    const int taps = int(pc.mode), r = taps / 2;
    const int w = int(pc.width), h = int(pc.height);
    const uint ke = pc.u6, kp = pc.u6 + pc.mode, kg = pc.u7;
    if (pc.flags == 0u) {
        // Rows: tasks of one row by EVAL_GROUP * OUTS columns, a workgroup per task (grid-stride).
        const int span = EVAL_GROUP * OUTS;
        const uint segments = uint((w + span - 1) / span);
        for (uint task = gl_WorkGroupID.x; task < segments * uint(h); task += gl_NumWorkGroups.x) {
            const int y = int(task / segments);
            const int x0 = int(task % segments) * span + int(gl_LocalInvocationID.x) * OUTS;
            if (x0 >= w) continue;
            const int row = y * w, first = x0 - r;
#define IN(j) planes[pc.u0].v[row + clamp(first + (j), 0, w - 1)]
            float v0 = IN(0), v1 = IN(1), v2 = IN(2), v3 = IN(3), v4 = IN(4), v5 = IN(5), v6 = IN(6), v7;
            ZERO8(e);
            ZERO8(p);
            ZERO8(g);
            for (int t = 0; t < taps; ++t) {
                v7 = IN(t + 7);
                const float kwe = kernels[ke + t], kwp = kernels[kp + t], kwg = kernels[kg + t];
                FMA8(e, kwe, v);
                FMA8(p, kwp, v);
                FMA8(g, kwg, v);
                SHIFT8(v);
            }
#undef IN
            const int at = row + x0, n = min(OUTS, w - x0);
            ROW_PUT(0) ROW_PUT(1) ROW_PUT(2) ROW_PUT(3) ROW_PUT(4) ROW_PUT(5) ROW_PUT(6) ROW_PUT(7)
        }
        return;
    }
    // Columns (eval_common.glsl columnTasks), OUTS rows at a time down the strip. Windows: hx
    // (edge taps' input, the Gaussian along rows u1), hp (point, u2), hg (the Gaussian, u3).
    for (uint task = gl_WorkGroupID.x; task < columnTasks(); task += gl_NumWorkGroups.x) {
        const int x = int(columnTaskX(task)), yStrip = int(columnTaskY(task));
        if (x >= w) continue;
        for (int y0 = yStrip; y0 < min(yStrip + int(EVAL_COLUMN_STRIP), h); y0 += OUTS) {
            const int first = y0 - r;
#define AT(j) uint(clamp(first + (j), 0, h - 1) * w + x)
#define LOAD3(j) hx##j = planes[pc.u1].v[AT(j)]; hp##j = planes[pc.u2].v[AT(j)]; hg##j = planes[pc.u3].v[AT(j)]
            float hx0, hx1, hx2, hx3, hx4, hx5, hx6, hx7, hp0, hp1, hp2, hp3, hp4, hp5, hp6, hp7;
            float hg0, hg1, hg2, hg3, hg4, hg5, hg6, hg7;
            LOAD3(0); LOAD3(1); LOAD3(2); LOAD3(3); LOAD3(4); LOAD3(5); LOAD3(6);
            ZERO8(ex);
            ZERO8(ey);
            ZERO8(px);
            ZERO8(py);
            for (int t = 0; t < taps; ++t) {
                const int j = t + 7;
                hx7 = planes[pc.u1].v[AT(j)];
                hp7 = planes[pc.u2].v[AT(j)];
                hg7 = planes[pc.u3].v[AT(j)];
                const float kwg = kernels[kg + t], kwe = kernels[ke + t], kwp = kernels[kp + t];
                FMA8(ex, kwg, hx);
                FMA8(ey, kwe, hg);
                FMA8(px, kwg, hp);
                FMA8(py, kwp, hg);
                SHIFT8(hx);
                SHIFT8(hp);
                SHIFT8(hg);
            }
#undef AT
#undef LOAD3
            const int at = y0 * w + x, n = min(OUTS, h - y0);
            COL_PUT(0) COL_PUT(1) COL_PUT(2) COL_PUT(3) COL_PUT(4) COL_PUT(5) COL_PUT(6) COL_PUT(7)
        }
    }
}
