#version 450
#extension GL_GOOGLE_include_directive : require
// Stage 2 of every reduction: field f of the result is the sum (or, where bit f of the mask
// u1..u4 is set, the maximum) of field f over the u5 records of u0 fields that stage 1 wrote,
// from record u7 on, in record order (deterministic, in double).
// mode 1 (many records, on a GPU): invocation f + u0 c folds chunk c of `flags` equal chunks of
// the u5 records into record u5 + c, for a second dispatch in mode 0 to fold (eval_device.cpp).
#include "eval_common.glsl"

void main() {
    uint t = invocation();
    uint fields = pc.u0, records = pc.u5;
    uint f = t % fields, chunk = t / fields;
    if (pc.mode == 0u ? t >= fields : chunk >= pc.flags) return;
    uint maskWord = f < 32u ? pc.u1 : (f < 64u ? pc.u2 : (f < 96u ? pc.u3 : pc.u4));
    bool isMax = ((maskWord >> (f & 31u)) & 1u) != 0u;
    double acc = isMax ? double(uintBitsToFloat(0xFF800000u)) : 0.0;  // -inf for maxima
    uint first = pc.mode == 0u ? pc.u7 : chunk * records / pc.flags;
    uint end = pc.mode == 0u ? pc.u7 + records : (chunk + 1u) * records / pc.flags;
    for (uint k = first; k < end; ++k) {
        double v = partials[k * fields + f];
        acc = isMax ? max(acc, v) : acc + v;
    }
    if (pc.mode == 0u) result[pc.u6 + f] = acc;
    else partials[(records + chunk) * fields + f] = acc;
}
