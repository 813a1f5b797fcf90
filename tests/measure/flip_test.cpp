// FLIP tests. The main check compares gbl::flipLdr / gbl::flipHdr against a second,
// independent implementation written below from the papers' formulas: double precision,
// direct (non-separable) 2D convolution with the 2D kernels as the paper writes them, its own
// colour conversions and its own exposure search (bisection instead of the closed form).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <numbers>
#include <utility>
#include <random>
#include <time.h>
#include <vector>

#include "error.h"
#include "flip.h"

namespace {

using gbl::Image;
constexpr double kPi = std::numbers::pi;

// ------------------------------------------------------------------------------------------------
// The independent reference implementation.
namespace slow {

using Px = std::array<double, 3>;
struct Img {
    int w = 0, h = 0;
    std::vector<Px> p;
    Px& at(int x, int y) { return p[size_t(y) * w + x]; }
    const Px& at(int x, int y) const { return p[size_t(y) * w + x]; }
    const Px& clampedAt(int x, int y) const {
        return at(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1));
    }
};

// sRGB (IEC 61966-2-1) linear RGB -> XYZ, D65.
constexpr double M[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                            {0.2126729, 0.7151522, 0.0721750},
                            {0.0193339, 0.1191920, 0.9503041}};

Px mul(const double m[3][3], const Px& v) {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// XYZ -> RGB by solving M rgb = xyz with Gaussian elimination (partial pivoting).
Px solve(const Px& xyz) {
    double a[3][4];
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) a[i][j] = M[i][j];
        a[i][3] = xyz[size_t(i)];
    }
    for (int c = 0; c < 3; ++c) {
        int piv = c;
        for (int r = c + 1; r < 3; ++r)
            if (std::abs(a[r][c]) > std::abs(a[piv][c])) piv = r;
        for (int j = 0; j < 4; ++j) std::swap(a[c][j], a[piv][j]);
        for (int r = 0; r < 3; ++r) {
            if (r == c) continue;
            const double f = a[r][c] / a[c][c];
            for (int j = c; j < 4; ++j) a[r][j] -= f * a[c][j];
        }
    }
    return {a[0][3] / a[0][0], a[1][3] / a[1][1], a[2][3] / a[2][2]};
}

Px white() { return mul(M, {1, 1, 1}); }

