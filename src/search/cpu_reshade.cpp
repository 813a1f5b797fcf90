#include "cpu_reshade.h"

#include <algorithm>
#include <cmath>

#include "brdf.h"
#include "brdf_layers.h"
#include "ibl_math.h"
#include "sheen_albedo.h"
#include "parallel_for.h"

namespace gbl::search {

std::vector<ShadeLight> shadeLights(const std::vector<Light>& lights) {
    std::vector<ShadeLight> out;
    for (const Light& l : lights) {
        ShadeLight s;
        s.type = int(l.type);
        s.radiance = l.color * l.intensity;
        s.position = l.position;
        s.direction = glm::normalize(l.direction);
        s.range = l.range;
        // KHR_lights_punctual's cone attenuation, as render/gpu_scene.cpp packs it.
        s.spotScale = 1.0f / std::max(0.001f, std::cos(l.innerConeAngle) - std::cos(l.outerConeAngle));
        s.spotOffset = -std::cos(l.outerConeAngle) * s.spotScale;
        out.push_back(s);
    }
    return out;
}

CpuIbl::CpuIbl(const IblMaps& maps, float environmentIntensity)
    : mips_(maps.prefiltered), sh_(maps.irradianceSh), lut_(maps.brdfLut), intensity_(environmentIntensity) {}

void CpuIbl::cubeCoordinates(glm::vec3 d, uint32_t size, uint32_t& face, float& x, float& y) {
    // Vulkan spec, "Cube Map Face Selection and Transformations": the major axis picks the face,
    // (sc, tc) per face, s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2.
    const glm::vec3 a = glm::abs(d);
    float sc, tc, ma;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x >= 0.0f ? 0u : 1u;
        ma = a.x;
        sc = d.x >= 0.0f ? -d.z : d.z;
        tc = -d.y;
    } else if (a.y >= a.z) {
        face = d.y >= 0.0f ? 2u : 3u;
        ma = a.y;
        sc = d.x;
        tc = d.y >= 0.0f ? d.z : -d.z;
    } else {
        face = d.z >= 0.0f ? 4u : 5u;
        ma = a.z;
        sc = d.z >= 0.0f ? d.x : -d.x;
        tc = -d.y;
    }
    const float inv = ma > 0.0f ? 1.0f / ma : 0.0f;
    x = (sc * inv + 1.0f) * 0.5f * float(size);
    y = (tc * inv + 1.0f) * 0.5f * float(size);
}

glm::vec3 CpuIbl::sampleMip(size_t mip, glm::vec3 dir) const {
    const CubeMip& m = mips_[mip];
    uint32_t face;
    float x, y;
    cubeCoordinates(dir, m.size, face, x, y);
    // Bilinear between texel centres, clamped to the face's edge texels.
    const float fx = std::clamp(x - 0.5f, 0.0f, float(m.size - 1)), fy = std::clamp(y - 0.5f, 0.0f, float(m.size - 1));
    const uint32_t x0 = uint32_t(fx), y0 = uint32_t(fy);
    const uint32_t x1 = std::min(x0 + 1, m.size - 1), y1 = std::min(y0 + 1, m.size - 1);
    const float tx = fx - float(x0), ty = fy - float(y0);
    auto texel = [&](uint32_t tx_, uint32_t ty_) {
        const size_t i = ((size_t(face) * m.size + ty_) * m.size + tx_) * 4;
        return glm::vec3(m.rgba[i], m.rgba[i + 1], m.rgba[i + 2]);
    };
    return glm::mix(glm::mix(texel(x0, y0), texel(x1, y0), tx), glm::mix(texel(x0, y1), texel(x1, y1), tx), ty);
}

glm::vec3 CpuIbl::prefiltered(glm::vec3 R, float roughness) const {
    const float lod = std::clamp(shading::mipFromRoughness(roughness, float(mips_.size())), 0.0f,
                                 float(mips_.size() - 1));
    const size_t lo = size_t(lod);
    const size_t hi = std::min(lo + 1, mips_.size() - 1);
    const float t = lod - float(lo);
    const glm::vec3 a = sampleMip(lo, R);
    return (t > 0.0f ? glm::mix(a, sampleMip(hi, R), t) : a) * intensity_;
}

glm::vec2 CpuIbl::lut(float NoV, float roughness) const {
    const int n = lut_.width;
    const float fx = std::clamp(NoV * float(n) - 0.5f, 0.0f, float(n - 1));
    const float fy = std::clamp(roughness * float(lut_.height) - 0.5f, 0.0f, float(lut_.height - 1));
    const int x0 = int(fx), y0 = int(fy);
    const int x1 = std::min(x0 + 1, n - 1), y1 = std::min(y0 + 1, lut_.height - 1);
    const float tx = fx - float(x0), ty = fy - float(y0);
    auto texel = [&](int x, int y) { return glm::vec2(lut_.at(x, y, 0), lut_.at(x, y, 1)); };
    return glm::mix(glm::mix(texel(x0, y0), texel(x1, y0), tx), glm::mix(texel(x0, y1), texel(x1, y1), tx), ty);
}

