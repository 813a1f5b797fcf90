#include "color_difference.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace gbl {
namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;

// Linear sRGB -> XYZ (D65), IEC 61966-2-1 primaries and white, to 7 digits.
constexpr Mat3 kRgbToXyz = {{{0.4124564, 0.3575761, 0.1804375},
                             {0.2126729, 0.7151522, 0.0721750},
                             {0.0193339, 0.1191920, 0.9503041}}};

Mat3 invert(const Mat3& m) {
    const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    const double s = 1.0 / det;
    Mat3 r{};
    r[0][0] = c00 * s;
    r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * s;
    r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * s;
    r[1][0] = c01 * s;
    r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * s;
    r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * s;
    r[2][0] = c02 * s;
    r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * s;
    r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * s;
    return r;
}

const Mat3& xyzToRgbMatrix() {
    static const Mat3 inv = invert(kRgbToXyz);
    return inv;
}

// CIE 15 f(t) and its inverse, delta = 6/29.
double labF(double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

double labFInv(double f) {
    constexpr double d = 6.0 / 29.0;
    return f > d ? f * f * f : 3.0 * d * d * (f - 4.0 / 29.0);
}

constexpr double kDeg = 180.0 / std::numbers::pi;
constexpr double kRad = std::numbers::pi / 180.0;

double pow7(double x) {
    const double x2 = x * x;
    return x2 * x2 * x2 * x;
}

}  // namespace

Xyz d65White() { return linearSrgbToXyz(1.0, 1.0, 1.0); }

Xyz linearSrgbToXyz(double r, double g, double b) {
    const Mat3& m = kRgbToXyz;
    return {m[0][0] * r + m[0][1] * g + m[0][2] * b, m[1][0] * r + m[1][1] * g + m[1][2] * b,
            m[2][0] * r + m[2][1] * g + m[2][2] * b};
}

void xyzToLinearSrgb(const Xyz& c, double& r, double& g, double& b) {
    const Mat3& m = xyzToRgbMatrix();
    r = m[0][0] * c.X + m[0][1] * c.Y + m[0][2] * c.Z;
    g = m[1][0] * c.X + m[1][1] * c.Y + m[1][2] * c.Z;
    b = m[2][0] * c.X + m[2][1] * c.Y + m[2][2] * c.Z;
}

Lab xyzToLab(const Xyz& c) {
    const Xyz w = d65White();
    const double fx = labF(c.X / w.X), fy = labF(c.Y / w.Y), fz = labF(c.Z / w.Z);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Xyz labToXyz(const Lab& lab) {
    const Xyz w = d65White();
    const double fy = (lab.L + 16.0) / 116.0;
    const double fx = fy + lab.a / 500.0;
    const double fz = fy - lab.b / 200.0;
    return {w.X * labFInv(fx), w.Y * labFInv(fy), w.Z * labFInv(fz)};
}

Lab linearSrgbToLab(double r, double g, double b) { return xyzToLab(linearSrgbToXyz(r, g, b)); }

double srgbEncode(double x) {
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

double srgbDecode(double x) {
    return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
}

// Sharma, Wu & Dalal (2005), eqs. (2)-(22). Angles in degrees as in the paper.
double deltaE2000(const Lab& p1, const Lab& p2, double kL, double kC, double kH) {
    // Eqs. (2)-(7): a' with the G factor, C', h'.
    const double C1 = std::hypot(p1.a, p1.b);
    const double C2 = std::hypot(p2.a, p2.b);
    const double Cbar = 0.5 * (C1 + C2);
    const double Cbar7 = pow7(Cbar);
    const double G = 0.5 * (1.0 - std::sqrt(Cbar7 / (Cbar7 + pow7(25.0))));
    const double a1p = (1.0 + G) * p1.a;
    const double a2p = (1.0 + G) * p2.a;
    const double C1p = std::hypot(a1p, p1.b);
    const double C2p = std::hypot(a2p, p2.b);
    auto hueDeg = [](double b, double ap) {
        if (b == 0.0 && ap == 0.0) return 0.0;
        double h = std::atan2(b, ap) * kDeg;
        if (h < 0.0) h += 360.0;
        return h;
    };
    const double h1p = hueDeg(p1.b, a1p);
    const double h2p = hueDeg(p2.b, a2p);

    // Eqs. (8)-(11): differences.
    const double dLp = p2.L - p1.L;
    const double dCp = C2p - C1p;
    const double CpProd = C1p * C2p;
    double dhp = 0.0;
    if (CpProd != 0.0) {
        dhp = h2p - h1p;
        if (dhp > 180.0) dhp -= 360.0;
        else if (dhp < -180.0) dhp += 360.0;
    }
    const double dHp = 2.0 * std::sqrt(CpProd) * std::sin(0.5 * dhp * kRad);

    // Eqs. (12)-(22): means, weighting functions, rotation term.
    const double Lbarp = 0.5 * (p1.L + p2.L);
    const double Cbarp = 0.5 * (C1p + C2p);
    double hbarp = h1p + h2p;
    if (CpProd != 0.0) {
        if (std::abs(h1p - h2p) <= 180.0) hbarp = 0.5 * (h1p + h2p);
        else if (h1p + h2p < 360.0) hbarp = 0.5 * (h1p + h2p + 360.0);
        else hbarp = 0.5 * (h1p + h2p - 360.0);
    }
    const double T = 1.0 - 0.17 * std::cos((hbarp - 30.0) * kRad) + 0.24 * std::cos(2.0 * hbarp * kRad) +
                     0.32 * std::cos((3.0 * hbarp + 6.0) * kRad) - 0.20 * std::cos((4.0 * hbarp - 63.0) * kRad);
    const double dTheta = 30.0 * std::exp(-((hbarp - 275.0) / 25.0) * ((hbarp - 275.0) / 25.0));
    const double Cbarp7 = pow7(Cbarp);
    const double RC = 2.0 * std::sqrt(Cbarp7 / (Cbarp7 + pow7(25.0)));
    const double L50 = (Lbarp - 50.0) * (Lbarp - 50.0);
    const double SL = 1.0 + 0.015 * L50 / std::sqrt(20.0 + L50);
    const double SC = 1.0 + 0.045 * Cbarp;
    const double SH = 1.0 + 0.015 * Cbarp * T;
    const double RT = -std::sin(2.0 * dTheta * kRad) * RC;

    const double tL = dLp / (kL * SL);
    const double tC = dCp / (kC * SC);
    const double tH = dHp / (kH * SH);
    // The sum is >= 0 in exact arithmetic (Sharma et al. 2005, Sec. 3); guard the rounding at 0.
    return std::sqrt(std::max(0.0, tL * tL + tC * tC + tH * tH + RT * tC * tH));
}

}  // namespace gbl