double decode(double v) {
    v = std::clamp(v, 0.0, 1.0);
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

double f(double t) {
    const double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

// Hunt-adjusted L*a*b* of linear RGB.
Px huntLab(const Px& rgb) {
    const Px xyz = mul(M, rgb), w = white();
    const double fx = f(xyz[0] / w[0]), fy = f(xyz[1] / w[1]), fz = f(xyz[2] / w[2]);
    const double L = 116 * fy - 16, a = 500 * (fx - fy), b = 200 * (fy - fz);
    return {L, L / 100 * a, L / 100 * b};
}

double hyab(const Px& p, const Px& q) {
    return std::abs(p[0] - q[0]) + std::sqrt((p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

// Direct 2D correlation with a (2r+1)^2 kernel k[(j+r)*(2r+1) + (i+r)], clamp-to-edge, channel c.
double conv(const Img& im, int x, int y, int c, const std::vector<double>& k, int r) {
    double s = 0;
    for (int j = -r; j <= r; ++j)
        for (int i = -r; i <= r; ++i) s += k[size_t((j + r) * (2 * r + 1) + (i + r))] * im.clampedAt(x + i, y + j)[size_t(c)];
    return s;
}

struct Prepared {
    std::vector<Px> lab;
    std::vector<double> edge, point;
};

Prepared prepare(const Img& linear, double ppd) {
    const Px w = white();
    Img ycc{linear.w, linear.h, {}}, lum{linear.w, linear.h, {}};
    for (const Px& rgb : linear.p) {
        const Px xyz = mul(M, rgb);
        const double X = xyz[0] / w[0], Y = xyz[1] / w[1], Z = xyz[2] / w[2];
        ycc.p.push_back({116 * Y - 16, 500 * (X - Y), 200 * (Y - Z)});
        lum.p.push_back({Y, 0, 0});
    }
    // CSF kernels (spatial domain, sum of Gaussians in the distance from the centre, degrees).
    const double a1[3] = {1, 1, 34.1}, b1[3] = {0.0047, 0.0053, 0.04}, a2[3] = {0, 0, 13.5},
                 b2[3] = {1e-5, 1e-5, 0.025};
    const int r = int(std::ceil(3 * std::sqrt(0.04 / (2 * kPi * kPi)) * ppd));
    std::vector<double> csf[3];
    for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (int j = -r; j <= r; ++j)
            for (int i = -r; i <= r; ++i) {
                const double d2 = (i * i + j * j) / (ppd * ppd);
                const double v = a1[c] * std::sqrt(kPi / b1[c]) * std::exp(-kPi * kPi * d2 / b1[c]) +
                                 a2[c] * std::sqrt(kPi / b2[c]) * std::exp(-kPi * kPi * d2 / b2[c]);
                csf[c].push_back(v);
                sum += v;
            }
        for (double& v : csf[c]) v /= sum;
    }
    Prepared out;
    for (int y = 0; y < linear.h; ++y)
        for (int x = 0; x < linear.w; ++x) {
            const double Yy = conv(ycc, x, y, 0, csf[0], r), Cx = conv(ycc, x, y, 1, csf[1], r),
                         Cz = conv(ycc, x, y, 2, csf[2], r);
            const double Yn = (Yy + 16) / 116;
            const Px xyz = {(Cx / 500 + Yn) * w[0], Yn * w[1], (Yn - Cz / 200) * w[2]};
            Px rgb = solve(xyz);
            for (double& v : rgb) v = std::clamp(v, 0.0, 1.0);
            out.lab.push_back(huntLab(rgb));
        }
    // Feature kernels: 2D first and second x-derivatives of a Gaussian, positive weights
    // normalised to sum 1 and negative weights to sum -1; the y versions are transposes.
    const double sigma = 0.5 * 0.082 * ppd;
    const int fr = int(std::ceil(3 * sigma));
    const int n = 2 * fr + 1;
    std::vector<double> ex(size_t(n * n)), px(size_t(n * n)), ey(ex.size()), py(ex.size());
    double ePos = 0, eNeg = 0, pPos = 0, pNeg = 0;
    for (int j = -fr; j <= fr; ++j)
        for (int i = -fr; i <= fr; ++i) {
            const double g = std::exp(-(i * i + j * j) / (2 * sigma * sigma));
            const size_t k = size_t((j + fr) * n + (i + fr));
            ex[k] = -i * g;
            px[k] = (i * i / (sigma * sigma) - 1) * g;
            (ex[k] > 0 ? ePos : eNeg) += ex[k];
            (px[k] > 0 ? pPos : pNeg) += px[k];
        }
    for (size_t k = 0; k < ex.size(); ++k) {
        ex[k] = ex[k] > 0 ? ex[k] / ePos : ex[k] / -eNeg;
        px[k] = px[k] > 0 ? px[k] / pPos : px[k] / -pNeg;
    }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            ey[size_t(j * n + i)] = ex[size_t(i * n + j)];
            py[size_t(j * n + i)] = px[size_t(i * n + j)];
        }
    for (int y = 0; y < linear.h; ++y)
        for (int x = 0; x < linear.w; ++x) {
            out.edge.push_back(std::hypot(conv(lum, x, y, 0, ex, fr), conv(lum, x, y, 0, ey, fr)));
            out.point.push_back(std::hypot(conv(lum, x, y, 0, px, fr), conv(lum, x, y, 0, py, fr)));
        }
    return out;
}

// LDR-FLIP of two linear-RGB images.
std::vector<double> flipLinear(const Img& r, const Img& t, double ppd) {
    const Prepared a = prepare(r, ppd), b = prepare(t, ppd);
    const double qc = 0.7, pc = 0.4, pt = 0.95, qf = 0.5;
    const double cmax = std::pow(hyab(huntLab({0, 1, 0}), huntLab({0, 0, 1})), qc);
    std::vector<double> out;
    for (size_t i = 0; i < a.lab.size(); ++i) {
        const double e = std::pow(hyab(a.lab[i], b.lab[i]), qc);
        const double ec = e < pc * cmax ? pt / pc * e / cmax : pt + (e - pc * cmax) / (cmax - pc * cmax) * (1 - pt);
        const double ef = std::pow(std::max(std::abs(a.edge[i] - b.edge[i]), std::abs(a.point[i] - b.point[i])) /
                                       std::sqrt(2.0),
                                   qf);
        out.push_back(std::pow(ec, 1 - ef));
    }
    return out;
}

Img fromImage(const Image& im, bool srgb) {
    Img o{im.width, im.height, {}};
    for (size_t i = 0; i < im.pixelCount(); ++i) {
        Px p;
        for (int c = 0; c < 3; ++c) {
            const double v = im.pixels[i * size_t(im.channels) + size_t(c)];
            p[size_t(c)] = srgb ? decode(v) : std::clamp(v, 0.0, 1.0);
        }
        o.p.push_back(p);
    }
    return o;
}

std::vector<double> flipSrgb(const Image& r, const Image& t, double ppd) {
    return flipLinear(fromImage(r, true), fromImage(t, true), ppd);
}

double toneMap(double x) {
    const double y = 0.6 * x;  // ACES fit (Narkowicz) of 0.6 x
    return std::clamp(y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14), 0.0, 1.0);
}

struct Range {
    double start, stop;
    int count;
};

Range exposures(const Image& ref) {
    double lo = 0, hi = 100;  // t(x) = 0.85 by bisection
    for (int i = 0; i < 200; ++i) ((toneMap(0.5 * (lo + hi)) < 0.85) ? lo : hi) = 0.5 * (lo + hi);
    const double xMax = 0.5 * (lo + hi);
    std::vector<double> y;
    for (size_t i = 0; i < ref.pixelCount(); ++i) {
        const float* p = &ref.pixels[i * size_t(ref.channels)];
        y.push_back(M[1][0] * std::max(0.f, p[0]) + M[1][1] * std::max(0.f, p[1]) + M[1][2] * std::max(0.f, p[2]));
    }
    std::sort(y.begin(), y.end());
    const double median = y[(y.size() + 1) / 2 - 1];  // lower median
    Range r{std::log2(xMax / y.back()), std::log2(xMax / median), 0};
    r.count = std::max(2, int(std::ceil(r.stop - r.start)));
    return r;
}

std::vector<double> flipHdr(const Image& ref, const Image& test, double ppd, Range& range) {
    range = exposures(ref);
    std::vector<double> best(ref.pixelCount(), 0.0);
    for (int e = 0; e < range.count; ++e) {
        const double c = range.start + e * (range.stop - range.start) / (range.count - 1);
        auto tm = [&](const Image& im) {
            Img o{im.width, im.height, {}};
            for (size_t i = 0; i < im.pixelCount(); ++i) {
                Px p;
                for (int k = 0; k < 3; ++k)
                    p[size_t(k)] = toneMap(std::max(0.0, double(im.pixels[i * size_t(im.channels) + size_t(k)])) *
                                           std::exp2(c));
                o.p.push_back(p);
            }
            return o;
        };
        const std::vector<double> m = flipLinear(tm(ref), tm(test), ppd);
        for (size_t i = 0; i < m.size(); ++i) best[i] = std::max(best[i], m[i]);
    }
    return best;
}

}  // namespace slow
// ------------------------------------------------------------------------------------------------

Image constant(int w, int h, float r, float g, float b) {
    Image im(w, h, 3);
    for (size_t i = 0; i < im.pixelCount(); ++i) {
        im.pixels[i * 3] = r;
        im.pixels[i * 3 + 1] = g;
        im.pixels[i * 3 + 2] = b;
    }
    return im;
}

Image noise(int w, int h, unsigned seed, float lo = 0.0f, float hi = 1.0f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    Image im(w, h, 3);
    for (float& v : im.pixels) v = u(rng);
    return im;
}

// A vertical edge at x = 16 between two colours; `blur` > 0 makes it a linear ramp that wide.
Image edge(int w, int h, float blur) {
    Image im(w, h, 3);
    const float left[3] = {0.1f, 0.2f, 0.6f}, right[3] = {0.9f, 0.8f, 0.3f};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float xc = x + 0.5f - 16.0f;
            const float t = blur > 0 ? std::clamp(xc / blur + 0.5f, 0.0f, 1.0f) : (xc > 0 ? 1.0f : 0.0f);
            for (int c = 0; c < 3; ++c) im.at(x, y, c) = left[c] + t * (right[c] - left[c]);
        }
    return im;
}

