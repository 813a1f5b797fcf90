#version 450
#extension GL_GOOGLE_include_directive : require
// Stage 2 of every reduction: field f of the result is the sum (or, where bit f of the mask
// u1..u4 is set, the maximum) of field f over the u2 records of u0 fields that stage 1 wrote,
// in record order (deterministic, in double).
#include "eval_common.glsl"

void main() {
    uint f = invocation();
    uint fields = pc.u0, records = pc.u5;
    if (f >= fields) return;
    uint maskWord = f < 32u ? pc.u1 : (f < 64u ? pc.u2 : (f < 96u ? pc.u3 : pc.u4));
    bool isMax = ((maskWord >> (f & 31u)) & 1u) != 0u;
    double acc = isMax ? double(uintBitsToFloat(0xFF800000u)) : 0.0;  // -inf for maxima
    for (uint k = 0u; k < records; ++k) {
        double v = partials[k * fields + f];
        acc = isMax ? max(acc, v) : acc + v;
    }
    result[pc.u6 + f] = acc;
}
