#pragma once
// What the tests that hold encoders to each other share (codec/gpu_cpu_bits_test,
// codec/layout_export_gpu_test, codec/cpu_codec_test, ...): seeded random Surfaces, a Surface's
// member for an attribute, the coverage pattern of the decode checks, and their 4-ulp comparison;
// and the shipped layouts (layout_files.h).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "layout.h"
#include "layout_files.h"
#include "surface.h"

namespace gbl::test {

// Seeded random Surfaces: every member uniform over its range, normals unit and uniform in
// direction, emissive up to 8, positions within +-100 with z mostly in [0, 1] and some outside (a
// stored window depth rides in position.z: wiring_plan.h). The layers (coat, coat roughness, sheen
// colour and roughness, anisotropy strength uniform in [0, 1], the coat normal and the anisotropy
// direction unit and uniform in direction) are 0 on a quarter of the Surfaces.
std::vector<Surface> randomSurfaces(size_t count, uint32_t seed);

// The layers of Surface i set by pattern i % 8, so that every shading model of a selector's rule
// (src/layout/shading_models.cpp) and every tie between them occurs: 0 none, 1 coat only, 2 sheen
// only (its colour's red 0), 3 anisotropy only, 4 coat and sheen, 5 sheen and anisotropy, 6 all
// three, 7 none but with -0.0 coat and strength (not > 0). Each layer kept is the Surface's own value
// (made > 0), each dropped is 0.
void assignLayerPatterns(std::vector<Surface>& surfaces);
// Which layers pattern i % 8 gives Surface i: bit 0 coat, 1 sheen, 2 anisotropy.
unsigned layerPattern(size_t i);

// The model a selector layout gives Surface s, restated from layouts/README.md ("Which model a pixel
// gets"), not taken from src/layout/shading_models.cpp: the first of clear_coat (coat > 0), cloth
// (some sheen colour component > 0), anisotropic (anisotropy strength > 0) that the selector
// names, else default. A layout without a selector: default.
ShadingModel statedModel(const Layout& layout, const Surface& s);
// Whether field f holds its attribute on a pixel of model m (an unconditional field always does).
inline bool fieldHolds(const Field& f, ShadingModel m) { return !f.conditional() || ((f.models >> unsigned(m)) & 1u); }

// The Surface member that holds `a` (its first component), nullptr for an attribute a Surface
// does not hold; a stored window depth rides in position.z (wiring_plan.h).
float* memberOf(Surface& s, Attribute a);
const float* memberOf(const Surface& s, Attribute a);

// The pixels "with geometry" of the decode checks: a fixed pattern that the test shaders mirror
// ((x * 7 + y * 3) % 5 != 0), so that reconstructions that skip pixels without geometry are held too.
bool coveredAt(uint32_t x, uint32_t y);
// coveredAt over a width x height image, row by row (CpuGBuffer::covered).
std::vector<uint8_t> coverageMask(uint32_t width, uint32_t height);

// GPU and CPU decodes agree: equal, or within 4 float epsilons of b (relative above 1).
bool within4Ulp(float a, float b);

}  // namespace gbl::test