// Max |a - b| over the map, and checks the range.
double maxDiff(const Image& map, const std::vector<double>& ref) {
    EXPECT_EQ(map.channels, 1);
    EXPECT_EQ(map.pixelCount(), ref.size());
    double m = 0;
    for (size_t i = 0; i < ref.size(); ++i) m = std::max(m, std::abs(double(map.pixels[i]) - ref[i]));
    return m;
}

// Float pipeline vs the double reference: the largest difference seen over these cases is
// 7e-6; the tolerance leaves room for libm differences but catches any formula change
// (a wrong constant, kernel or normalisation moves values by 1e-3 or more).
constexpr double kTol = 5e-5;

TEST(Flip, PixelsPerDegreeFromViewingConditions) {
    EXPECT_NEAR(gbl::flipPixelsPerDegree(), 3840.0 * kPi / 180.0, 1e-12);
    EXPECT_NEAR(gbl::flipPixelsPerDegree(), 67.0206, 1e-4);
    EXPECT_NEAR(gbl::flipPixelsPerDegree(1.4, 3840, 0.7), 2 * 67.02064327658225, 1e-9);
}

TEST(Flip, IdenticalImagesGiveExactlyZero) {
    const Image a = noise(37, 29, 1);
    const Image m = gbl::flipLdr(a, a);
    ASSERT_EQ(m.width, 37);
    ASSERT_EQ(m.height, 29);
    for (float v : m.pixels) ASSERT_EQ(v, 0.0f);
    const gbl::FlipStats s = gbl::flipStats(m);
    EXPECT_EQ(s.mean, 0.0);
    EXPECT_EQ(s.max, 0.0);
    EXPECT_EQ(s.weightedMedian, 0.0);

    Image hdr = noise(20, 20, 2, 0.0f, 30.0f);
    const gbl::HdrFlipResult h = gbl::flipHdr(hdr, hdr);
    for (float v : h.flip.pixels) ASSERT_EQ(v, 0.0f);
}

