#pragma once
// The search's fast evaluation of a layout: the reference's decoded Surfaces (rendered once on
// the GPU) go through the layout's CPU codec (cpu_codec.h: encode, decode, bit-exact with the
// GPU's wiring) in the layout's stored space, are re-lit on the CPU (cpu_reshade.h) with the
// depth the layout's depth format would hold, tone-mapped as compare tone-maps, and compared with
// the CPU re-shade of the reference itself, so what is measured is what the layout's storage
// loses. Full resolution, every view; no subsampling.
//
// Every candidate is measured on all of Evaluation's errors (the Pareto front is over all of
// them); the objective only orders the front and picks the parents to mutate.
// Objectives (lower is better; each the mean over views):
//   flip:       mean LDR-FLIP of the 8-bit tone-mapped images (compare's flip_mean);
//   psnr:       minus the tone-mapped PSNR in dB (compare's psnr_tonemapped_db);
//   attributes: mean over covered pixels of normal angle / 10 degrees + |diffuse colour error|
//               (mean of channels) + 4 |specular colour error| + |roughness error|: one degree of
//               normal counts like 0.1 of albedo, F0 four times albedo (F0 spans 0..0.16 for
//               dielectrics, albedo 0..1).
// What is not modelled: deferred lighting's light buffers (those layouts are not evaluated) and
// the IBL modes other than split-sum (compare's default).
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cpu_reshade.h"
#include "framebuffer_compression.h"
#include "layout.h"
#include "surface.h"

namespace gbl {
class LdrFlipReference;
}

namespace gbl::search {

enum class Objective { Flip, Psnr, Attributes };
const char* objectiveName(Objective o);            // "flip", "psnr", "attributes"
Objective parseObjective(const std::string& text);  // throws UserError naming --objective

// The reference rendered with another depth format: what a layout with that format sees. Depth
// precision decides visibility too (distant coplanar geometry resolves differently in D16), which
// no quantisation of the D32 depth can model, so the renderer is asked.
struct DepthVariant {
    std::string format;  // a [depth] format
    bool reversedZ = false;
    std::vector<Surface> surfaces;  // decoded, world (Y-up)
    std::vector<uint8_t> covered;
    std::vector<float> depth;
    glm::mat4 invViewProj{1.0f};      // of this variant's projection (reversed or not)
    std::vector<glm::vec3> position;  // filled by FastEvaluator
};

// One view of the reference, as rendered on the GPU and read back.
struct EvalView {
    ShadeView shade;                 // width, height, camera, coverage, background; position is filled here
    std::vector<Surface> reference;  // decoded reference Surfaces, world (Y-up)
    std::vector<float> depth;        // the reference's depth buffer (D32_SFLOAT, reversed as depthReversedZ)
    bool depthReversedZ = false;     // the reference's [depth] reversed_z (layouts/reference.toml)
    glm::mat4 view{1.0f};            // world -> view (for layouts storing in view space)
    glm::mat4 invViewProj{1.0f};     // of the reference's projection (reversed as depthReversedZ)
    // Optional: the reference under other depth formats. A layout whose depth matches one is fed
    // that variant's Surfaces, coverage and depth; otherwise the D32 depth is quantised
    // (quantizeDepth) and the D32 visibility kept.
    std::vector<DepthVariant> depthVariants;
};

// Every error the front is judged on (search_metrics.h names and orders them), each the mean over
// views; the attribute errors are over covered pixels, in compare's units (run_metrics.h): the
// decoded Surfaces against the reference's under the same depth format.
struct Evaluation {
    double error = 0.0;  // the objective's value (lower is better)
    double flip = -1.0;  // mean LDR-FLIP (-1: not computed)
    double psnr = 0.0;   // tone-mapped PSNR, dB
    double attributes = 0.0;
    double normalDeg = 0.0;        // angle, degrees
    double baseColorDe = 0.0;      // CIEDE2000
    double diffuseColorDe = 0.0;   // CIEDE2000
    double specularColorDe = 0.0;  // CIEDE2000 of F0
    double roughness = 0.0;        // |decoded - reference|
    double metallic = 0.0;
    double occlusion = 0.0;
};

class FastEvaluator {
public:
    FastEvaluator(std::vector<EvalView> views, std::vector<ShadeLight> lights, const IblMaps& ibl, Objective objective,
                  float exposure = 1.0f);
    ~FastEvaluator();

    // Single-threaded per call (the search runs several candidates at once); deterministic.
    // Throws UserError for a deferred-lighting layout (not modelled).
    Evaluation evaluate(const Layout& layout) const;
    // `threads` for the codec and the re-shade (one evaluation using the whole machine).
    Evaluation evaluate(const Layout& layout, int threads) const;

    Objective objective() const { return objective_; }
    size_t viewCount() const { return views_.size(); }
    // The CPU re-shade of the reference in view v (what candidates are compared with).
    const Image& referenceHdr(size_t v) const;
    // The CPU re-shade of `layout` in view v.
    Image renderLayout(const Layout& layout, size_t v, int threads) const;
    // View v's G-buffer words as the CPU codec encodes them (bit for bit the GPU pass's),
    // compressed by measure/framebuffer_compression.h: search --budget-model's effective bytes.
    FrameCompression compressWords(const Layout& layout, size_t v, int threads) const;

private:
    struct Prepared;
    // The re-shade of view vi; with `errors`, the decoded Surfaces' attribute errors are added to it
    // (normalDeg .. occlusion, attributes).
    // With `compression`, the encoded words are compressed into it and nothing is shaded.
    Image renderImpl(const Layout& layout, size_t vi, int threads, Evaluation* errors,
                     FrameCompression* compression = nullptr) const;
    std::vector<EvalView> views_;
    std::vector<ShadeLight> lights_;
    CpuIbl ibl_;
    Objective objective_;
    float exposure_;
    std::vector<std::unique_ptr<Prepared>> prepared_;
};

// World positions of a view from a depth buffer, as the lighting pass rebuilds them
// (worldPositionFromDepth): NDC from pixel centres, through invViewProj.
std::vector<glm::vec3> positionsFromDepth(const std::vector<float>& depth, int width, int height,
                                          const glm::mat4& invViewProj);

// The reference's D32 depth `d` (reversed Z when referenceReversedZ) as `depth`'s format would hold
// it, returned in the reference's convention: unorm formats round to 2^bits - 1 steps of the
// layout's own depth; a float depth of the other convention stores 1 - d in float32 (gbufferlab's
// reversed Z is z' = w - z: computeCameraMatrices); a float depth of the same convention is exact.
float quantizeDepth(float d, bool referenceReversedZ, const Depth& depth);

}  // namespace gbl::search
