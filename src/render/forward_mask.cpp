#include "forward_mask.h"

#include <algorithm>
#include <stdexcept>

#include "layout.h"
#include "wiring_codegen.h"

namespace gbl {

namespace {

// A visibility buffer whose ids name the draw in a word of their own (visibility-64's split) with
// the reference's depth (layouts/reference.toml: D32, reversed Z).
constexpr const char* kForwardMaskLayout = R"toml(name = "forward-mask"
title = "The pixels of forward-drawn materials (internal)"
pipeline = "visibility-buffer"
source = { engine = "gbufferlab", talk = "internal: compare's mask of forward-drawn pixels", year = 2026 }
[depth]
format = "D32_SFLOAT"
reversed_z = true
[ids]
format = "R32G32_UINT"
triangle_bits = 32
draw_bits = 32
alpha_mask_bit = false
)toml";

const GBufferWiring& forwardMaskWiring() {
    static const GBufferWiring wiring = generateWiring(parseLayout(kForwardMaskLayout, "forward-mask.toml"));
    return wiring;
}

}  // namespace

bool hasForwardMaterials(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return !m.forward.empty(); });
}

std::vector<uint8_t> renderForwardMask(Renderer& renderer, const Scene& scene, const RenderSettings& settings) {
    if (!hasForwardMaterials(scene)) return {};
    RenderSettings s = settings;
    s.readTargetWords = true;
    s.decodeSurfaces = false;
    s.keepOnDevice = false;
    s.specularIbl = IblMode::SplitSum;  // the shading is not looked at: the cheapest mode
    s.splitSumShaderSamples = 1;
    s.bandFirstRow = 0;
    s.bandRows = 0;
    const RenderOutput out = renderer.render(forwardMaskWiring(), s);
    const size_t n = size_t(s.width) * size_t(s.height);
    if (out.targetWords.size() != 1 || out.targetWords[0].size() != 2 * n || out.depth.size() != n)
        throw std::logic_error("renderForwardMask: the visibility buffer's ids did not come back");
    std::vector<uint8_t> mask(n, 0);
    for (size_t i = 0; i < n; ++i) {
        if (out.depth[i] == 0.0f) continue;  // the reversed-Z clear: no geometry
        const uint32_t draw = out.targetWords[0][2 * i + 1];
        if (draw >= scene.draws.size()) continue;
        const int material = scene.draws[draw].material;
        if (material >= 0 && size_t(material) < scene.materials.size() && !scene.materials[size_t(material)].forward.empty())
            mask[i] = 1;
    }
    return mask;
}

}  // namespace gbl
