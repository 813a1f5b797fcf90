#include "layer_classes.h"

#include <cmath>
#include <numbers>

namespace gbl {
namespace {
// t - n (n.t) / (n.n) in double; false when it vanishes or is not finite.
bool projected(const float* t, const float* n, double out[3]) {
    const double nn = double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2];
    const double nt = double(n[0]) * t[0] + double(n[1]) * t[1] + double(n[2]) * t[2];
    const double k = nn > 0.0 ? nt / nn : 0.0;
    double len2 = 0.0;
    for (int c = 0; c < 3; ++c) {
        out[c] = double(t[c]) - k * double(n[c]);
        len2 += out[c] * out[c];
    }
    return std::isfinite(len2) && len2 > 1e-12;
}
}  // namespace

double anisotropyDirectionErrorDeg(const float* referenceTangent, const float* referenceNormal,
                                   const float* testTangent, const float* testNormal, bool& ok) {
    double a[3], b[3];
    ok = projected(referenceTangent, referenceNormal, a) && projected(testTangent, testNormal, b);
    if (!ok) return 0.0;
    const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2], cz = a[0] * b[1] - a[1] * b[0];
    const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // atan2(|a x b|, |a . b|): the acute angle between the lines, accurate near 0 (as normalAngleDeg).
    const double deg = std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), std::abs(dot)) * (180.0 / std::numbers::pi);
    ok = std::isfinite(deg);
    return ok ? deg : 0.0;
}

}  // namespace gbl
