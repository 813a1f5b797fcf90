#pragma once
// gbufferlab search, GPU side: the float reference rendered once per view and read back as what
// the fast evaluation needs (search/fast_eval.h EvalView): decoded Surfaces, depth, coverage,
// the environment behind, the camera.
#include <string>
#include <vector>

#include "fast_eval.h"
#include "renderer.h"
#include "scene.h"

namespace gbl {

struct SearchReference {
    std::vector<search::EvalView> views;
    std::vector<Image> gpuHdr;  // the GPU's render of the reference per view (to validate the CPU re-shade)
};

// A depth format and its direction, for DepthVariant.
struct DepthKey {
    std::string format;
    bool reversedZ = false;
    bool operator==(const DepthKey&) const = default;
};

// The reference per camera; and, per camera, the reference again under each of `variants`
// (its layout with only [depth] changed), for layouts with that depth (fast_eval.h DepthVariant).
SearchReference renderSearchReference(Renderer& renderer, const std::vector<Camera>& cameras, uint32_t width,
                                      uint32_t height, const std::vector<DepthKey>& variants = {});

}  // namespace gbl
