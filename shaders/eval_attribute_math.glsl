// The attribute errors' per-pixel maths, shared by eval_attributes.comp.glsl and
// eval_layers.comp.glsl: the normal angle (measure/metrics.cpp normalAngleDeg) and CIEDE2000 of
// linear sRGB colours (image/color_difference.cpp), as the CPU computes them (see
// gpu_evaluator.h for where float maths makes them differ).
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