glm::vec3 CpuIbl::irradiance(glm::vec3 n) const {
    // shaders/image_based_light.glsl irradianceFromSh, term by term.
    glm::vec3 e = sh_[0] * 0.282095f;
    e += sh_[1] * (0.488603f * n.y);
    e += sh_[2] * (0.488603f * n.z);
    e += sh_[3] * (0.488603f * n.x);
    e += sh_[4] * (1.092548f * n.x * n.y);
    e += sh_[5] * (1.092548f * n.y * n.z);
    e += sh_[6] * (0.315392f * (3.0f * n.z * n.z - 1.0f));
    e += sh_[7] * (1.092548f * n.x * n.z);
    e += sh_[8] * (0.546274f * (n.x * n.x - n.y * n.y));
    return glm::max(e, glm::vec3(0.0f)) * intensity_;
}

namespace {

// lighting_pass.comp.glsl lightRadianceAndDirection.
glm::vec3 lightRadianceAndDirection(const ShadeLight& light, glm::vec3 position, glm::vec3& L) {
    if (light.type == int(LightType::Directional)) {
        L = -light.direction;
        return light.radiance;
    }
    const glm::vec3 toLight = light.position - position;
    const float d2 = std::max(glm::dot(toLight, toLight), 1e-8f);
    L = toLight / std::sqrt(d2);
    float falloff = 1.0f / d2;
    if (light.range > 0.0f) {
        const float r = d2 / (light.range * light.range);
        const float window = std::clamp(1.0f - r * r, 0.0f, 1.0f);
        falloff *= window * window;
    }
    if (light.type == int(LightType::Spot)) {
        const float cd = glm::dot(light.direction, -L);
        const float a = std::clamp(cd * light.spotScale + light.spotOffset, 0.0f, 1.0f);
        falloff *= a * a;
    }
    return light.radiance * falloff;
}

// lighting_pass.comp.glsl gblLayersOf: the decoded Surface's layers, "no layer" where 0.
shading::Layers layersOf(const Surface& s, glm::vec3 N) {
    shading::Layers ly;
    ly.coat = std::clamp(s.coat, 0.0f, 1.0f);
    ly.coatRoughness = std::clamp(s.coatRoughness, 0.0f, 1.0f);
    ly.coatNormal = glm::dot(s.coatNormal, s.coatNormal) > 0.0f ? glm::normalize(s.coatNormal) : N;
    ly.sheenColor = glm::max(s.sheenColor, glm::vec3(0.0f));
    ly.sheenRoughness = std::clamp(s.sheenRoughness, 0.0f, 1.0f);
    const glm::vec3 t = s.anisotropyDirection - N * glm::dot(N, s.anisotropyDirection);
    const float tt = glm::dot(t, t);
    const bool aniso = tt > 1e-12f;
    ly.anisotropy = aniso ? std::clamp(s.anisotropyStrength, 0.0f, 1.0f) : 0.0f;
    ly.anisotropyT = aniso ? t * (1.0f / std::sqrt(tt)) : glm::vec3(0.0f);
    ly.anisotropyB = glm::cross(N, ly.anisotropyT);
    return ly;
}

bool hasLayers(const shading::Layers& ly) {
    return ly.coat > 0.0f || shading::max3(ly.sheenColor) > 0.0f || ly.anisotropy > 0.0f;
}

// The layered pixel as lighting_pass.comp.glsl shades it with GBL_LAYERS, the split-sum IBL of
// image_based_light.glsl evaluateImageBasedLightLayered.
glm::vec3 shadeLayeredPixel(const Surface& s, glm::vec3 N, glm::vec3 V, const shading::Layers& ly, glm::vec3 position,
                            const std::vector<ShadeLight>& lights, const CpuIbl& ibl, glm::vec3 forwardEmissive) {
    const shading::SheenAlbedoTable& table = shading::sheenAlbedoTable();
    const bool sheen = shading::max3(ly.sheenColor) > 0.0f;
    const float sheenV = sheen ? table.lookup(std::clamp(glm::dot(N, V), 0.0f, 1.0f), ly.sheenRoughness) : 0.0f;
    glm::vec3 color(0.0f);
    for (const ShadeLight& light : lights) {
        glm::vec3 L;
        const glm::vec3 radiance = lightRadianceAndDirection(light, position, L);
        const float sheenL = sheen ? table.lookup(std::clamp(glm::dot(N, L), 0.0f, 1.0f), ly.sheenRoughness) : 0.0f;
        color += shading::evaluateDirectLightLayeredMode(N, V, L, s.diffuseColor, s.specularColor, s.roughness, ly, sheenV,
                                                         sheenL, radiance, shading::FRESNEL_KARIS);
    }
    const float roughness = std::clamp(s.roughness, 0.0f, 1.0f);
    const float NoV = std::max(std::clamp(glm::dot(N, V), 0.0f, 1.0f), shading::kMinIblNoV);
    const glm::vec3 Rn = 2.0f * glm::dot(N, V) * N - V;  // reflect(-V, N)
    const glm::vec3 R = ly.anisotropy > 0.0f
                            ? shading::anisotropicReflection(N, V, ly.anisotropyB, ly.anisotropy, roughness)
                            : Rn;
    const glm::vec3 specular = ibl.prefiltered(R, roughness) * shading::envBRDF(s.specularColor, ibl.lut(NoV, roughness));
    const glm::vec3 diffuse = s.diffuseColor * (1.0f / shading::kPi) * ibl.irradiance(N);
    glm::vec3 indirect = diffuse + specular;
    if (sheen) {
        const float sheenIbl = table.lookup(NoV, ly.sheenRoughness);  // the IBL's NoV floor, as the GLSL's
        indirect = ly.sheenColor * sheenIbl * ibl.prefiltered(Rn, ly.sheenRoughness) +
                   indirect * (1.0f - shading::max3(ly.sheenColor) * sheenIbl);
    }
    if (ly.coat > 0.0f) {
        const float NcoV = std::max(shading::coatNoV(ly.coatNormal, V), shading::kMinIblNoV);
        const float fc = ly.coat * shading::coatFresnel(NcoV);
        const glm::vec3 Rc = 2.0f * glm::dot(ly.coatNormal, V) * ly.coatNormal - V;
        const glm::vec2 AB = ibl.lut(NcoV, ly.coatRoughness);
        indirect = indirect * (1.0f - fc) + fc * ibl.prefiltered(Rc, ly.coatRoughness) * (AB.x + AB.y);
    }
    color += indirect * s.occlusion;
    return color + shading::coatedEmission(s.emissive, ly, V) + shading::coatedEmission(forwardEmissive, ly, V);
}

}  // namespace

