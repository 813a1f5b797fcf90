#include "flip.h"

#include "flip_pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <string>

#include "color_difference.h"
#include "error.h"
#include "float_sort.h"
#include "metrics.h"
#include "parallel_for.h"
#include "simd_clones.h"

// Equation numbers below are those of the FLIP paper (HPG 2020) unless marked [HDR], which
// refers to the HDR-FLIP paper (Eurographics 2021 short). Every comment also restates the
// formula it implements, so each step can be checked against the paper even if a number is
// off. Where the paper fixes a constant, it is written here once, with the paper's name.

namespace gbl {
namespace flip_pipeline {

constexpr double kPi = std::numbers::pi;

// ---- Constants from the paper -------------------------------------------------------------------

// Contrast sensitivity functions, eq. (2) (frequency domain S(f) = a1 exp(-b1 f^2) + a2 exp(-b2 f^2)),
// one per opponent channel: achromatic (A), red-green (RG), blue-yellow (BY).
struct CsfParams {
    double a1, b1, a2, b2;
};
constexpr CsfParams kCsfA = {1.0, 0.0047, 0.0, 1.0e-5};
constexpr CsfParams kCsfRG = {1.0, 0.0053, 0.0, 1.0e-5};
constexpr CsfParams kCsfBY = {34.1, 0.04, 13.5, 0.025};

// Colour error remapping, eqs. (6)-(8): exponent q_c, error-map breakpoints p_c and p_t.
constexpr double kQc = 0.7;
constexpr double kPc = 0.4;
constexpr double kPt = 0.95;

// Feature pipeline: the edge/point width w in degrees, the Gaussian's
// sigma = 0.5 * w * p (pixels), and the feature exponent q_f, eq. (9).
constexpr double kFeatureWidthDeg = 0.082;
constexpr double kQf = 0.5;

// ---- Colour transforms (float, per pixel) ----------------------------------------------------

struct ColorConsts {
    float m[3][3];     // linear sRGB -> XYZ
    float mi[3][3];    // XYZ -> linear sRGB
    float wx, wy, wz;  // D65 white (XYZ of RGB (1,1,1)) and its reciprocals
    float iwx, iwy, iwz;
};

const ColorConsts& colorConsts() {
    static const ColorConsts c = [] {
        ColorConsts k{};
        const double basis[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        for (int j = 0; j < 3; ++j) {
            const Xyz col = linearSrgbToXyz(basis[j][0], basis[j][1], basis[j][2]);
            k.m[0][j] = float(col.X);
            k.m[1][j] = float(col.Y);
            k.m[2][j] = float(col.Z);
            Xyz e{basis[j][0], basis[j][1], basis[j][2]};
            double r, g, b;
            xyzToLinearSrgb(e, r, g, b);
            k.mi[0][j] = float(r);
            k.mi[1][j] = float(g);
            k.mi[2][j] = float(b);
        }
        const Xyz w = d65White();
        k.wx = float(w.X), k.wy = float(w.Y), k.wz = float(w.Z);
        k.iwx = float(1.0 / w.X), k.iwy = float(1.0 / w.Y), k.iwz = float(1.0 / w.Z);
        return k;
    }();
    return c;
}

// Cube root of t > 0 (here t > (6/29)^3): a bit-level first guess (about 5% off), then two
// Halley steps y <- y (y^3 + 2t) / (2 y^3 + t) in double (cubic convergence: 5e-2 -> 1e-4 ->
// 1e-12), rounded to float. About 3x faster than glibc's cbrtf, and as accurate after rounding.
GBL_CLONE_INLINE float cubeRoot(float t) {
    uint32_t bits;
    std::memcpy(&bits, &t, sizeof bits);
    bits = bits / 3u + 0x2A514067u;  // exponent / 3, re-biased
    float g;
    std::memcpy(&g, &bits, sizeof g);
    const double x = t;
    double y = g;
    double y3 = y * y * y;
    y = y * (y3 + 2.0 * x) / (2.0 * y3 + x);
    y3 = y * y * y;
    y = y * (y3 + 2.0 * x) / (2.0 * y3 + x);
    return float(y);
}

// CIE 15 f(t) of CIELAB.
GBL_CLONE_INLINE float labF(float t) {
    constexpr float d3 = float((6.0 / 29.0) * (6.0 / 29.0) * (6.0 / 29.0));
    constexpr float s = float(1.0 / (3.0 * (6.0 / 29.0) * (6.0 / 29.0)));
    constexpr float o = float(4.0 / 29.0);
    const float root = cubeRoot(t);  // both sides computed: a select, so the loop vectorises
    const float line = t * s + o;
    return t > d3 ? root : line;
}

inline float srgbToLinearF(float v) {
    v = clamp01(v);
    return v <= 0.04045f ? v * float(1.0 / 12.92) : std::pow((v + 0.055f) * float(1.0 / 1.055), 2.4f);
}

// Hunt-adjusted CIELAB (eq. (4): a_h = 0.01 L a, b_h = 0.01 L b) of a linear RGB colour.
struct HuntLab {
    float L, a, b;
};

GBL_CLONE_INLINE HuntLab linearRgbToHuntLab(float r, float g, float b, const ColorConsts& k) {
    const float X = k.m[0][0] * r + k.m[0][1] * g + k.m[0][2] * b;
    const float Y = k.m[1][0] * r + k.m[1][1] * g + k.m[1][2] * b;
    const float Z = k.m[2][0] * r + k.m[2][1] * g + k.m[2][2] * b;
    const float fx = labF(X * k.iwx), fy = labF(Y * k.iwy), fz = labF(Z * k.iwz);
    const float L = 116.0f * fy - 16.0f;
    const float a = 500.0f * (fx - fy);
    const float bb = 200.0f * (fy - fz);
    return {L, 0.01f * L * a, 0.01f * L * bb};
}

// HyAB distance (eq. (5)): |dL| + sqrt(da^2 + db^2), on Hunt-adjusted values.
inline float hyab(const HuntLab& p, const HuntLab& q) {
    const float da = p.a - q.a, db = p.b - q.b;
    return std::abs(p.L - q.L) + std::sqrt(da * da + db * db);
}

// c_max = (HyAB(Hunt(green), Hunt(blue)))^q_c, eq. (6): the largest colour difference, between
// pure green and pure blue. Computed in double from the same colour transforms.
double maxColorDifference() {
    auto hunt = [](double r, double g, double b) {
        const Lab l = linearSrgbToLab(r, g, b);
        return Lab{l.L, 0.01 * l.L * l.a, 0.01 * l.L * l.b};
    };
    const Lab g = hunt(0, 1, 0), b = hunt(0, 0, 1);
    const double d = std::abs(g.L - b.L) + std::hypot(g.a - b.a, g.b - b.b);
    return std::pow(d, kQc);
}


// One term of the spatial-domain CSF, eq. (3): a sqrt(pi/b) exp(-pi^2 x^2 / b), x in degrees.
// Returns the 1D factor exp(-pi^2 x^2 / b) over [-r, r] (so the 2D term is
// a sqrt(pi/b) e(x) e(y)) and its sum.
std::vector<double> csfFactor(double b, int radius, double ppd, double& sum) {
    std::vector<double> e(size_t(2 * radius + 1));
    sum = 0.0;
    for (int i = -radius; i <= radius; ++i) {
        const double x = i / ppd;
        e[size_t(i + radius)] = std::exp(-kPi * kPi * x * x / b);
        sum += e[size_t(i + radius)];
    }
    return e;
}

std::vector<float> normalized(const std::vector<double>& v, double sum) {
    std::vector<float> out(v.size());
    for (size_t i = 0; i < v.size(); ++i) out[i] = float(v[i] / sum);
    return out;
}

Kernels makeKernels(double ppd) {
    Kernels k;
    // CSF filter radius: 3 standard deviations of the widest Gaussian term,
    // r = ceil(3 sqrt(b_max / (2 pi^2)) p), b_max the largest b over all channels (0.04, BY).
    const double bMax = std::max({kCsfA.b1, kCsfA.b2, kCsfRG.b1, kCsfRG.b2, kCsfBY.b1, kCsfBY.b2});
    k.csfRadius = int(std::ceil(3.0 * std::sqrt(bMax / (2.0 * kPi * kPi)) * ppd));
    const int r = k.csfRadius;

    // The 2D filter is S(x, y) = sum_i a_i sqrt(pi/b_i) exp(-pi^2 (x^2 + y^2) / b_i) over the
    // (2r+1)^2 window, normalised to sum 1. Each term is separable; A and RG have a2 = 0.
    double sA = 0, sRG = 0, s1 = 0, s2 = 0;
    const std::vector<double> eA = csfFactor(kCsfA.b1, r, ppd, sA);
    const std::vector<double> eRG = csfFactor(kCsfRG.b1, r, ppd, sRG);
    const std::vector<double> e1 = csfFactor(kCsfBY.b1, r, ppd, s1);
    const std::vector<double> e2 = csfFactor(kCsfBY.b2, r, ppd, s2);
    k.csfA = normalized(eA, sA);
    k.csfRG = normalized(eRG, sRG);
    k.csfBY1 = normalized(e1, s1);
    k.csfBY2 = normalized(e2, s2);
    const double c1 = kCsfBY.a1 * std::sqrt(kPi / kCsfBY.b1) * s1 * s1;  // 2D sum of term 1
    const double c2 = kCsfBY.a2 * std::sqrt(kPi / kCsfBY.b2) * s2 * s2;  // 2D sum of term 2
    k.wBY1 = float(c1 / (c1 + c2));
    k.wBY2 = float(c2 / (c1 + c2));

    // Feature detectors: sigma = 0.5 w p pixels, radius ceil(3 sigma).
    // Edge: first partial derivative of the Gaussian, -x g(x, y); point: second partial
    // derivative, (x^2/sigma^2 - 1) g(x, y). Each 2D filter is normalised so that its positive
    // weights sum to 1 and its negative weights to -1. Both are separable, d(x) g(y) and
    // p(x) g(y); the sign split depends on x only, so normalising the x factor by its positive
    // and negative sums and the y factor by its sum gives the same normalised 2D filter.
    const double sigma = 0.5 * kFeatureWidthDeg * ppd;
    k.featRadius = int(std::ceil(3.0 * sigma));
    const int fr = k.featRadius;
    std::vector<double> g(size_t(2 * fr + 1)), d(g.size()), p(g.size());
    double gs = 0, dPos = 0, dNeg = 0, pPos = 0, pNeg = 0;
    for (int i = -fr; i <= fr; ++i) {
        const double x = i;
        const double gi = std::exp(-x * x / (2.0 * sigma * sigma));
        const size_t j = size_t(i + fr);
        g[j] = gi;
        d[j] = -x * gi;
        p[j] = (x * x / (sigma * sigma) - 1.0) * gi;
        gs += gi;
        (d[j] > 0 ? dPos : dNeg) += d[j];
        (p[j] > 0 ? pPos : pNeg) += p[j];
    }
    k.gauss.resize(g.size());
    k.edge.resize(g.size());
    k.point.resize(g.size());
    for (size_t j = 0; j < g.size(); ++j) {
        k.gauss[j] = float(g[j] / gs);
        k.edge[j] = float(d[j] > 0 ? d[j] / dPos : (d[j] < 0 ? d[j] / -dNeg : 0.0));
        k.point[j] = float(p[j] > 0 ? p[j] / pPos : (p[j] < 0 ? p[j] / -pNeg : 0.0));
    }
    return k;
}

// ---- Separable filtering (clamp-to-edge), correlation order ------------------------------------

// a[x] += k * src[x]: one tap of a filter over a row. The per-pixel loops below are compiled for
// AVX2 too (simd_clones.h): lanes only widen the loop over x, each sum still adds its taps in the
// same order with the same roundings (no FMA contraction), so the maps are unchanged.
GBL_SIMD_CLONES void addTap(float* __restrict a, const float* __restrict src, float k, int w) {
    for (int x = 0; x < w; ++x) a[x] += k * src[x];
}

// Four taps in one sweep: each a[x] still gets k0 s0, then k1 s1, k2 s2, k3 s3 added, each
// product and sum rounded as addTap's four calls would round them, so the planes are bit for bit
// the same; the sum stays in a register between the taps. One tap per sweep loaded and stored
// the sum once per tap, and addTap was FLIP's largest share of a compare's CPU samples.
GBL_SIMD_CLONES void addTaps4(float* __restrict a, const float* __restrict s0, const float* __restrict s1,
                              const float* __restrict s2, const float* __restrict s3, const float* k, int w) {
    const float k0 = k[0], k1 = k[1], k2 = k[2], k3 = k[3];
    for (int x = 0; x < w; ++x) {
        float v = a[x];
        v += k0 * s0[x];
        v += k1 * s1[x];
        v += k2 * s2[x];
        v += k3 * s3[x];
        a[x] = v;
    }
}

// a += sum over taps j of k[j] * src(j), in tap order; src(j) is tap j's source row.
template <class Source>
void addTaps(float* a, const std::vector<float>& k, int w, Source&& src) {
    size_t j = 0;
    for (; j + 4 <= k.size(); j += 4) addTaps4(a, src(j), src(j + 1), src(j + 2), src(j + 3), k.data() + j, w);
    for (; j < k.size(); ++j) addTap(a, src(j), k[j], w);
}

// out(x, y) = sum_j k[j] in(clamp(x + j - r), y).
void filterRows(const float* in, float* out, int w, int h, const std::vector<float>& k) {
    const int r = int(k.size() / 2);
    forChunks(size_t(h), kMinRowsPerThread, [&](size_t y0, size_t y1) {
        std::vector<float> pad(static_cast<size_t>(w + 2 * r));
        std::vector<float> acc(static_cast<size_t>(w));
        for (size_t y = y0; y < y1; ++y) {
            const float* row = in + y * size_t(w);
            for (int i = 0; i < w + 2 * r; ++i) pad[size_t(i)] = row[std::clamp(i - r, 0, w - 1)];
            std::fill(acc.begin(), acc.end(), 0.0f);
            addTaps(acc.data(), k, w, [&](size_t j) { return pad.data() + j; });
            std::copy(acc.begin(), acc.end(), out + y * size_t(w));
        }
    });
}

// out(x, y) = sum_j k[j] in(x, clamp(y + j - r)).
void filterCols(const float* in, float* out, int w, int h, const std::vector<float>& k) {
    const int r = int(k.size() / 2);
    forChunks(size_t(h), kMinRowsPerThread, [&](size_t y0, size_t y1) {
        for (size_t y = y0; y < y1; ++y) {
            float* o = out + y * size_t(w);
            std::fill(o, o + w, 0.0f);
            addTaps(o, k, w, [&](size_t j) { return in + size_t(std::clamp(int(y) + int(j) - r, 0, h - 1)) * size_t(w); });
        }
    });
}

// ---- The per-image pipeline ------------------------------------------------------------------


// Linear RGB -> XYZ -> YyCxCz (the colour pipeline's opponent space, after Zhang & Wandell's
// S-CIELAB): Yy = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn). The feature
// pipeline uses the achromatic channel normalised to [0,1], (Yy + 16) / 116 = Y / Yn (lum).
GBL_SIMD_CLONES void rgbToOpponent(const float* __restrict R, const float* __restrict G, const float* __restrict B,
                   float* __restrict oy, float* __restrict ox, float* __restrict oz, float* __restrict ol, size_t n,
                   const ColorConsts& cc) {
    const ColorConsts k = cc;
    for (size_t i = 0; i < n; ++i) {
        const float r = R[i], g = G[i], b = B[i];
        const float X = (k.m[0][0] * r + k.m[0][1] * g + k.m[0][2] * b) * k.iwx;
        const float Y = (k.m[1][0] * r + k.m[1][1] * g + k.m[1][2] * b) * k.iwy;
        const float Z = (k.m[2][0] * r + k.m[2][1] * g + k.m[2][2] * b) * k.iwz;
        oy[i] = 116.0f * Y - 16.0f;
        ox[i] = 500.0f * (X - Y);
        oz[i] = 200.0f * (Y - Z);
        ol[i] = Y;
    }
}

// Filtered YyCxCz -> XYZ -> linear RGB, clamped to [0,1] (the filtered colour may leave the
// gamut), in place: the planes y, x, z become r, g, b.
GBL_SIMD_CLONES void opponentToClampedRgb(float* __restrict y, float* __restrict x, float* __restrict z, size_t n,
                          const ColorConsts& cc) {
    const ColorConsts k = cc;
    for (size_t i = 0; i < n; ++i) {
        const float Yr = (y[i] + 16.0f) * float(1.0 / 116.0);
        const float X = (x[i] * (1.0f / 500.0f) + Yr) * k.wx;
        const float Y = Yr * k.wy;
        const float Z = (Yr - z[i] * (1.0f / 200.0f)) * k.wz;
        // (Filtered values are finite, so min/max clamping is enough here.)
        y[i] = std::min(std::max(k.mi[0][0] * X + k.mi[0][1] * Y + k.mi[0][2] * Z, 0.0f), 1.0f);
        x[i] = std::min(std::max(k.mi[1][0] * X + k.mi[1][1] * Y + k.mi[1][2] * Z, 0.0f), 1.0f);
        z[i] = std::min(std::max(k.mi[2][0] * X + k.mi[2][1] * Y + k.mi[2][2] * Z, 0.0f), 1.0f);
    }
}

// Linear RGB -> CIELAB with the Hunt adjustment, eq. (4).
GBL_SIMD_CLONES void rgbToHuntLab(const float* __restrict R, const float* __restrict G, const float* __restrict B,
                  float* __restrict oL, float* __restrict oa, float* __restrict ob, size_t n, const ColorConsts& cc) {
    const ColorConsts k = cc;
    for (size_t i = 0; i < n; ++i) {
        const HuntLab lab = linearRgbToHuntLab(R[i], G[i], B[i], k);
        oL[i] = lab.L;
        oa[i] = lab.a;
        ob[i] = lab.b;
    }
}

// rgb: three planes of linear RGB in [0,1].
Prepared prepare(const Plane rgb[3], int w, int h, const Kernels& k, Workspace& ws) {
    const ColorConsts& cc = colorConsts();
    const size_t n = size_t(w) * size_t(h);
    Plane& yy = ws.s[0];
    Plane& cx = ws.s[1];
    Plane& cz = ws.s[2];
    Plane& lum = ws.s[3];
    Plane& tmp = ws.s[4];
    Plane& f1 = ws.s[5];
    Plane& f2 = ws.s[6];
    Prepared out;
    out.L.resize(n);
    out.a.resize(n);
    out.b.resize(n);
    out.edge.resize(n);
    out.point.resize(n);

    forPixels(n, [&](size_t b, size_t e) {
        rgbToOpponent(rgb[0].data() + b, rgb[1].data() + b, rgb[2].data() + b, yy.data() + b, cx.data() + b,
                      cz.data() + b, lum.data() + b, e - b, cc);
    });

    // Spatial (CSF) filtering per channel, in place: yy, cx, cz become filtered.
    filterRows(yy.data(), tmp.data(), w, h, k.csfA);
    filterCols(tmp.data(), yy.data(), w, h, k.csfA);
    filterRows(cx.data(), tmp.data(), w, h, k.csfRG);
    filterCols(tmp.data(), cx.data(), w, h, k.csfRG);
    filterRows(cz.data(), tmp.data(), w, h, k.csfBY1);
    filterCols(tmp.data(), f1.data(), w, h, k.csfBY1);
    if (k.wBY2 != 0.0f) {
        filterRows(cz.data(), tmp.data(), w, h, k.csfBY2);
        filterCols(tmp.data(), f2.data(), w, h, k.csfBY2);
        forPixels(n, [&](size_t b, size_t e) {
            for (size_t i = b; i < e; ++i) cz[i] = k.wBY1 * f1[i] + k.wBY2 * f2[i];
        });
    } else {
        cz.swap(f1);
    }

    // Back to linear RGB (clamped) and to Hunt-adjusted CIELAB.
    forPixels(n, [&](size_t b, size_t e) {
        opponentToClampedRgb(yy.data() + b, cx.data() + b, cz.data() + b, e - b, cc);
        rgbToHuntLab(yy.data() + b, cx.data() + b, cz.data() + b, out.L.data() + b, out.a.data() + b,
                     out.b.data() + b, e - b, cc);
    });

    // Feature pipeline: detection on the (unfiltered) normalised luminance.
    // x-derivative filters: edge(x) gauss(y), point(x) gauss(y); y-derivative: transposed.
    Plane& hd = ws.s[0];
    Plane& hp = ws.s[1];
    Plane& hg = ws.s[2];
    filterRows(lum.data(), hd.data(), w, h, k.edge);
    filterRows(lum.data(), hp.data(), w, h, k.point);
    filterRows(lum.data(), hg.data(), w, h, k.gauss);
    filterCols(hd.data(), f1.data(), w, h, k.gauss);  // e_x
    filterCols(hg.data(), f2.data(), w, h, k.edge);   // e_y
    forPixels(n, [&](size_t b, size_t e) {
        for (size_t i = b; i < e; ++i) out.edge[i] = std::sqrt(f1[i] * f1[i] + f2[i] * f2[i]);
    });
    filterCols(hp.data(), f1.data(), w, h, k.gauss);  // p_x
    filterCols(hg.data(), f2.data(), w, h, k.point);  // p_y
    forPixels(n, [&](size_t b, size_t e) {
        for (size_t i = b; i < e; ++i) out.point[i] = std::sqrt(f1[i] * f1[i] + f2[i] * f2[i]);
    });
    return out;
}

void checkPair(const Image& ref, const Image& test, const char* what) {
    if (ref.width != test.width || ref.height != test.height)
        throwUserError(std::string(what) + ": reference is " + std::to_string(ref.width) + "x" +
                       std::to_string(ref.height) + " but test is " + std::to_string(test.width) + "x" +
                       std::to_string(test.height) + "; compare images of the same size");
    for (const Image* im : {&ref, &test})
        if (im->channels != 1 && im->channels < 3)
            throwUserError(std::string(what) + ": an image has " + std::to_string(im->channels) +
                           " channels; give 1 (grey) or >= 3 (RGB[A])");
    if (ref.empty())
        throwUserError(std::string(what) + ": the images are empty; give images of at least 1x1 pixels");
}

void checkPixelsPerDegree(double ppd, const char* what) {
    if (!(ppd > 0.0) || !(ppd <= kMaxFlipPixelsPerDegree))
        throwUserError(std::string(what) + ": pixels per degree is " + std::to_string(ppd) +
                       "; give a value above 0 and at most " + std::to_string(int(kMaxFlipPixelsPerDegree)) +
                       " (default 67.02)");
}

enum class Input { Srgb, Linear01 };

// srgbToLinearF of the 256 values an 8-bit image holds (code / 255.0f, as image files are read and
// as compare's tone map gives them): its inputs are almost always one of these, and a table
// lookup, checked to be that exact float, replaces the powf.
struct Srgb8Decode {
    float value[256];  // code / 255.0f
    float linear[256];  // srgbToLinearF(value)
    Srgb8Decode() {
        for (int c = 0; c < 256; ++c) {
            value[c] = float(c) / 255.0f;
            linear[c] = srgbToLinearF(value[c]);
        }
    }
    float operator()(float v) const {
        if (v >= 0.0f && v <= 1.0f) {
            const int c = int(v * 255.0f + 0.5f);
            if (value[c] == v) return linear[c];
        }
        return srgbToLinearF(v);  // any other value (and NaN)
    }
};

void toLinearPlanes(const Image& im, Input mode, Plane rgb[3]) {
    static const Srgb8Decode decode;
    const size_t n = im.pixelCount();
    for (int c = 0; c < 3; ++c) rgb[c].resize(n);
    const int ch = im.channels;
    forPixels(n, [&](size_t b, size_t e) {
        for (size_t i = b; i < e; ++i) {
            const float* p = im.pixels.data() + i * size_t(ch);
            for (int c = 0; c < 3; ++c) {
                const float v = p[ch == 1 ? 0 : c];
                rgb[c][i] = mode == Input::Srgb ? decode(v) : clamp01(v);
            }
        }
    });
}

// Combines two prepared images into the FLIP map, eqs. (5)-(10), pixels [begin, end).
void combineRange(const Prepared& r, const Prepared& t, float cMax, float* out, size_t begin, size_t end) {
    const float pcCmax = float(kPc) * cMax;
    const float lowScale = float(kPt) / pcCmax;
    const float highScale = float(1.0 - kPt) / (cMax - pcCmax);
    const float invSqrt2 = float(1.0 / std::numbers::sqrt2);
    for (size_t i = begin; i < end; ++i) {
        // Colour: HyAB (eq. (5)) raised to q_c, then the piecewise-linear remap (eq. (8)):
        // [0, p_c c_max) -> [0, p_t), [p_c c_max, c_max] -> [p_t, 1].
        const float dE = hyab({r.L[i], r.a[i], r.b[i]}, {t.L[i], t.a[i], t.b[i]});
        const float dEq = std::pow(dE, float(kQc));
        float dEc = dEq < pcCmax ? dEq * lowScale : float(kPt) + (dEq - pcCmax) * highScale;
        dEc = std::min(dEc, 1.0f);  // c_max is the largest HyAB^q_c in gamut; guard rounding
        // Features, eq. (9): dE_f = ((1/sqrt 2) max(| |e_r| - |e_t| |, | |p_r| - |p_t| |))^q_f.
        const float de = std::abs(r.edge[i] - t.edge[i]);
        const float dp = std::abs(r.point[i] - t.point[i]);
        static_assert(kQf == 0.5, "the feature exponent is applied as a square root");
        const float dEf = std::min(1.0f, std::sqrt(invSqrt2 * std::max(de, dp)));
        // FLIP, eq. (10): dE_c^(1 - dE_f).
        out[i] = dEf == 0.0f ? dEc : std::pow(dEc, 1.0f - dEf);
    }
}

void combine(const Prepared& r, const Prepared& t, float cMax, float* out, size_t n) {
    forPixels(n, [&](size_t b, size_t e) { combineRange(r, t, cMax, out, b, e); });
}

Image flipLdrImpl(const Image& ref, const Image& test, double ppd, Input mode, const char* what) {
    checkPair(ref, test, what);
    checkPixelsPerDegree(ppd, what);
    const int w = ref.width, h = ref.height;
    const Kernels k = makeKernels(ppd);
    Workspace ws(ref.pixelCount());
    Plane rgb[3];  // reused for both images
    toLinearPlanes(ref, mode, rgb);
    const Prepared pr = prepare(rgb, w, h, k, ws);
    toLinearPlanes(test, mode, rgb);
    const Prepared pt = prepare(rgb, w, h, k, ws);
    Image out(w, h, 1);
    combine(pr, pt, float(maxColorDifference()), out.pixels.data(), out.pixelCount());
    return out;
}

}  // namespace flip_pipeline

using namespace flip_pipeline;

double flipPixelsPerDegree(double distanceMeters, double monitorWidthPixels, double monitorWidthMeters) {
    return distanceMeters * (monitorWidthPixels / monitorWidthMeters) * (kPi / 180.0);
}

Image flipLdr(const Image& referenceSrgb, const Image& testSrgb, double pixelsPerDegree) {
    return flipLdrImpl(referenceSrgb, testSrgb, pixelsPerDegree, Input::Srgb, "flipLdr");
}

struct LdrFlipReference::State {
    Image shape;  // the reference's size and channels (no pixels), for checkPair
    double ppd = 0.0;
    Kernels kernels;
    Prepared prepared;
};

LdrFlipReference::LdrFlipReference(const Image& referenceSrgb, double pixelsPerDegree) : state_(new State) {
    checkPair(referenceSrgb, referenceSrgb, "LdrFlipReference");
    checkPixelsPerDegree(pixelsPerDegree, "LdrFlipReference");
    State& s = *state_;
    s.shape.width = referenceSrgb.width;
    s.shape.height = referenceSrgb.height;
    s.shape.channels = referenceSrgb.channels;
    s.ppd = pixelsPerDegree;
    s.kernels = makeKernels(pixelsPerDegree);
    Workspace ws(referenceSrgb.pixelCount());
    Plane rgb[3];
    toLinearPlanes(referenceSrgb, Input::Srgb, rgb);
    s.prepared = prepare(rgb, referenceSrgb.width, referenceSrgb.height, s.kernels, ws);
}

LdrFlipReference::~LdrFlipReference() = default;

Image LdrFlipReference::compare(const Image& testSrgb) const {
    const State& s = *state_;
    if (testSrgb.width != s.shape.width || testSrgb.height != s.shape.height)
        throwUserError("LdrFlipReference: reference is " + std::to_string(s.shape.width) + "x" +
                       std::to_string(s.shape.height) + " but test is " + std::to_string(testSrgb.width) + "x" +
                       std::to_string(testSrgb.height) + "; compare images of the same size");
    checkPair(testSrgb, testSrgb, "LdrFlipReference");
    Workspace ws(testSrgb.pixelCount());
    Plane rgb[3];
    toLinearPlanes(testSrgb, Input::Srgb, rgb);
    const Prepared pt = prepare(rgb, testSrgb.width, testSrgb.height, s.kernels, ws);
    Image out(testSrgb.width, testSrgb.height, 1);
    combine(s.prepared, pt, float(maxColorDifference()), out.pixels.data(), out.pixelCount());
    return out;
}

Image flipLdrLinear(const Image& referenceLinear, const Image& testLinear, double pixelsPerDegree) {
    return flipLdrImpl(referenceLinear, testLinear, pixelsPerDegree, Input::Linear01, "flipLdrLinear");
}

FlipStats flipStats(const Image& map, const std::vector<uint8_t>* mask) {
    if (map.channels != 1) throwUserError("flipStats: the map has " + std::to_string(map.channels) +
                                          " channels; give the 1-channel map flipLdr/flipHdr return");
    const bool useMask = mask && !mask->empty();
    if (useMask && mask->size() != map.pixelCount())
        throwUserError("flipStats: the mask has " + std::to_string(mask->size()) + " entries for " +
                       std::to_string(map.pixelCount()) + " pixels; give one byte per pixel");
    std::vector<float> v;
    if (useMask) {
        v.reserve(map.pixelCount());
        for (size_t i = 0; i < map.pixelCount(); ++i)
            if ((*mask)[i]) v.push_back(map.pixels[i]);
    } else {
        v = map.pixels;
    }
    FlipStats s;
    s.count = v.size();
    if (v.empty()) return s;
    // Sorted as the floats they are (float -> double is exact and keeps the order): the sum below
    // adds the same values in the same order as a std::sort of doubles would.
    radixSortFloats(v);
    double sum = 0.0;
    for (float x : v) sum += x;
    s.mean = sum / double(v.size());
    s.min = v.front();
    s.max = v.back();
    s.median = v[nearestRankIndex(0.5, v.size())];
    if (sum > 0.0) {
        // Weighted quantiles: walk the sorted values accumulating their own weight.
        const double targets[3] = {0.25 * sum, 0.5 * sum, 0.75 * sum};
        double* outs[3] = {&s.weightedQ1, &s.weightedMedian, &s.weightedQ3};
        double acc = 0.0;
        int t = 0;
        for (size_t i = 0; i < v.size() && t < 3; ++i) {
            acc += v[i];
            while (t < 3 && acc >= targets[t]) *outs[t++] = v[i];
        }
        for (; t < 3; ++t) *outs[t] = v.back();  // rounding in acc: the last value
    }
    return s;
}

}  // namespace gbl
