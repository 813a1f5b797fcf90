#include "ibl_brdf_lut.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "ibl_math.h"

namespace gbl::shading {

Image computeBrdfLutCpu(int size, int samples, BrdfLutEstimator estimator) {
    if (size < 1 || samples < 1)
        throw std::invalid_argument("computeBrdfLutCpu: size and samples must be >= 1 (got size " +
                                    std::to_string(size) + ", samples " + std::to_string(samples) + ")");
    Image lut(size, size, 2);
    for (int y = 0; y < size; ++y) {
        float roughness = (float(y) + 0.5f) / float(size);
        for (int x = 0; x < size; ++x) {
            float NoV = (float(x) + 0.5f) / float(size);
            glm::vec2 AB = estimator == BrdfLutEstimator::VisibleNormals
                               ? integrateBRDFVisible(roughness, NoV, uint32_t(samples))
                               : integrateBRDF(roughness, NoV, uint32_t(samples));
            lut.at(x, y, 0) = AB.x;
            lut.at(x, y, 1) = AB.y;
        }
    }
    return lut;
}

glm::vec2 sampleBrdfLut(const Image& lut, float NoV, float roughness) {
    // Texel-centre coordinates: u * size - 0.5, clamped to the edge texels.
    float fx = std::clamp(NoV * float(lut.width) - 0.5f, 0.0f, float(lut.width - 1));
    float fy = std::clamp(roughness * float(lut.height) - 0.5f, 0.0f, float(lut.height - 1));
    int x0 = int(fx);
    int y0 = int(fy);
    int x1 = std::min(x0 + 1, lut.width - 1);
    int y1 = std::min(y0 + 1, lut.height - 1);
    float tx = fx - float(x0);
    float ty = fy - float(y0);
    glm::vec2 result;
    for (int c = 0; c < 2; ++c) {
        float top = lut.at(x0, y0, c) * (1.0f - tx) + lut.at(x1, y0, c) * tx;
        float bottom = lut.at(x0, y1, c) * (1.0f - tx) + lut.at(x1, y1, c) * tx;
        result[c] = top * (1.0f - ty) + bottom * ty;
    }
    return result;
}

}  // namespace gbl::shading