TEST(Flip, BlackVsWhiteMatchesIndependentImplementation) {
    const Image b = constant(32, 32, 0, 0, 0), w = constant(32, 32, 1, 1, 1);
    const Image m = gbl::flipLdr(b, w);
    const std::vector<double> ref = slow::flipSrgb(b, w, gbl::flipPixelsPerDegree());
    EXPECT_LT(maxDiff(m, ref), kTol);
    // By hand: HyAB = 100 (L* 0 vs 100, a* = b* = 0), 100^0.7 = 25.119 is above p_c c_max, so
    // 0.95 + (25.119 - 0.4 c_max) / (0.6 c_max) * 0.05 with c_max = HyAB(green, blue)^0.7.
    const double cmax = std::pow(slow::hyab(slow::huntLab({0, 1, 0}), slow::huntLab({0, 0, 1})), 0.7);
    const double expected = 0.95 + (std::pow(100.0, 0.7) - 0.4 * cmax) / (0.6 * cmax) * 0.05;
    EXPECT_NEAR(expected, 0.9674, 1e-3);  // a sanity check of the hand formula itself
    for (float v : m.pixels) ASSERT_NEAR(v, expected, 1e-5);
}

TEST(Flip, StepVsBlurredEdgeMatchesIndependentImplementation) {
    const Image a = edge(32, 32, 0.0f), b = edge(32, 32, 6.0f);
    const Image m = gbl::flipLdr(a, b);
    const std::vector<double> ref = slow::flipSrgb(a, b, gbl::flipPixelsPerDegree());
    EXPECT_LT(maxDiff(m, ref), kTol);
    // The error sits on the edge: far from it both images are the same constant.
    EXPECT_GT(m.at(16, 16, 0), 0.05f);
    EXPECT_EQ(m.at(0, 16, 0), 0.0f);
}

