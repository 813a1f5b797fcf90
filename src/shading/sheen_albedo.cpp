// The sheen BRDF's directional albedo table (sheen_albedo.h).
#include "sheen_albedo.h"

#include <algorithm>
#include <cmath>

#include "brdf.h"
#include "brdf_layers.h"
#include "parallel_for.h"

namespace gbl::shading {

double sheenAlbedoQuadrature(float NoV, float sheenRoughness, int tSteps, int phiSteps) {
    NoV = std::clamp(NoV, kMinSheenNoV, 1.0f);
    const glm::vec3 V(std::sqrt(std::max(1.0f - NoV * NoV, 0.0f)), 0.0f, NoV);
    double sum = 0.0;
    for (int a = 0; a < tSteps; ++a) {
        const double t = (a + 0.5) / tSteps;
        const float NoL = float(t * t);
        const float sinL = std::sqrt(std::max(1.0f - NoL * NoL, 0.0f));
        double ring = 0.0;
        for (int b = 0; b < phiSteps; ++b) {
            const float phi = float((b + 0.5) / phiSteps * 3.14159265358979323846);
            const glm::vec3 L(sinL * std::cos(phi), sinL * std::sin(phi), NoL);
            const glm::vec3 H = glm::normalize(V + L);
            ring += sheenBrdf(std::clamp(H.z, 0.0f, 1.0f), NoV, NoL, sheenRoughness);
        }
        // dL = dNoL dphi = 2 t dt dphi; phi over [0, pi], doubled.
        sum += ring * double(NoL) * 2.0 * t;
    }
    return sum * 2.0 * (3.14159265358979323846 / phiSteps) * (1.0 / tSteps);
}

SheenAlbedoTable buildSheenAlbedoTable(int size, int tSteps, int phiSteps) {
    SheenAlbedoTable table;
    table.size = size;
    table.values.assign(size_t(size) * size_t(size), 0.0f);
    parallelFor(size, 0, [&](int64_t j0, int64_t j1) {
        for (int64_t j = j0; j < j1; ++j)
            for (int i = 0; i < size; ++i)
                table.values[size_t(j) * size_t(size) + size_t(i)] = float(std::min(
                    sheenAlbedoQuadrature(float((i + 0.5) / size), float((j + 0.5) / size), tSteps, phiSteps), 1.0));
    });
    return table;
}

float SheenAlbedoTable::lookup(float NoV, float sheenRoughness) const {
    const float fx = std::clamp(NoV * float(size) - 0.5f, 0.0f, float(size - 1));
    const float fy = std::clamp(sheenRoughness * float(size) - 0.5f, 0.0f, float(size - 1));
    const int x0 = int(fx), y0 = int(fy);
    const int x1 = std::min(x0 + 1, size - 1), y1 = std::min(y0 + 1, size - 1);
    const float tx = fx - float(x0), ty = fy - float(y0);
    auto at = [&](int x, int y) { return values[size_t(y) * size_t(size) + size_t(x)]; };
    const float top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * tx;
    const float bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * tx;
    return top + (bottom - top) * ty;
}

const SheenAlbedoTable& sheenAlbedoTable() {
    static const SheenAlbedoTable table = buildSheenAlbedoTable(kSheenAlbedoSize, 96, 48);
    return table;
}

}  // namespace gbl::shading
