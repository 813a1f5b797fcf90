#version 450
#extension GL_GOOGLE_include_directive : require
// The material layers' errors (issue 40; measure/run_metrics.h "Material layers" and
// measure/layer_classes.h define them, the CPU oracle; tests/evaluate/gpu_evaluator_test holds
// the two together). Bound: the decoded layers as four RGBA32F images per side (refLayer,
// testLayer: coat normal + coat, sheen colour + sheen roughness, anisotropy direction + strength,
// coat roughness; render/decode_pass.comp.glsl's GBL_LAYERS vec4s), beside the surfaces.
// Over the pixels covered in both renders (HDR alpha):
// mode 0: each layer attribute over the pixels whose reference carries its layer, per material
//   class (reference metallic > 0.5: metal), as eval_attributes.comp.glsl's fields (PER_ATTR per
//   attribute: dielectric count, sum, sum of squares, max, colour d^2; metal the same; skipped),
//   histograms EVAL_LAYER_HIST + 2 a + class; then per layer class (coated, sheen, anisotropic,
//   plain; a pixel may be in several): pixels, relative luminance error, linear d^2, noise /
//   max(Y, floor) (flags bit 1: the noise plane u0; f3: the floor), as eval_image.comp.glsl's.
// mode 1: LDR-FLIP (plane u0) summed per layer class: 4 fields.
#include "eval_common.glsl"
#include "eval_attribute_math.glsl"

#define LATTRS 7
#define PER_ATTR 11
#define CLASS_AT (LATTRS * PER_ATTR)  // 77: 4 classes x (pixels, rel, d^2, noise)
#define FIELDS (CLASS_AT + 16)

const uint kCoat = 1u, kSheen = 2u, kAniso = 4u;  // layer_classes.h kCarries*

// layer_classes.h layerBitsAt, from the reference's layer images.
uint layerBits(vec4 l0, vec4 l1, vec4 l2) {
    uint bits = 0u;
    if (l0.w > 0.0) bits |= kCoat;
    if (l1.r > 0.0 || l1.g > 0.0 || l1.b > 0.0) bits |= kSheen;
    if (l2.w > 0.0) bits |= kAniso;
    return bits;
}
bool inClass(uint bits, int c) { return c == 3 ? bits == 0u : (bits & (1u << uint(c))) != 0u; }

double acc[FIELDS];
void add(int a, int cls, double e, double colorSq) {
    int b = a * PER_ATTR + cls * 5;
    acc[b] += 1.0;
    acc[b + 1] += e;
    acc[b + 2] += e * e;
    acc[b + 3] = max(acc[b + 3], e);
    acc[b + 4] += colorSq;
    histAdd(EVAL_LAYER_HIST + uint(a * 2 + cls), float(e));
}
void skip(int a) { acc[a * PER_ATTR + 10] += 1.0; }
bool finiteD(double v) { return !isnan(float(v)) && !isinf(float(v)); }
void scalar(int a, int cls, float r, float t) {
    double e = abs(double(t) - double(r));
    if (finiteD(e)) add(a, cls, e, 0.0);
    else skip(a);
}
// layer_classes.h effectiveCoatNormal: 0 is the base normal.
vec3 coatNormalOf(vec3 coatN, vec3 n) { return coatN != vec3(0.0) ? coatN : n; }
// layer_classes.h anisotropyDirectionErrorDeg: the angle between the tangent lines, each made
// orthogonal to its own normal; ok = false where either vanishes.
bool projectedTangent(vec3 t, vec3 n, out dvec3 o) {
    dvec3 dn = dvec3(n), dt = dvec3(t);
    double nn = dot(dn, dn);
    double k = nn > 0.0 ? dot(dn, dt) / nn : 0.0;
    o = dt - k * dn;
    double len2 = dot(o, o);
    return finiteD(len2) && len2 > 1e-12;
}
double tangentLineAngleDeg(vec3 ta, vec3 na, vec3 tb, vec3 nb, out bool ok) {
    dvec3 a, b;
    ok = projectedTangent(ta, na, a) && projectedTangent(tb, nb, b);
    if (!ok) return 0.0;
    dvec3 c = cross(a, b);
    double deg = double(atan(float(sqrt(dot(c, c))), float(abs(dot(a, b))))) * (180.0 / PI);
    ok = finiteD(deg);
    return ok ? deg : 0.0;
}

