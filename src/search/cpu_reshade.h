#pragma once
// The lighting pass on the CPU, for the search's fast evaluation: a decoded Surface image lit as
// shaders/lighting_pass.comp.glsl lights it (deferred shading, split-sum IBL, the default
// compare mode): every analytic light through shading::evaluateDirectLightMode (Karis' Fresnel),
// then the image-based light of shaders/image_based_light.glsl (IblMode::SplitSum):
// prefilteredRadiance(R, roughness) * envBRDF(F0, LUT(NoV, roughness)) plus Lambert diffuse of
// the SH9 irradiance, times occlusion, plus emissive. No shadows: the GPU pass has none either.
//
// Texture filtering is modelled, not copied: the cube is sampled trilinearly per face with
// clamp-to-edge (the GPU's seamless cube filtering blends across faces: the two differ only
// within half a texel of a face edge), the LUT bilinearly. tests/search/search_reshade_test
// measures the difference against the GPU render of the reference and states it.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "ibl_precompute.h"
#include "image.h"
#include "scene.h"
#include "surface.h"

namespace gbl::search {

// One analytic light as the lighting pass reads it (render/gpu_scene.cpp packLights).
struct ShadeLight {
    int type = 0;  // LightType
    glm::vec3 radiance{0.0f};  // colour * intensity
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit, the direction the light travels
    float range = 0.0f;
    float spotScale = 0.0f, spotOffset = 0.0f;  // KHR_lights_punctual
};
std::vector<ShadeLight> shadeLights(const std::vector<Light>& lights);

// The split-sum IBL on the CPU: pre-filtered cube mips, SH9 irradiance, BRDF LUT (IblMaps).
class CpuIbl {
public:
    explicit CpuIbl(const IblMaps& maps, float environmentIntensity = 1.0f);
    // Pre-filtered radiance along R at roughness (mip = roughness (mips - 1)), trilinear.
    glm::vec3 prefiltered(glm::vec3 R, float roughness) const;
    glm::vec2 lut(float NoV, float roughness) const;
    glm::vec3 irradiance(glm::vec3 n) const;
    // Cube face and texel coordinates (in texels, centres at +0.5) of a direction, Vulkan's
    // major-axis rule (spec, "Cube Map Face Selection"); exposed for the test.
    static void cubeCoordinates(glm::vec3 dir, uint32_t size, uint32_t& face, float& x, float& y);

private:
    glm::vec3 sampleMip(size_t mip, glm::vec3 dir) const;
    std::vector<CubeMip> mips_;
    std::array<glm::vec3, 9> sh_{};
    Image lut_;
    float intensity_ = 1.0f;
};

// What one view needs beyond the Surfaces: where each pixel is and where the camera is.
struct ShadeView {
    int width = 0, height = 0;
    glm::vec3 cameraPosition{0.0f};
    std::vector<glm::vec3> position;  // world, per pixel (unused where not covered)
    std::vector<uint8_t> covered;
    Image background;  // RGBA: what pixels without geometry show (the environment, layout-independent)
};

// Radiance of one covered pixel: direct lights + IBL * occlusion + emissive (+ forwardEmissive,
// the unquantised emissive of emissive = "forward").
glm::vec3 shadePixel(const Surface& s, glm::vec3 position, glm::vec3 cameraPosition,
                     const std::vector<ShadeLight>& lights, const CpuIbl& ibl, glm::vec3 forwardEmissive);

// The whole image (RGBA, alpha = coverage), rows in parallel over `threads`: `surfaces` lit at
// `positions` where `covered`, view.background elsewhere. `forwardEmissive`, when given, adds
// each pixel's emissive from those Surfaces (emissive = "forward": unquantised).
Image reshade(const ShadeView& view, const std::vector<uint8_t>& covered, const std::vector<Surface>& surfaces,
              const std::vector<glm::vec3>& positions, const std::vector<ShadeLight>& lights, const CpuIbl& ibl,
              const std::vector<Surface>* forwardEmissive, int threads);

}  // namespace gbl::search