glm::vec3 shadePixel(const Surface& s, glm::vec3 position, glm::vec3 cameraPosition,
                     const std::vector<ShadeLight>& lights, const CpuIbl& ibl, glm::vec3 forwardEmissive) {
    const glm::vec3 V = glm::normalize(cameraPosition - position);
    const glm::vec3 N = glm::normalize(s.normal);
    if (const shading::Layers ly = layersOf(s, N); hasLayers(ly))
        return shadeLayeredPixel(s, N, V, ly, position, lights, ibl, forwardEmissive);
    glm::vec3 color(0.0f);
    for (const ShadeLight& light : lights) {
        glm::vec3 L;
        const glm::vec3 radiance = lightRadianceAndDirection(light, position, L);
        color += shading::evaluateDirectLightMode(N, V, L, s.diffuseColor, s.specularColor, s.roughness, radiance,
                                                  shading::FRESNEL_KARIS);
    }
    // image_based_light.glsl evaluateImageBasedLight, GBL_IBL_SPLIT_SUM, diffuse IBL on.
    const float roughness = std::clamp(s.roughness, 0.0f, 1.0f);
    const float NoV = std::max(std::clamp(glm::dot(N, V), 0.0f, 1.0f), shading::kMinIblNoV);
    const glm::vec3 R = 2.0f * glm::dot(N, V) * N - V;  // reflect(-V, N)
    const glm::vec3 specular = ibl.prefiltered(R, roughness) * shading::envBRDF(s.specularColor, ibl.lut(NoV, roughness));
    const glm::vec3 diffuse = s.diffuseColor * (1.0f / shading::kPi) * ibl.irradiance(N);
    color += (diffuse + specular) * s.occlusion;
    return color + s.emissive + forwardEmissive;
}

Image reshade(const ShadeView& view, const std::vector<uint8_t>& covered, const std::vector<Surface>& surfaces,
              const std::vector<glm::vec3>& positions, const std::vector<ShadeLight>& lights, const CpuIbl& ibl,
              const std::vector<Surface>* forwardEmissive, int threads) {
    Image out(view.width, view.height, 4);
    parallelFor(view.height, threads, [&](int64_t y0, int64_t y1) {
        for (int64_t y = y0; y < y1; ++y)
            for (int x = 0; x < view.width; ++x) {
                const size_t i = size_t(y) * size_t(view.width) + size_t(x);
                float* o = &out.pixels[i * 4];
                if (!covered[i]) {
                    for (int c = 0; c < 4; ++c) o[c] = view.background.pixels[i * 4 + c];
                    continue;
                }
                const glm::vec3 c = shadePixel(surfaces[i], positions[i], view.cameraPosition, lights, ibl,
                                               forwardEmissive ? (*forwardEmissive)[i].emissive : glm::vec3(0.0f));
                o[0] = c.r;
                o[1] = c.g;
                o[2] = c.b;
                o[3] = 1.0f;
            }
    });
    return out;
}

}  // namespace gbl::search