TEST(Flip, RandomNoiseMatchesIndependentImplementation) {
    const Image a = noise(32, 32, 7), b = noise(32, 32, 8);
    const Image m = gbl::flipLdr(a, b);
    EXPECT_LT(maxDiff(m, slow::flipSrgb(a, b, gbl::flipPixelsPerDegree())), kTol);
    // Small perturbation: exercises the low (p < p_c) branch of the remap.
    Image c = a;
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-0.03f, 0.03f);
    for (float& v : c.pixels) v = std::clamp(v + u(rng), 0.0f, 1.0f);
    EXPECT_LT(maxDiff(gbl::flipLdr(a, c), slow::flipSrgb(a, c, gbl::flipPixelsPerDegree())), kTol);
}

TEST(Flip, PreparedReferenceGivesTheSameMapBitForBit) {
    // 300x200 = 60000 pixels: large enough that the filters and per-pixel loops split across
    // threads, so this also checks the split changes nothing.
    const Image a = noise(300, 200, 31), b = noise(300, 200, 32), c = noise(300, 200, 33);
    const gbl::LdrFlipReference prepared(a);
    for (const Image* test : {&b, &c, &a}) {
        const Image once = gbl::flipLdr(a, *test);
        const Image reused = prepared.compare(*test);
        ASSERT_EQ(once.pixels.size(), reused.pixels.size());
        for (size_t i = 0; i < once.pixels.size(); ++i) ASSERT_EQ(once.pixels[i], reused.pixels[i]) << i;
    }
    EXPECT_NE(gbl::flipStats(prepared.compare(b)).mean, 0.0);
    EXPECT_THROW(prepared.compare(noise(299, 200, 34)), gbl::UserError);
}

TEST(Flip, OtherSizesAndPpdMatchIndependentImplementation) {
    // Non-square, smaller than the kernels in one direction, and a different ppd (other radii).
    const Image a = noise(41, 9, 11), b = noise(41, 9, 12);
    for (double ppd : {20.0, 45.5}) {
        EXPECT_LT(maxDiff(gbl::flipLdr(a, b, ppd), slow::flipSrgb(a, b, ppd)), kTol) << "ppd " << ppd;
    }
}

TEST(Flip, HdrMatchesIndependentImplementation) {
    Image a = noise(24, 24, 21, 0.0f, 4.0f);
    for (int i = 0; i < 24; ++i) a.at(i, i, 0) = 40.0f;  // a few very bright pixels
    Image b = a;
    std::mt19937 rng(22);
    std::uniform_real_distribution<float> u(0.7f, 1.3f);
    for (float& v : b.pixels) v *= u(rng);
    slow::Range range{};
    const std::vector<double> ref = slow::flipHdr(a, b, gbl::flipPixelsPerDegree(), range);
    const gbl::HdrFlipResult h = gbl::flipHdr(a, b);
    EXPECT_NEAR(h.range.start, range.start, 1e-5);
    EXPECT_NEAR(h.range.stop, range.stop, 1e-5);
    EXPECT_EQ(h.range.count, range.count);
    EXPECT_GE(h.range.count, 3);
    EXPECT_LT(maxDiff(h.flip, ref), kTol);
    for (float e : h.exposureMap.pixels) {
        EXPECT_GE(e, 0.0f);
        EXPECT_LT(e, float(h.range.count));
    }
}

