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
#define PI 3.14159265358979323846

double normalAngleDeg(vec3 a, vec3 b, out bool ok) {  // measure/metrics.cpp normalAngleDeg
    dvec3 da = dvec3(a), db = dvec3(b);
    double la = dot(da, da), lb = dot(db, db);
    ok = !isnan(float(la)) && !isinf(float(la)) && !isnan(float(lb)) && !isinf(float(lb)) && la > 0.0 && lb > 0.0;
    if (!ok) return 0.0;
    dvec3 c = cross(da, db);
    return double(atan(float(sqrt(dot(c, c))), float(dot(da, db)))) * (180.0 / PI);
}

// Linear sRGB -> CIELAB (D65), image/color_difference.cpp's matrix and white, in double (a small
// colour error is a difference of two Lab values near 50: float would cancel most of its digits).
double cbrtD(double t) {  // float guess, two Halley steps y <- y (y^3 + 2t) / (2 y^3 + t) in double
    double y = double(pow(float(t), 1.0 / 3.0));
    for (int k = 0; k < 2; ++k) {
        double y3 = y * y * y;
        y = y * (y3 + 2.0 * t) / (2.0 * y3 + t);
    }
    return y;
}
dvec3 labOf(vec3 rgbF) {
    const dmat3 m = transpose(dmat3(0.4124564LF, 0.3575761LF, 0.1804375LF, 0.2126729LF, 0.7151522LF, 0.0721750LF,
                                    0.0193339LF, 0.1191920LF, 0.9503041LF));
    dvec3 xyz = m * dvec3(rgbF);
    dvec3 w = dvec3(0.4124564LF + 0.3575761LF + 0.1804375LF, 0.2126729LF + 0.7151522LF + 0.0721750LF,
                    0.0193339LF + 0.1191920LF + 0.9503041LF);
    dvec3 t = xyz / w, f;
    const double d = 6.0LF / 29.0LF;
    for (int i = 0; i < 3; ++i) f[i] = t[i] > d * d * d ? cbrtD(t[i]) : t[i] / (3.0LF * d * d) + 4.0LF / 29.0LF;
    return dvec3(116.0LF * f.y - 16.0LF, 500.0LF * (f.x - f.y), 200.0LF * (f.y - f.z));
}
double pow7(double x) { double x2 = x * x; return x2 * x2 * x2 * x; }
float hueDeg(double b, double ap) {
    if (b == 0.0 && ap == 0.0) return 0.0;
    float h = degrees(atan(float(b), float(ap)));
    return h < 0.0 ? h + 360.0 : h;
}
// CIEDE2000, Sharma, Wu & Dalal (2005) eqs. (2)-(22), kL = kC = kH = 1 (color_difference.cpp).
// Differences in double; the hue difference from the cross and dot products of (a', b') (equal to
// h2' - h1' wrapped to (-180, 180], without cancelling); only weights use float trigonometry.
double deltaE2000(dvec3 p1, dvec3 p2) {
    double C1 = sqrt(p1.y * p1.y + p1.z * p1.z), C2 = sqrt(p2.y * p2.y + p2.z * p2.z);
    double Cbar7 = pow7(0.5 * (C1 + C2));
    double G = 0.5 * (1.0 - sqrt(Cbar7 / (Cbar7 + pow7(25.0))));
    double a1p = (1.0 + G) * p1.y, a2p = (1.0 + G) * p2.y;
    double C1p = sqrt(a1p * a1p + p1.z * p1.z), C2p = sqrt(a2p * a2p + p2.z * p2.z);
    float h1p = hueDeg(p1.z, a1p), h2p = hueDeg(p2.z, a2p);
    double dLp = p2.x - p1.x, dCp = C2p - C1p, CpProd = C1p * C2p;
    double dHp = 0.0;
    if (CpProd != 0.0) {
        double crossAB = a1p * p2.z - p1.z * a2p, dotAB = a1p * a2p + p1.z * p2.z;
        float dhp = atan(float(crossAB), float(dotAB));  // radians
        dHp = 2.0 * sqrt(CpProd) * double(sin(0.5 * dhp));
    }
    double Lbarp = 0.5 * (p1.x + p2.x), Cbarp = 0.5 * (C1p + C2p);
    float hbarp = h1p + h2p;
    if (CpProd != 0.0) {
        if (abs(h1p - h2p) <= 180.0) hbarp = 0.5 * (h1p + h2p);
        else if (h1p + h2p < 360.0) hbarp = 0.5 * (h1p + h2p + 360.0);
        else hbarp = 0.5 * (h1p + h2p - 360.0);
    }
    double T = 1.0 - 0.17 * cos(radians(hbarp - 30.0)) + 0.24 * cos(radians(2.0 * hbarp)) +
               0.32 * cos(radians(3.0 * hbarp + 6.0)) - 0.20 * cos(radians(4.0 * hbarp - 63.0));
    float dTheta = 30.0 * exp(-((hbarp - 275.0) / 25.0) * ((hbarp - 275.0) / 25.0));
    double Cbarp7 = pow7(Cbarp);
    double RC = 2.0 * sqrt(Cbarp7 / (Cbarp7 + pow7(25.0)));
    double L50 = (Lbarp - 50.0) * (Lbarp - 50.0);
    double SL = 1.0 + 0.015 * L50 / sqrt(20.0 + L50), SC = 1.0 + 0.045 * Cbarp, SH = 1.0 + 0.015 * Cbarp * T;
    double RT = -double(sin(radians(2.0 * dTheta))) * RC;
    double tL = dLp / SL, tC = dCp / SC, tH = dHp / SH;
    return sqrt(max(0.0LF, tL * tL + tC * tC + tH * tH + RT * tC * tH));
}

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
