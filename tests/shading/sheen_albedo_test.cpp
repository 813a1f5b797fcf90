// The sheen albedo table (src/shading/sheen_albedo.h) against a brute-force integral: E(NoV, r) =
// integral over the hemisphere of the Charlie sheen BRDF times NoL, by Monte Carlo with uniformly
// distributed directions (no importance sampling, no shared code: the Charlie D and V are written
// here again from the KHR_materials_sheen README, in double).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "brdf_layers.h"
#include "sheen_albedo.h"

using namespace gbl::shading;

namespace {

constexpr double kPiD = 3.14159265358979323846;

double readmeSheenBrdf(double NoH, double NoV, double NoL, double sheenRoughness) {
    const double r = sheenRoughness * sheenRoughness;
    const double D = (2.0 + 1.0 / r) * std::pow(std::max(1.0 - NoH * NoH, 0.0), 0.5 / r) / (2.0 * kPiD);
    auto l = [&](double x) {
        const double t = (1.0 - r) * (1.0 - r);
        auto mix = [&](double a, double b) { return a * (1.0 - t) + b * t; };
        return mix(21.5473, 25.3245) / (1.0 + mix(3.82987, 3.32435) * std::pow(x, mix(0.19823, 0.16801))) +
               mix(-1.97760, -1.27393) * x + mix(-4.32054, -4.85967);
    };
    auto lambda = [&](double c) { return c < 0.5 ? std::exp(l(c)) : std::exp(2.0 * l(0.5) - l(1.0 - c)); };
    const double V = 1.0 / ((1.0 + lambda(NoV) + lambda(NoL)) * (4.0 * NoV * NoL));
    return D * V;
}

// Monte Carlo over uniformly distributed directions of the hemisphere (pdf 1 / (2 pi)); returns the
// estimate and its standard error.
std::pair<double, double> bruteForceAlbedo(double NoV, double sheenRoughness, int samples, uint32_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double sv = std::sqrt(1.0 - NoV * NoV);
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < samples; ++i) {
        const double c = u(rng), phi = 2.0 * kPiD * u(rng), s = std::sqrt(1.0 - c * c);
        const double Lx = s * std::cos(phi), Ly = s * std::sin(phi), Lz = c;
        const double Hx = sv + Lx, Hy = Ly, Hz = NoV + Lz, len = std::sqrt(Hx * Hx + Hy * Hy + Hz * Hz);
        const double f = c > 0.0 ? readmeSheenBrdf(Hz / len, NoV, c, sheenRoughness) * c * 2.0 * kPiD : 0.0;
        sum += f;
        sum2 += f * f;
    }
    const double mean = sum / samples;
    return {mean, std::sqrt(std::max(sum2 / samples - mean * mean, 0.0) / samples)};
}

}  // namespace

// Every 6th node of the table against 2^18 brute-force samples, clamped to 1 as the table is
// (sheen_albedo.h: the lobe's albedo exceeds 1 at grazing NoV and low roughness). Tolerance: 4
// standard errors of the Monte Carlo plus 1e-3 absolute for the table's quadrature (96 x 48 midpoint
// nodes, within 1e-4 of 1024 x 512); at the sharpest lobes the brute force itself is the noisier.
TEST(SheenAlbedo, TableMatchesBruteForceIntegral) {
    const SheenAlbedoTable& table = sheenAlbedoTable();
    ASSERT_EQ(table.size, kSheenAlbedoSize);
    double worst = 0.0;
    int checked = 0, clamped = 0;
    for (int j = 1; j < table.size; j += 6)
        for (int i = 1; i < table.size; i += 6) {
            const double NoV = (i + 0.5) / table.size, r = (j + 0.5) / table.size;
            const float e = table.values[size_t(j) * table.size + i];
            EXPECT_GE(e, 0.0f);
            EXPECT_LE(e, 1.0f);
            const auto [mc, se] = bruteForceAlbedo(NoV, std::max(r, double(kMinSheenRoughness)), 1 << 18, 1000u + uint32_t(j * 64 + i));
            clamped += mc > 1.0 ? 1 : 0;
            const double diff = std::abs(double(e) - std::min(mc, 1.0));
            worst = std::max(worst, diff);
            EXPECT_LT(diff, 4.0 * se + 1e-3) << "NoV " << NoV << " sheen roughness " << r << ": table " << e << ", brute force "
                                             << mc << " +- " << se;
            ++checked;
        }
    std::printf("  %d table nodes against brute force (%d of them above 1, clamped): worst |difference| %.2e\n", checked,
                clamped, worst);
    EXPECT_GT(clamped, 0);  // the clamp is exercised: grazing NoV at low roughness
}

// The look-up is the GPU's bilinear filtering between texel centres with clamp-to-edge: exact at
// the centres, linear between, the edge texel beyond.
TEST(SheenAlbedo, LookupIsBilinearBetweenTexelCentres) {
    const SheenAlbedoTable& t = sheenAlbedoTable();
    auto at = [&](int i, int j) { return t.values[size_t(j) * t.size + i]; };
    const float c = 1.0f / float(t.size);
    EXPECT_FLOAT_EQ(t.lookup(5.5f * c, 7.5f * c), at(5, 7));
    EXPECT_NEAR(t.lookup(6.0f * c, 7.5f * c), 0.5f * (at(5, 7) + at(6, 7)), 1e-6);
    EXPECT_NEAR(t.lookup(5.5f * c, 8.0f * c), 0.5f * (at(5, 7) + at(5, 8)), 1e-6);
    EXPECT_FLOAT_EQ(t.lookup(0.0f, 0.0f), at(0, 0));
    EXPECT_FLOAT_EQ(t.lookup(1.0f, 1.0f), at(t.size - 1, t.size - 1));
}