TEST(Flip, HdrHandlesNonFiniteAndNegativeValues) {
    Image a = noise(16, 16, 61, 0.0f, 5.0f), b = noise(16, 16, 62, 0.0f, 5.0f);
    b.pixels[0] = std::numeric_limits<float>::infinity();
    b.pixels[4] = -2.0f;
    b.pixels[8] = std::nanf("");
    a.pixels[12] = std::numeric_limits<float>::infinity();  // left out of the luminance statistics
    const gbl::HdrFlipResult h = gbl::flipHdr(a, b);
    EXPECT_TRUE(std::isfinite(h.range.start));
    EXPECT_TRUE(std::isfinite(h.range.stop));
    for (float v : h.flip.pixels) {
        ASSERT_GE(v, 0.0f);
        ASSERT_LE(v, 1.0f);
    }
}

TEST(Flip, ExposureRange) {
    // Luminance 1 everywhere except one pixel of luminance 8: Y_max = 8, Y_median = 1.
    Image a = constant(5, 5, 1, 1, 1);
    for (int c = 0; c < 3; ++c) a.at(2, 2, c) = 8.0f;
    const gbl::FlipExposureRange r = gbl::flipExposureRange(a);
    double lo = 0, hi = 100;
    for (int i = 0; i < 200; ++i) ((gbl::flipToneMap(float(0.5 * (lo + hi))) < 0.85f) ? lo : hi) = 0.5 * (lo + hi);
    EXPECT_NEAR(gbl::flipToneMap(float(0.5 * (lo + hi))), 0.85f, 1e-6);
    const double xMax = 0.5 * (lo + hi);  // about 2.119
    EXPECT_NEAR(xMax, 2.1189, 1e-3);
    EXPECT_NEAR(r.start, std::log2(xMax / 8.0), 1e-4);  // luminance of (8,8,8) is 8 * Y_white
    EXPECT_NEAR(r.stop, std::log2(xMax / 1.0), 1e-4);
    EXPECT_EQ(r.count, 3);  // ceil(3) = 3
    EXPECT_NEAR(r.exposure(0), r.start, 1e-6);
    EXPECT_NEAR(r.exposure(2), r.stop, 1e-6);
    // All black: one exposure of 0 (repeated), FLIP of black vs black is 0.
    const gbl::FlipExposureRange z = gbl::flipExposureRange(constant(4, 4, 0, 0, 0));
    EXPECT_EQ(z.start, 0.0f);
    EXPECT_EQ(z.stop, 0.0f);
}

TEST(Flip, ToneMapper) {
    EXPECT_EQ(gbl::flipToneMap(0.0f), 0.0f);
    EXPECT_NEAR(gbl::flipToneMap(1.0f), slow::toneMap(1.0), 1e-6);
    EXPECT_NEAR(gbl::flipToneMap(1e6f), 1.0f, 1e-6);  // 2.51 / 2.43 > 1, clamped
    EXPECT_EQ(gbl::flipToneMap(std::numeric_limits<float>::infinity()), 1.0f);
    EXPECT_EQ(gbl::flipToneMap(3e30f), 1.0f);
    EXPECT_EQ(gbl::flipToneMap(std::nanf("")), 0.0f);
    float prev = 0.0f;
    for (float x = 0.01f; x < 100.0f; x *= 1.1f) {
        const float t = gbl::flipToneMap(x);
        EXPECT_GE(t, prev);
        prev = t;
    }
}

