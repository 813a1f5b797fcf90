#include "surface_support.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <glm/glm.hpp>


namespace gbl::test {

namespace {

glm::vec3 randomUnitVector(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    glm::vec3 n;
    do n = glm::vec3(u(rng), u(rng), u(rng)) * 2.0f - 1.0f;
    while (glm::dot(n, n) > 1.0f || glm::dot(n, n) < 1e-4f);
    return glm::normalize(n);
}

}  // namespace

// The layers come from a stream of their own, so the other members are what they were before the
// layers; a quarter of the Surfaces carry no layer at all.
std::vector<Surface> randomSurfaces(size_t count, uint32_t seed) {
    std::mt19937 rng(seed), layers(seed ^ 0x9e3779b9u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Surface> v(count);
    for (Surface& s : v) {
        s.normal = randomUnitVector(rng);
        s.baseColor = {u(rng), u(rng), u(rng)};
        s.metallic = u(rng);
        s.roughness = u(rng);
        s.specular = u(rng);
        s.specularColor = {u(rng), u(rng), u(rng)};
        s.diffuseColor = {u(rng), u(rng), u(rng)};
        s.occlusion = u(rng);
        s.emissive = glm::vec3(u(rng), u(rng), u(rng)) * 8.0f;
        s.position = (glm::vec3(u(rng), u(rng), u(rng)) * 2.0f - 1.0f) * 100.0f;
        s.position.z = u(rng) * 1.2f - 0.1f;
        if (u(layers) < 0.25f) continue;  // no layer
        s.coat = u(layers);
        s.coatRoughness = u(layers);
        s.coatNormal = randomUnitVector(layers);
        s.sheenColor = {u(layers), u(layers), u(layers)};
        s.sheenRoughness = u(layers);
        s.anisotropyStrength = u(layers);
        s.anisotropyDirection = randomUnitVector(layers);
    }
    return v;
}

ShadingModel statedModel(const Layout& layout, const Surface& s) {
    const uint32_t named = layout.selectorModels();
    auto names = [&](ShadingModel m) { return ((named >> unsigned(m)) & 1u) != 0; };
    if (names(ShadingModel::ClearCoat) && s.coat > 0.0f) return ShadingModel::ClearCoat;
    if (names(ShadingModel::Cloth) && (s.sheenColor.x > 0.0f || s.sheenColor.y > 0.0f || s.sheenColor.z > 0.0f))
        return ShadingModel::Cloth;
    if (names(ShadingModel::Anisotropic) && s.anisotropyStrength > 0.0f) return ShadingModel::Anisotropic;
    return ShadingModel::Default;
}

unsigned layerPattern(size_t i) {
    static const unsigned kPatterns[8] = {0u, 1u, 2u, 4u, 3u, 6u, 7u, 0u};
    return kPatterns[i % 8];
}

void assignLayerPatterns(std::vector<Surface>& surfaces) {
    for (size_t i = 0; i < surfaces.size(); ++i) {
        Surface& s = surfaces[i];
        const unsigned p = layerPattern(i);
        if (p & 1u) {
            // A coat has a unit normal, as the material evaluation gives it (a zero vector is no
            // normal: octahedral encodings leave its code to each implementation's NaN handling).
            s.coat = 0.05f + 0.95f * std::abs(s.coat);
            if (glm::length(s.coatNormal) == 0.0f) s.coatNormal = s.normal;
        } else {
            s.coat = 0.0f;
            s.coatRoughness = 0.0f;
            s.coatNormal = glm::vec3(0.0f);
        }
        if (p & 2u) {
            s.sheenColor = glm::vec3(0.0f, 0.05f + 0.95f * std::abs(s.sheenColor.y), std::abs(s.sheenColor.z));
        } else {
            s.sheenColor = glm::vec3(0.0f);
            s.sheenRoughness = 0.0f;
        }
        if (p & 4u) {
            s.anisotropyStrength = 0.05f + 0.95f * std::abs(s.anisotropyStrength);
            if (glm::length(s.anisotropyDirection) == 0.0f) s.anisotropyDirection = glm::vec3(1.0f, 0.0f, 0.0f);  // as the coat's
        } else {
            s.anisotropyStrength = 0.0f;
            s.anisotropyDirection = glm::vec3(0.0f);
        }
        if (i % 8 == 7) {
            s.coat = -0.0f;
            s.anisotropyStrength = -0.0f;
        }
    }
}

float* memberOf(Surface& s, Attribute a) {
    switch (a) {
        case Attribute::Normal: return &s.normal.x;
        case Attribute::BaseColor: return &s.baseColor.x;
        case Attribute::Metallic: return &s.metallic;
        case Attribute::Roughness: return &s.roughness;
        case Attribute::Specular: return &s.specular;
        case Attribute::SpecularColor: return &s.specularColor.x;
        case Attribute::DiffuseColor: return &s.diffuseColor.x;
        case Attribute::Occlusion: return &s.occlusion;
        case Attribute::Emissive: return &s.emissive.x;
        case Attribute::Position: return &s.position.x;
        case Attribute::Depth: return &s.position.z;
        case Attribute::Coat: return &s.coat;
        case Attribute::CoatRoughness: return &s.coatRoughness;
        case Attribute::CoatNormal: return &s.coatNormal.x;
        case Attribute::SheenColor: return &s.sheenColor.x;
        case Attribute::SheenRoughness: return &s.sheenRoughness;
        case Attribute::AnisotropyStrength: return &s.anisotropyStrength;
        case Attribute::AnisotropyDirection: return &s.anisotropyDirection.x;
        default: return nullptr;
    }
}

const float* memberOf(const Surface& s, Attribute a) { return memberOf(const_cast<Surface&>(s), a); }

bool coveredAt(uint32_t x, uint32_t y) { return ((x * 7 + y * 3) % 5) != 0; }

std::vector<uint8_t> coverageMask(uint32_t width, uint32_t height) {
    std::vector<uint8_t> m(size_t(width) * height);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) m[size_t(y) * width + x] = coveredAt(x, y);
    return m;
}

bool within4Ulp(float a, float b) {
    if (a == b) return true;
    return std::abs(a - b) <= 4.0f * std::numeric_limits<float>::epsilon() * std::max(1.0f, std::abs(b));
}

}  // namespace gbl::test
