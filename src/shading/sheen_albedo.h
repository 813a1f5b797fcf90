#pragma once
// The directional albedo of the sheen BRDF, E(NoV, sheenRoughness) = integral over the hemisphere of
// sheenBrdf(L, V) NoL dL (brdf_layers.h: Charlie D and V of KHR_materials_sheen), the table the
// albedo scaling of the base reads [KHR_materials_sheen README, "Albedo-scaling technique": "The
// values E(x) can be looked up in a table"; the Enterprise PBR Shading Model tabulates it 32 x 32
// in its section 6.2.3]. Built here by quadrature, once per process; the lighting pass reads it
// as a 32 x 32 R32F texture (bilinear, clamp to edge), the CPU shading through lookup().
// tests/shading/sheen_albedo_test.cpp holds it to a brute-force Monte Carlo integral of an
// independent Charlie implementation.
#include <vector>

namespace gbl::shading {

inline constexpr int kSheenAlbedoSize = 32;

struct SheenAlbedoTable {
    int size = 0;
    // values[j * size + i]: E at NoV = (i + 0.5) / size, sheen roughness = (j + 0.5) / size.
    std::vector<float> values;
    // Bilinear between texel centres, clamped to the edge texels: the GPU's linear sampling of the
    // texture with clamp-to-edge at u = NoV, v = sheen roughness.
    float lookup(float NoV, float sheenRoughness) const;
};

// E(NoV, sheenRoughness) by the midpoint rule over L in (t, phi), NoL = t^2 (nodes dense at the
// horizon, where the Charlie lobe of a grazing view lies), phi in [0, pi] doubled (the integrand
// is even in phi), of the float sheenBrdf the shaders evaluate; accumulated in double.
double sheenAlbedoQuadrature(float NoV, float sheenRoughness, int tSteps, int phiSteps);
// The table of it, each entry clamped to at most 1: at grazing NoV and low sheen roughness the
// Charlie lobe's albedo exceeds 1 (2.8 at NoV 0.016, roughness 0.045; 1.08 at roughness 0.2), and
// 1 - max3(c) E would turn the base's scaling negative. (The Khronos Sample Viewer's table, an
// 8-bit PNG, holds no value above 1 either.)
SheenAlbedoTable buildSheenAlbedoTable(int size, int tSteps, int phiSteps);
// The table the renderer uploads: size kSheenAlbedoSize, 96 x 48 nodes per entry (within 1e-4 of
// 1024 x 512 nodes everywhere, the worst at NoV 0.016, roughness 0.95); built on first use
// (thread-safe), about 0.35 s of CPU.
const SheenAlbedoTable& sheenAlbedoTable();

}  // namespace gbl::shading