TEST(Flip, RangeIsUnitInterval) {
    const Image a = noise(48, 40, 31), b = noise(48, 40, 32);
    const Image m = gbl::flipLdr(a, b);
    for (float v : m.pixels) {
        ASSERT_GE(v, 0.0f);
        ASSERT_LE(v, 1.0f);
    }
    // Out-of-range and NaN inputs are clamped, not propagated.
    Image c = a;
    c.pixels[0] = -3.0f;
    c.pixels[1] = 7.0f;
    c.pixels[2] = std::nanf("");
    for (float v : gbl::flipLdr(a, c).pixels) {
        ASSERT_GE(v, 0.0f);
        ASSERT_LE(v, 1.0f);
    }
    // The largest colour difference (pure green vs pure blue) maps to 1.
    const Image g = constant(8, 8, 0, 1, 0), bl = constant(8, 8, 0, 0, 1);
    for (float v : gbl::flipLdr(g, bl).pixels) ASSERT_NEAR(v, 1.0f, 1e-5);
}

TEST(Flip, SymmetricForConstantColours) {
    const float colours[][3] = {{0.2f, 0.5f, 0.7f}, {0.9f, 0.1f, 0.1f}, {0.5f, 0.5f, 0.5f}, {0, 0, 0}, {1, 1, 0.2f}};
    const size_t n = std::size(colours);
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i; j < n; ++j) {
            const auto& c1 = colours[i];
            const auto& c2 = colours[j];
            const Image a = constant(8, 8, c1[0], c1[1], c1[2]), b = constant(8, 8, c2[0], c2[1], c2[2]);
            const Image ab = gbl::flipLdr(a, b), ba = gbl::flipLdr(b, a);
            for (size_t k = 0; k < ab.pixels.size(); ++k) {
                ASSERT_EQ(ab.pixels[k], ba.pixels[k]);
                ASSERT_EQ(ab.pixels[k], ab.pixels[0]);  // constant in, constant out
            }
            if (i == j) EXPECT_EQ(ab.pixels[0], 0.0f);
            else EXPECT_NEAR(ab.pixels[0], slow::flipSrgb(a, b, gbl::flipPixelsPerDegree())[0], kTol);
        }
}

TEST(Flip, MonotonicInDifferenceSize) {
    // Grey level offsets on a constant image: each step is a larger difference.
    float prev = 0.0f;
    for (float d : {0.01f, 0.02f, 0.05f, 0.1f, 0.2f, 0.3f, 0.45f}) {
        const float v = gbl::flipLdr(constant(8, 8, 0.5f, 0.5f, 0.5f), constant(8, 8, 0.5f + d, 0.5f + d, 0.5f + d))
                            .pixels[0];
        EXPECT_GT(v, prev) << "offset " << d;
        prev = v;
    }
    // A fixed noise pattern added with growing amplitude to a texture: mean FLIP grows.
    const Image ref = noise(40, 40, 41, 0.3f, 0.7f);
    const Image n = noise(40, 40, 42, -0.25f, 0.25f);
    double prevMean = 0.0;
    for (float s : {0.05f, 0.1f, 0.2f, 0.4f, 0.7f, 1.0f}) {
        Image t = ref;
        for (size_t i = 0; i < t.pixels.size(); ++i) t.pixels[i] = ref.pixels[i] + s * n.pixels[i];
        const double mean = gbl::flipStats(gbl::flipLdr(ref, t)).mean;
        EXPECT_GT(mean, prevMean) << "scale " << s;
        prevMean = mean;
    }
}

TEST(Flip, TinyImagesMatchIndependentImplementation) {
    for (auto [w, h] : {std::pair{1, 1}, std::pair{3, 2}, std::pair{1, 5}}) {
        const Image a = noise(w, h, 71), b = noise(w, h, 72);
        EXPECT_LT(maxDiff(gbl::flipLdr(a, b), slow::flipSrgb(a, b, gbl::flipPixelsPerDegree())), kTol)
            << w << "x" << h;
    }
}

TEST(Flip, GreyInputReplicated) {
    Image g1(10, 10, 1, 0.25f), g2(10, 10, 1, 0.75f);
    const Image m1 = gbl::flipLdr(g1, g2);
    const Image m3 = gbl::flipLdr(constant(10, 10, 0.25f, 0.25f, 0.25f), constant(10, 10, 0.75f, 0.75f, 0.75f));
    EXPECT_EQ(m1.pixels, m3.pixels);
}