void flipSums() {
    double sums[4] = double[4](0.0, 0.0, 0.0, 0.0);
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    for (uint i = countedBegin() + invocation(); i < countedEnd(); i += total) {
        ivec2 p = ivec2(i % pc.width, i / pc.width);
        if (imageLoad(refHdr, p).a == 0.0 || imageLoad(testHdr, p).a == 0.0) continue;
        uint bits = layerBits(imageLoad(refLayer[0], p), imageLoad(refLayer[1], p), imageLoad(refLayer[2], p));
        float v = planes[pc.u0].v[i];
        for (int c = 0; c < 4; ++c)
            if (inClass(bits, c)) sums[c] += v;
    }
    for (int c = 0; c < 4; ++c) partials[invocation() * 4 + c] = sums[c];
}

void main() {
    if (pc.mode == 1u) {
        flipSums();
        return;
    }
    const uint total = gl_NumWorkGroups.x * EVAL_GROUP;
    const float floorY = pc.f3;
    for (int f = 0; f < FIELDS; ++f) acc[f] = 0.0;
    for (uint i = countedBegin() + invocation(); i < countedEnd(); i += total) {
        ivec2 p = ivec2(i % pc.width, i / pc.width);
        vec4 rh = imageLoad(refHdr, p), th = imageLoad(testHdr, p);
        if (rh.a == 0.0 || th.a == 0.0) continue;
        vec4 r[4], t[4];
        for (int k = 0; k < 4; ++k) {
            r[k] = imageLoad(refLayer[k], p);
            t[k] = imageLoad(testLayer[k], p);
        }
        vec3 rn = imageLoad(refSurface[0], p).xyz, tn = imageLoad(testSurface[0], p).xyz;
        int cls = imageLoad(refSurface[1], p).a > 0.5 ? 1 : 0;
        uint bits = layerBits(r[0], r[1], r[2]);
        bool ok;
        if ((bits & kCoat) != 0u) {
            scalar(0, cls, r[0].w, t[0].w);
            scalar(1, cls, r[3].x, t[3].x);
            double angle = normalAngleDeg(coatNormalOf(r[0].xyz, rn), coatNormalOf(t[0].xyz, tn), ok);
            if (ok && finiteD(angle)) add(2, cls, angle, 0.0);
            else skip(2);
        }
        if ((bits & kSheen) != 0u) {
            dvec3 d = dvec3(t[1].rgb) - dvec3(r[1].rgb);
            double e = (r[1].rgb == t[1].rgb) ? 0.0 : deltaE2000(labOf(r[1].rgb), labOf(t[1].rgb));
            if (finiteD(e)) add(3, cls, e, dot(d, d));
            else skip(3);
            scalar(4, cls, r[1].a, t[1].a);
        }
        if ((bits & kAniso) != 0u) {
            scalar(5, cls, r[2].w, t[2].w);
            double angle = tangentLineAngleDeg(r[2].xyz, rn, t[2].xyz, tn, ok);
            if (ok) add(6, cls, angle, 0.0);
            else skip(6);
        }
        // The image per layer class (eval_image.comp.glsl's class sums).
        double yr = 0.2126 * double(rh.r) + 0.7152 * double(rh.g) + 0.0722 * double(rh.b);
        double yt = 0.2126 * double(th.r) + 0.7152 * double(th.g) + 0.0722 * double(th.b);
        bool finiteY = !isnan(float(yr)) && !isinf(float(yr));
        double rel = abs(yt - yr) / max(finiteY ? yr : 0.0, double(floorY));
        float relF = isnan(float(rel)) || isinf(float(rel)) ? uintBitsToFloat(0x7FC00000u) : float(rel);
        double sq = 0.0;
        for (int c = 0; c < 3; ++c) {
            double d = double(th[c]) - double(rh[c]);
            sq += d * d;
        }
        double noise = (pc.flags & 2u) != 0u ? double(planes[pc.u0].v[i]) / max(finiteY ? yr : 0.0, double(floorY)) : 0.0;
        for (int c = 0; c < 4; ++c) {
            if (!inClass(bits, c)) continue;
            int b = CLASS_AT + 4 * c;
            acc[b] += 1.0;
            acc[b + 1] += isnan(relF) ? 0.0 : double(relF);
            acc[b + 2] += sq;
            acc[b + 3] += noise;
        }
    }
    for (int f = 0; f < FIELDS; ++f) partials[invocation() * FIELDS + f] = acc[f];
}
