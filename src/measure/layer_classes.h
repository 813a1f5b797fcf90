#pragma once
// The material classes of issue 40's layers, from the REFERENCE's decoded surfaces (its float32
// layers are the material's own values): which layers a pixel carries, and the per-layer errors'
// per-pixel definitions. One library (measure/) states them; the GPU evaluator's
// shaders/eval_layers.glsl mirrors them (tests/evaluate/gpu_evaluator_test holds the two together).
//
// A pixel carries
//  * a clear coat when its reference coat amount (KHR_materials_clearcoat's clearcoat) > 0,
//  * a sheen when some channel of its reference sheen colour (KHR_materials_sheen) > 0,
//  * anisotropy when its reference anisotropy strength (KHR_materials_anisotropy) > 0;
// it is "plain" when it carries none. A pixel may be in several layer classes (SheenChair's
// fabric is sheen only, a coated anisotropic car paint would be both): each class's numbers are
// over its own pixels, so the classes' pixels may add up to more than the covered pixels. The
// layer classes are only defined for a scene that has layers (SurfaceImages::hasLayers).
#include <array>
#include <cstddef>
#include <cstdint>

#include "surface_images.h"

namespace gbl {

enum class LayerClass : uint8_t { Coated, Sheen, Anisotropic, Plain };
constexpr size_t kLayerClassCount = 4;
constexpr std::array<LayerClass, kLayerClassCount> kLayerClasses = {LayerClass::Coated, LayerClass::Sheen,
                                                                    LayerClass::Anisotropic, LayerClass::Plain};
// "coated", "sheen", "anisotropic", "plain": the report's keys.
inline const char* layerClassName(LayerClass c) {
    constexpr const char* kNames[] = {"coated", "sheen", "anisotropic", "plain"};
    return kNames[size_t(c)];
}

// Bits of layerBitsAt: the layers a pixel carries (0: plain).
constexpr uint8_t kCarriesCoat = 1, kCarriesSheen = 2, kCarriesAnisotropy = 4;

// The layers pixel i of `reference` carries (it must have layers).
inline uint8_t layerBitsAt(const SurfaceImages& reference, size_t i) {
    uint8_t bits = 0;
    if (reference.coat.pixels[i] > 0.0f) bits |= kCarriesCoat;
    const float* sheen = &reference.sheenColor.pixels[i * 3];
    if (sheen[0] > 0.0f || sheen[1] > 0.0f || sheen[2] > 0.0f) bits |= kCarriesSheen;
    if (reference.anisotropyStrength.pixels[i] > 0.0f) bits |= kCarriesAnisotropy;
    return bits;
}

inline bool inLayerClass(uint8_t bits, LayerClass c) {
    switch (c) {
        case LayerClass::Coated: return (bits & kCarriesCoat) != 0;
        case LayerClass::Sheen: return (bits & kCarriesSheen) != 0;
        case LayerClass::Anisotropic: return (bits & kCarriesAnisotropy) != 0;
        case LayerClass::Plain: return bits == 0;
    }
    return false;
}

// The coat normal the lighting pass shades with: the stored one, or where that is 0 ("none", a
// layout without a coat normal, Bevy's coat) the base normal (lighting_pass.comp.glsl gblLayersOf).
inline const float* effectiveCoatNormal(const float* coatNormal, const float* normal) {
    return coatNormal[0] != 0.0f || coatNormal[1] != 0.0f || coatNormal[2] != 0.0f ? coatNormal : normal;
}

// The anisotropy direction's error in degrees: the angle between the two tangent LINES, each
// first made orthogonal to its own side's normal as the lighting pass does (gblLayersOf's
// Gram-Schmidt). Lines, not vectors: anisotropic GGX's D depends on (T.H)^2 and (B.H)^2 only, its
// height-correlated V on (T.V)^2, (B.V)^2, (T.L)^2, (B.L)^2 (Burley 2012, "Physically-Based
// Shading at Disney", appendix B.2; the KHR_materials_anisotropy README's BRDF section;
// shaders/brdf_layers.glsl), so t and -t shade alike and the error lies in [0, 90]. ok = false
// (and 0) where either tangent vanishes after the projection (|t|^2 <= 1e-12, the lighting's
// "no direction") or a value is not finite.
double anisotropyDirectionErrorDeg(const float* referenceTangent, const float* referenceNormal,
                                   const float* testTangent, const float* testNormal, bool& ok);

}  // namespace gbl
