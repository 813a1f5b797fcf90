#version 450
#extension GL_GOOGLE_include_directive : require
// The reference's luminance (CIE Y of linear sRGB, negatives and NaN as 0) for HDR-FLIP's
// exposure range (flip_hdr.cpp flipExposureRange): mode 0 its maximum (field 0) and histogram u0
// (eval_common.glsl bins); mode 1 an exact refinement of one bin: for the values whose top bits
// are u1 (bits >> 14), the count per low 14 bits into histogram u0 (16384 counters); mode 2
// (a band of the reference, gpu_evaluator.cpp: the exact median needs the whole frame's values)
// the luminance itself into planes[u0] (field 0 still the maximum).
#include "eval_common.glsl"

void main() {
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    double mx = 0.0;
    for (uint i = countedBegin() + invocation(); i < countedEnd(); i += total) {
        vec3 c = imageLoad(refHdr, ivec2(i % pc.width, i / pc.width)).rgb;
        for (int k = 0; k < 3; ++k) c[k] = c[k] >= 0.0 ? c[k] : 0.0;
        float y = float(dot(dvec3(c), dvec3(0.2126729LF, 0.7151522LF, 0.0721750LF)));
        if (isnan(y) || isinf(y)) y = 0.0;
        if (pc.mode == 0u) {
            mx = max(mx, double(y));
            histAdd(pc.u0, y);
        } else if (pc.mode == 2u) {
            mx = max(mx, double(y));
            planes[pc.u0].v[i] = y;
        } else if (y > 0.0 && (floatBitsToUint(y) >> 14) == pc.u1) {
            atomicAdd(hist[pc.u0 * EVAL_HIST_BINS + (floatBitsToUint(y) & 16383u)], 1u);
        }
    }
    if (pc.mode != 1u) partials[invocation()] = mx;
}
