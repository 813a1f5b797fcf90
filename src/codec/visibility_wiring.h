#pragma once
// A visibility-buffer layout (pipeline = "visibility-buffer", [ids]) turned into the renderer's
// wiring: one UINT target of ids (R32_UINT or R32G32_UINT) and depth, and GLSL that defines the
// id packing and includes shaders/visibility_buffer.glsl (writeVisibilityIds under GBUFFER_WRITE;
// the resolve's bindings and the readGBuffer prototype under GBUFFER_READ).
#include <cstddef>
#include <string>

#include "gbuffer_wiring.h"
#include "layout.h"

namespace gbl {

GBufferWiring generateVisibilityWiring(const Layout& layout);
std::string generateVisibilityWiringGlsl(const Layout& layout);

// "" when every draw index (< draws) and triangle index (< maxTrianglesPerDraw) of a scene fits
// the wiring's ids, else one line naming the layout, the count, the limit and the fix.
std::string visibilityCapacityProblem(const GBufferWiring& wiring, size_t draws, size_t maxTrianglesPerDraw);

}  // namespace gbl
