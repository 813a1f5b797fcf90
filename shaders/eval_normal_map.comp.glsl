#version 450
#extension GL_GOOGLE_include_directive : require
// The report's normal-error image of a banded run (gpu_evaluator.cpp finishRun): planes[u0] holds
// what eval_attributes.comp.glsl mode 2 wrote for the counted rows (the angle in degrees, or
// -(grey + 1) where the pixel is not covered in both renders); mapped into out8[4] exactly as
// mode 1 maps them in a whole-frame run, over [0, f1] (f1 from the whole frame's p99). Reads no
// image: the band's images may be gone by then.
#include "eval_common.glsl"

void main() {
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    for (uint i = countedBegin() + invocation(); i < countedEnd(); i += total) {
        float v = planes[pc.u0].v[i];
        out8[4].px[i] = v < 0.0 ? pack8(uvec3(uint(-v) - 1u)) : colorMap(v, 0.0, pc.f1);
    }
}
