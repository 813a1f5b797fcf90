#include "procedural_sky.h"

#include <algorithm>
#include <cmath>

#include "error.h"
#include "parallel_for.h"

namespace gbl {
namespace {

constexpr double kSkyPi = 3.14159265358979323846;
// The ground meets the sky over this band of d.y just below the horizon (about 1.1 degrees),
// so the horizon does not alias into a jagged seam at low map resolutions.
constexpr double kHorizonBand = 0.02;
// The sun's edge softens from radius * (1 - kSunEdge) to radius * (1 + kSunEdge); the band is
// symmetric, so the disc's solid angle stays within a percent of pi r^2.
constexpr double kSunEdge = 0.2;
// The sky darkens from horizon to zenith colour as (1 - elevation)^kGradientPower.
constexpr double kGradientPower = 4.0;

double smoothstep(double edge0, double edge1, double x) {
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// 0 on the ground, 1 in the sky.
double skyVisibility(const glm::dvec3& d) { return smoothstep(-kHorizonBand, 0.0, d.y); }

glm::dvec3 skyAndGround(const glm::dvec3& d, const SkyParameters& p) {
    const double towardsHorizon = std::pow(1.0 - std::max(d.y, 0.0), kGradientPower);
    const glm::dvec3 sky = glm::mix(glm::dvec3(p.zenithColor), glm::dvec3(p.horizonColor), towardsHorizon);
    return glm::mix(glm::dvec3(p.groundColor), sky, skyVisibility(d));
}

// Angle between unit vectors; atan2 keeps precision at the sun's tiny angles where acos loses it.
double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

glm::dvec3 directionAt(double u, double v) {
    const double phi = (u - 0.5) * 2.0 * kSkyPi, theta = v * kSkyPi;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

// Fraction of texel (i, j) the sun covers, weighted by solid angle (sin theta), found by
// supersampling: point sampling the centre would make the sun's power depend on the map size
// and let a small sun fall between texel centres.
double sunCoverage(int i, int j, int width, int height, const glm::dvec3& sun, double radius) {
    const double du = 1.0 / width, dv = 1.0 / height;
    const double texelAngle = std::max(2.0 * kSkyPi * du, kSkyPi * dv);
    const double outer = radius * (1.0 + kSunEdge);
    if (angleBetween(directionAt((i + 0.5) * du, (j + 0.5) * dv), sun) > outer + texelAngle) return 0.0;
    const int n = std::clamp(int(std::ceil(8.0 * texelAngle / radius)), 4, 64);  // sub-spacing <= r/8
    double covered = 0.0, total = 0.0;
    for (int sj = 0; sj < n; ++sj) {
        const double v = (j + (sj + 0.5) / n) * dv;
        const double weight = std::sin(v * kSkyPi);
        for (int si = 0; si < n; ++si) {
            const glm::dvec3 d = directionAt((i + (si + 0.5) / n) * du, v);
            const double disc = 1.0 - smoothstep(radius * (1.0 - kSunEdge), outer, angleBetween(d, sun));
            covered += weight * disc * skyVisibility(d);  // the ground hides a low sun
            total += weight;
        }
    }
    return covered / total;
}

bool finiteNonNegative(const glm::vec3& c) {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && c.x >= 0 && c.y >= 0 && c.z >= 0;
}

void validate(int width, const SkyParameters& p) {
    const std::string place = "procedural sky: ";
    if (width < 8 || width > 65536 || width % 2 != 0)
        throwUserError(place + "width " + std::to_string(width) + " must be even and in [8, 65536] (e.g. 1024)");
    const float length = glm::length(p.sunDirection);
    if (!std::isfinite(length) || length < 1e-6f)
        throwUserError(place + "sun direction must be a finite, non-zero vector");
    if (!(p.sunAngularRadius > 0.0f && p.sunAngularRadius <= 0.5f))
        throwUserError(place + "sun angular radius " + std::to_string(p.sunAngularRadius) +
                       " must be in (0, 0.5] radians (the real sun is about 0.0047)");
    if (!finiteNonNegative(p.sunRadiance) || !finiteNonNegative(p.zenithColor) ||
        !finiteNonNegative(p.horizonColor) || !finiteNonNegative(p.groundColor))
        throwUserError(place + "sun radiance and sky/ground colours must be finite and non-negative");
}

}  // namespace

EnvironmentMap makeProceduralSky(int width, const SkyParameters& params) {
    validate(width, params);
    const int height = width / 2;
    const glm::dvec3 sun = glm::normalize(glm::dvec3(params.sunDirection));
    EnvironmentMap map{"built-in procedural sky", Image(width, height, 3)};
    // Every texel on its own (rows side by side: the same values on any thread count).
    parallelFor(height, 0, [&](int64_t j0, int64_t j1) {
        for (int j = int(j0); j < int(j1); ++j) {
            for (int i = 0; i < width; ++i) {
                const glm::dvec3 d = directionAt((i + 0.5) / width, (j + 0.5) / height);
                const glm::dvec3 radiance =
                    skyAndGround(d, params) + glm::dvec3(params.sunRadiance) *
                                                  sunCoverage(i, j, width, height, sun, double(params.sunAngularRadius));
                for (int c = 0; c < 3; ++c) map.image.at(i, j, c) = float(radiance[c]);
            }
        }
    });
    return map;
}

}  // namespace gbl
