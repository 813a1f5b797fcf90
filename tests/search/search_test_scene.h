#pragma once
// A small synthetic "reference render" for the search's unit tests, made without Vulkan: Surfaces
// with normals over the hemisphere, saturated and grey colours, metals and dielectrics, roughness
// from 0 to 1, an uncovered border; an IBL whose cube faces differ in colour; two lights.
#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "fast_eval.h"
#include "ibl_brdf_lut.h"
#include "ibl_precompute.h"

namespace gbl::test {

inline IblMaps syntheticIbl() {
    IblMaps maps;
    const glm::vec3 faceColour[6] = {{2.0f, 0.4f, 0.3f}, {0.3f, 1.5f, 0.4f}, {1.2f, 1.2f, 1.4f},
                                     {0.2f, 0.2f, 0.25f}, {0.5f, 0.6f, 2.0f}, {1.0f, 0.8f, 0.2f}};
    for (uint32_t size : {8u, 4u, 2u, 1u}) {
        CubeMip mip;
        mip.size = size;
        mip.rgba.resize(size_t(6) * size * size * 4);
        for (uint32_t f = 0; f < 6; ++f)
            for (uint32_t y = 0; y < size; ++y)
                for (uint32_t x = 0; x < size; ++x) {
                    const size_t i = ((size_t(f) * size + y) * size + x) * 4;
                    const float ramp = 0.5f + float(x + y) / float(2 * size);  // texel-level detail
                    for (int c = 0; c < 3; ++c) mip.rgba[i + size_t(c)] = faceColour[f][c] * ramp;
                    mip.rgba[i + 3] = 1.0f;
                }
        maps.prefiltered.push_back(mip);
    }
    maps.settings.prefilteredMips = 4;
    maps.irradianceSh[0] = glm::vec3(2.0f, 2.1f, 2.3f);
    maps.irradianceSh[2] = glm::vec3(0.4f, 0.4f, 0.6f);
    maps.brdfLut = shading::computeBrdfLutCpu(16, 64);
    return maps;
}

// One w x h view: a hemisphere of normals across the image, colours in bands (saturated, grey,
// metal), roughness across x, occlusion across y, some emissive; a 2-pixel uncovered border.
inline search::EvalView syntheticView(int w, int h, float azimuth = 0.0f) {
    search::EvalView v;
    v.shade.width = w;
    v.shade.height = h;
    const glm::vec3 eye(5.0f * std::sin(azimuth), 1.0f, 5.0f * std::cos(azimuth));
    v.shade.cameraPosition = eye;
    v.view = glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    glm::mat4 proj = glm::perspective(0.8f, float(w) / float(h), 0.1f, 100.0f);
    proj[1][1] *= -1.0f;
    v.invViewProj = glm::inverse(proj * v.view);
    const size_t n = size_t(w) * size_t(h);
    v.shade.covered.assign(n, 0);
    v.shade.background = Image(w, h, 4, 0.0f);
    v.depth.assign(n, 1.0f);
    v.reference.resize(n);
    const glm::vec3 palette[6] = {{0.9f, 0.1f, 0.1f}, {0.1f, 0.8f, 0.2f}, {0.1f, 0.2f, 0.9f},
                                  {0.5f, 0.5f, 0.5f}, {1.0f, 0.78f, 0.34f}, {0.95f, 0.64f, 0.54f}};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            for (int c = 0; c < 3; ++c) v.shade.background.pixels[i * 4 + size_t(c)] = 0.3f + 0.1f * float(c);
            if (x < 2 || y < 2 || x >= w - 2 || y >= h - 2) continue;
            v.shade.covered[i] = 1;
            const float u = (float(x) + 0.5f) / float(w) * 2.0f - 1.0f, t = (float(y) + 0.5f) / float(h) * 2.0f - 1.0f;
            const float r2 = std::min(u * u + t * t, 0.99f);
            Surface s;
            s.normal = glm::normalize(glm::vec3(u, -t, std::sqrt(1.0f - r2)));
            const int band = (x / 5 + y / 4) % 6;
            s.metallic = band >= 4 ? 1.0f : 0.0f;
            s.baseColor = palette[band];
            s.specular = 0.5f;
            s.specularColor = s.metallic > 0.5f ? s.baseColor : glm::vec3(0.04f);
            s.diffuseColor = s.baseColor * (1.0f - s.metallic);
            s.roughness = (float(x) + 0.5f) / float(w);
            s.occlusion = 1.0f - 0.5f * (float(y) + 0.5f) / float(h);
            s.emissive = band == 3 && (x % 7) == 0 ? glm::vec3(2.0f, 1.0f, 0.5f) : glm::vec3(0.0f);
            v.reference[i] = s;
            v.depth[i] = 0.96f + 0.03f * float(x) / float(w) + 0.005f * float(y) / float(h);
        }
    return v;
}

inline std::vector<search::ShadeLight> syntheticLights() {
    Light sun;
    sun.type = LightType::Directional;
    sun.color = glm::vec3(1.0f, 0.95f, 0.9f);
    sun.intensity = 3.0f;
    sun.direction = glm::vec3(-0.3f, -1.0f, -0.4f);
    Light lamp;
    lamp.type = LightType::Point;
    lamp.color = glm::vec3(0.6f, 0.7f, 1.0f);
    lamp.intensity = 20.0f;
    lamp.position = glm::vec3(1.0f, 2.0f, 3.0f);
    lamp.range = 30.0f;
    return search::shadeLights({sun, lamp});
}

}  // namespace gbl::test
