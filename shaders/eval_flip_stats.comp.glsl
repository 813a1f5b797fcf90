#version 450
#extension GL_GOOGLE_include_directive : require
// The FLIP map planes[u0] summed (all pixels, and per material class over the pixels covered in
// both renders), into histogram u1 when flags bit 1 (the median), colour-mapped over [0,1] into
// out8[3] when flags bit 0 (the report's flip.png).
#include "eval_common.glsl"

#define FIELDS 5  // 0 sum, 1 dielectric sum, 2 dielectric pixels, 3 metal sum, 4 metal pixels
void main() {
    double acc[FIELDS];
    for (int f = 0; f < FIELDS; ++f) acc[f] = 0.0;
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    for (uint i = countedBegin() + invocation(); i < countedEnd(); i += total) {
        ivec2 p = ivec2(i % pc.width, i / pc.width);
        float v = planes[pc.u0].v[i];
        acc[0] += v;
        if (imageLoad(refHdr, p).a != 0.0 && imageLoad(testHdr, p).a != 0.0) {
            int base = imageLoad(refSurface[1], p).a > 0.5 ? 3 : 1;
            acc[base] += v;
            acc[base + 1] += 1.0;
        }
        if ((pc.flags & 2u) != 0u) histAdd(pc.u1, v);
        if ((pc.flags & 1u) != 0u) out8[3].px[i] = colorMap(v, 0.0, 1.0);
    }
    for (int f = 0; f < FIELDS; ++f) partials[invocation() * FIELDS + f] = acc[f];
}
