#pragma once
// The pixels a deferred engine draws forward: where the visible surface's material is transmissive
// or volumetric (scene.h Material::forward: KHR_materials_transmission, KHR_materials_volume).
// Deferred engines draw such materials after the G-buffer's lighting, in a forward pass (UE's
// translucency pass, HDRP's transparent and refraction passes, Bevy's transmissive phase), so no
// G-buffer layout holds them; compare leaves their pixels out of every metric
// (run_metrics.h RunMetricsOptions::excluded) and reports how many there are, rather than shading
// them as if opaque in silence.
#include <cstdint>
#include <vector>

#include "renderer.h"
#include "scene.h"

namespace gbl {

// True when some material of the scene is drawn forward.
bool hasForwardMaterials(const Scene& scene);

// One byte per pixel, row-major: 1 where the nearest surface drawn at the pixel's centre has a
// forward material, else 0. Rendered as a visibility buffer of the scene (64-bit ids: the draw of
// each pixel; the reference's reversed-Z D32 depth, so the same surface wins as in the reference)
// under `settings`' camera and size, its draw ids mapped to their materials. Empty when the scene
// has no forward material (no render at all).
std::vector<uint8_t> renderForwardMask(Renderer& renderer, const Scene& scene, const RenderSettings& settings);

}  // namespace gbl
