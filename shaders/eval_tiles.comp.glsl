#version 450
#extension GL_GOOGLE_include_directive : require
// Mean relative luminance error (run_metrics.h relativeLuminanceError; floor f3) of each u0 x u0
// tile, into tiles[]: compare finds the worst regions on these (worst_regions.h) instead of
// reading the per-pixel map back. NaN counts as 0, as findWorstRegions does. The tiles cover the
// counted rows (eval_common.glsl), from their first: a band's tiles are the frame's when its
// first row is a multiple of u0 (gpu_evaluator.h).
#include "eval_common.glsl"

void main() {
    const uint s = pc.u0;
    const uint tw = (pc.width + s - 1u) / s, th = (pc.rowCount + s - 1u) / s;
    const uint rowEnd = pc.rowFirst + pc.rowCount;
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    for (uint k = invocation(); k < tw * th; k += total) {
        uint x0 = (k % tw) * s, y0 = pc.rowFirst + (k / tw) * s;
        double sum = 0.0;
        uint count = 0u;
        for (uint y = y0; y < min(y0 + s, rowEnd); ++y)
            for (uint x = x0; x < min(x0 + s, pc.width); ++x) {
                vec4 r = imageLoad(refHdr, ivec2(x, y)), t = imageLoad(testHdr, ivec2(x, y));
                double yr = 0.2126 * double(r.r) + 0.7152 * double(r.g) + 0.0722 * double(r.b);
                double yt = 0.2126 * double(t.r) + 0.7152 * double(t.g) + 0.0722 * double(t.b);
                bool finiteY = !isnan(float(yr)) && !isinf(float(yr));
                float rel = float(abs(yt - yr) / max(finiteY ? yr : 0.0, double(pc.f3)));
                if (!isnan(rel) && !isinf(rel)) sum += rel;
                ++count;
            }
        tiles[k] = float(sum / double(max(count, 1u)));
    }
}