TEST(Flip, SizeMismatchIsAUserError) {
    EXPECT_THROW(gbl::flipLdr(Image(4, 4, 3), Image(4, 5, 3)), gbl::UserError);
    EXPECT_THROW(gbl::flipLdr(Image(4, 4, 2), Image(4, 4, 2)), gbl::UserError);
    EXPECT_THROW(gbl::flipLdr(Image(4, 4, 3), Image(4, 4, 3), 0.0), gbl::UserError);
}

TEST(Flip, Stats) {
    Image m(5, 1, 1);
    m.pixels = {0.4f, 0.0f, 0.3f, 0.1f, 0.2f};
    gbl::FlipStats s = gbl::flipStats(m);
    EXPECT_EQ(s.count, 5u);
    EXPECT_NEAR(s.mean, 0.2, 1e-7);
    EXPECT_FLOAT_EQ(s.median, 0.2f);
    EXPECT_FLOAT_EQ(s.min, 0.0f);
    EXPECT_FLOAT_EQ(s.max, 0.4f);
    // Weights = values; cumulative 0, .1, .3, .6, 1.0 of total 1.0.
    EXPECT_FLOAT_EQ(s.weightedQ1, 0.2f);
    EXPECT_FLOAT_EQ(s.weightedMedian, 0.3f);
    EXPECT_FLOAT_EQ(s.weightedQ3, 0.4f);
    const std::vector<uint8_t> mask = {1, 1, 0, 1, 0};  // 0.4, 0.0, 0.1
    s = gbl::flipStats(m, &mask);
    EXPECT_EQ(s.count, 3u);
    EXPECT_NEAR(s.mean, 0.5 / 3, 1e-7);
    EXPECT_FLOAT_EQ(s.median, 0.1f);
    EXPECT_FLOAT_EQ(s.weightedMedian, 0.4f);  // cumulative .0, .1, .5 of .5: .25 reached at 0.4
    const std::vector<uint8_t> bad = {1, 1};
    EXPECT_THROW(gbl::flipStats(m, &bad), gbl::UserError);
}

// CPU time of this thread, seconds (unaffected by other processes sharing the cores).
double threadCpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Timing at 1920x1080 on one core: run with --gtest_also_run_disabled_tests.
TEST(Flip, DISABLED_Timing1080p) {
    const Image a = noise(1920, 1080, 51);
    Image b = a;
    for (size_t i = 0; i < b.pixels.size(); i += 7) b.pixels[i] = 1.0f - b.pixels[i];
    double bestWall = 1e9, bestCpu = 1e9;
    Image m;
    for (int rep = 0; rep < 3; ++rep) {
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = threadCpuSeconds();
        m = gbl::flipLdr(a, b);
        bestCpu = std::min(bestCpu, threadCpuSeconds() - c0);
        bestWall = std::min(bestWall, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        ASSERT_EQ(m.pixelCount(), size_t(1920) * 1080);
    }
    std::printf("LDR-FLIP 1920x1080: %.3f s CPU, %.3f s wall (best of 3)\n", bestCpu, bestWall);
    double c0 = threadCpuSeconds();
    const gbl::FlipStats st = gbl::flipStats(m);
    std::printf("flipStats 1920x1080: %.3f s CPU (mean %.4f)\n", threadCpuSeconds() - c0, st.mean);
    Image h1 = a, h2 = b;
    for (float& v : h1.pixels) v = v * v * 20.0f;
    for (float& v : h2.pixels) v = v * v * 20.0f;
    c0 = threadCpuSeconds();
    const gbl::HdrFlipResult hr = gbl::flipHdr(h1, h2);
    std::printf("HDR-FLIP 1920x1080: %.3f s CPU, %d exposures\n", threadCpuSeconds() - c0, hr.range.count);
}

}  // namespace
