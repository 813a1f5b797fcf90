#version 450
#extension GL_GOOGLE_include_directive : require
// Image errors of a test render against the reference (measure/run_metrics.h defines each one):
// linear RMSE / mean / max / p99 (histogram 0) of |test - reference| over RGB, the PSNR peak, the
// tone-mapped RMSE on the 8-bit values, and per material class (covered in both; metal when the
// reference metallic > 0.5) the relative luminance error, the linear squared error and the
// reference noise. With flags bit 0 it also writes the report's 8-bit images: the tone-mapped
// render (out8 0), the amplified difference (out8 1, x f1) and the relative-luminance heat map
// (out8 2, 0 .. f2), and the reference's tone-mapped render (out8 5, for the worst-region crops). f0: exposure; f3: the relative error's floor; flags bit 1: a noise plane
// (planes[u0]) is bound.
#include "eval_common.glsl"

#define FIELDS 15
// 0 sum d^2, 1 sum |d|, 2 max |d|, 3 max reference value, 4 sum of tone-mapped d^2,
// 5 sum of finite positive reference luminance, 6 finite reference luminance count,
// 7.. per class (dielectric 7-10, metal 11-14): pixels, relative error, d^2, noise / max(Y, floor).
void main() {
    double acc[FIELDS];
    for (int f = 0; f < FIELDS; ++f) acc[f] = 0.0;
    acc[2] = 0.0;
    acc[3] = double(uintBitsToFloat(0xFF800000u));  // -inf
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    const float exposure = pc.f0, floorY = pc.f3;
    for (uint i = countedBegin() + invocation(); i < countedEnd(); i += total) {
        ivec2 p = ivec2(i % pc.width, i / pc.width);
        vec4 r = imageLoad(refHdr, p), t = imageLoad(testHdr, p);
        for (int c = 0; c < 3; ++c) {
            double d = double(t[c]) - double(r[c]);
            acc[0] += d * d;
            acc[1] += abs(d);
            acc[2] = max(acc[2], abs(d));
            acc[3] = max(acc[3], double(r[c]));
            histAdd(0u, float(abs(d)));
        }
        uvec3 rb = toneMap8(r.rgb, exposure), tb = toneMap8(t.rgb, exposure);
        vec3 rs = vec3(rb) / 255.0, ts = vec3(tb) / 255.0;
        for (int c = 0; c < 3; ++c) {
            double d = double(ts[c]) - double(rs[c]);
            acc[4] += d * d;
        }
        double yr = 0.2126 * double(r.r) + 0.7152 * double(r.g) + 0.0722 * double(r.b);
        double yt = 0.2126 * double(t.r) + 0.7152 * double(t.g) + 0.0722 * double(t.b);
        bool finiteY = !isnan(float(yr)) && !isinf(float(yr));
        if (finiteY && yr > 0.0) acc[5] += yr;
        if (finiteY) acc[6] += 1.0;
        double rel = abs(yt - yr) / max(finiteY ? yr : 0.0, double(floorY));
        float relF = isnan(float(rel)) || isinf(float(rel)) ? uintBitsToFloat(0x7FC00000u) : float(rel);
        if (r.a != 0.0 && t.a != 0.0) {
            int base = imageLoad(refSurface[1], p).a > 0.5 ? 11 : 7;
            acc[base] += 1.0;
            acc[base + 1] += isnan(relF) ? 0.0 : double(relF);
            for (int c = 0; c < 3; ++c) {
                double d = double(t[c]) - double(r[c]);
                acc[base + 2] += d * d;
            }
            if ((pc.flags & 2u) != 0u) acc[base + 3] += double(planes[pc.u0].v[i]) / max(finiteY ? yr : 0.0, double(floorY));
        }
        if ((pc.flags & 1u) != 0u) {
            out8[0].px[i] = pack8(tb);
            out8[5].px[i] = pack8(rb);
            uvec3 diff;
            for (int c = 0; c < 3; ++c) {
                float d = pc.f1 * abs(ts[c] - rs[c]);
                d = isnan(d) ? 1.0 : min(d, 1.0);
                diff[c] = uint(floor(d * 255.0 + 0.5));
            }
            out8[1].px[i] = pack8(diff);
            out8[2].px[i] = colorMap(relF, 0.0, pc.f2);
        }
    }
    for (int f = 0; f < FIELDS; ++f) partials[invocation() * FIELDS + f] = acc[f];
}
