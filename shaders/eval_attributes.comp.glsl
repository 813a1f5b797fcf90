#version 450
#extension GL_GOOGLE_include_directive : require
// Attribute errors of a test layout's decoded surfaces against the reference's (units and pixel
// choice as measure/run_metrics.h states them): over the pixels covered in both renders (HDR
// alpha), per material class (reference metallic > 0.5: metal), the normal angle (degrees), the
// CIEDE2000 of base, diffuse and specular colour (Sharma, Wu & Dalal 2005, via linear sRGB -> XYZ
// D65 -> CIELAB) with the colours' squared RGB error, |roughness|, |metallic|, |occlusion| and
// the relative view depth error. Histograms 2 + 2 a + class. mode 1 instead writes the report's
// normal-error image into out8[4]: the angle colour-mapped over [0, f1], other pixels the
// reference's tone-mapped luminance (exposure f0) dimmed to grey (report/error_images.cpp).
// mode 2 (a band of a banded run, whose colour scale needs the whole frame's p99) writes what
// mode 1 would map instead, into planes[u0]: the angle as the float mode 1 maps, or -(grey + 1)
// for the other pixels; eval_normal_map.comp.glsl maps them once the frame is done.
#include "eval_common.glsl"

#define ATTRS 8
#define PER_ATTR 11  // per class (dielectric, metal): count, sum, sum of squares, max, colour d^2; then skipped
#define FIELDS (ATTRS * PER_ATTR + 5)  // + both, reference only, test only, metal, dielectric

#include "eval_attribute_math.glsl"  // normalAngleDeg, labOf, deltaE2000 (shared with eval_layers)

double acc[FIELDS];
void add(int a, int cls, double e, double colorSq) {
    int b = a * PER_ATTR + cls * 5;
    acc[b] += 1.0;
    acc[b + 1] += e;
    acc[b + 2] += e * e;
    acc[b + 3] = max(acc[b + 3], e);
    acc[b + 4] += colorSq;
    histAdd(2u + uint(a * 2 + cls), float(e));
}
void skip(int a) { acc[a * PER_ATTR + 10] += 1.0; }
bool finiteD(double v) { return !isnan(float(v)) && !isinf(float(v)); }

void colour(int a, int cls, vec3 r, vec3 t) {
    dvec3 d = dvec3(t) - dvec3(r);
    double sq = dot(d, d);
    double e = (r == t) ? 0.0 : deltaE2000(labOf(r), labOf(t));
    if (finiteD(e)) add(a, cls, e, sq);
    else skip(a);
}
void scalar(int a, int cls, float r, float t) {
    double e = abs(double(t) - double(r));
    if (finiteD(e)) add(a, cls, e, 0.0);
    else skip(a);
}

// Modes 1 and 2: the normal-error image, in a loop of its own: llvmpipe runs both sides of a
// branch under a lane mask, so the statistics' code inside the same loop cost as much again.
void normalImage() {
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    for (uint i = countedBegin() + invocation(); i < countedEnd(); i += total) {
        ivec2 p = ivec2(i % pc.width, i / pc.width);
        bool rc = imageLoad(refHdr, p).a != 0.0, tc = imageLoad(testHdr, p).a != 0.0;
        float angle = 0.0;
        uint grey = 0u;
        if (rc && tc) {
            bool ok;
            angle = float(normalAngleDeg(imageLoad(refSurface[0], p).xyz, imageLoad(testSurface[0], p).xyz, ok));
        } else {
            vec3 s = vec3(toneMap8(imageLoad(refHdr, p).rgb, pc.f0)) / 255.0;
            float y = clamp(luminance(s), 0.0, 1.0);
            grey = uint(floor((0.12 + 0.3 * y) * 255.0 + 0.5));
        }
        if (pc.mode == 2u) planes[pc.u0].v[i] = rc && tc ? angle : -(float(grey) + 1.0);
        else out8[4].px[i] = rc && tc ? colorMap(angle, 0.0, pc.f1) : pack8(uvec3(grey));
    }
}

void main() {
    if (pc.mode != 0u) {
        normalImage();
        return;
    }
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    for (int f = 0; f < FIELDS; ++f) acc[f] = 0.0;
    for (uint i = countedBegin() + invocation(); i < countedEnd(); i += total) {
        ivec2 p = ivec2(i % pc.width, i / pc.width);
        bool rc = imageLoad(refHdr, p).a != 0.0, tc = imageLoad(testHdr, p).a != 0.0;
        if (!(rc && tc)) {
            if (rc) acc[ATTRS * PER_ATTR + 1] += 1.0;
            if (tc) acc[ATTRS * PER_ATTR + 2] += 1.0;
            continue;
        }
        vec4 r[4], t[4];
        for (int k = 0; k < 4; ++k) {
            r[k] = imageLoad(refSurface[k], p);
            t[k] = imageLoad(testSurface[k], p);
        }
        int cls = r[1].a > 0.5 ? 1 : 0;
        acc[ATTRS * PER_ATTR] += 1.0;
        acc[ATTRS * PER_ATTR + 3 + (cls == 1 ? 0 : 1)] += 1.0;
        bool ok;
        double angle = normalAngleDeg(r[0].xyz, t[0].xyz, ok);
        if (ok && finiteD(angle)) add(0, cls, angle, 0.0);
        else skip(0);
        colour(1, cls, r[1].rgb, t[1].rgb);
        colour(2, cls, r[2].rgb, t[2].rgb);
        colour(3, cls, r[3].rgb, t[3].rgb);
        scalar(4, cls, r[0].a, t[0].a);
        scalar(5, cls, r[1].a, t[1].a);
        scalar(6, cls, r[2].a, t[2].a);
        double rd = r[3].a, td = t[3].a;
        double e = abs(td - rd) / rd;
        if (rd > 0.0 && finiteD(rd) && finiteD(e)) add(7, cls, e, 0.0);
        else skip(7);
    }
    for (int f = 0; f < FIELDS; ++f) partials[invocation() * FIELDS + f] = acc[f];
}
