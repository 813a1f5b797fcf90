#pragma once
// A visibility-buffer layout (pipeline = "visibility-buffer", [ids]) turned into the renderer's
// wiring: one UINT target of ids (R32_UINT or R32G32_UINT) and depth, and GLSL that defines the
// id packing and includes shaders/visibility_buffer.glsl (writeVisibilityIds under GBUFFER_WRITE;
// the resolve's bindings and the readGBuffer prototype under GBUFFER_READ). The packing's C++
// twin is here too (packVisibilityIds, unpackVisibilityIds), held bit for bit against the GLSL by
// tests/codec/visibility_bits_test.cpp and against UE's and Bevy's packings by visibility_ids_test.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gbuffer_wiring.h"
#include "layout.h"

namespace gbl {

GBufferWiring generateVisibilityWiring(const Layout& layout);
std::string generateVisibilityWiringGlsl(const Layout& layout);

// "" when every id of a scene fits the wiring's ids, else one line naming the layout, the count,
// the limit and the fix. `drawTriangles`: each draw's triangle count. Without clusters the draw
// field counts draws (plus draw_offset) and the triangle field a draw's triangles; with clusters
// ([ids] cluster_triangles) the draw field counts the scene's clusters (plus draw_offset), and
// a draw of any size fits (its triangles go to clusters of cluster_triangles).
std::string visibilityCapacityProblem(const GBufferWiring& wiring, const std::vector<size_t>& drawTriangles);

// Clusters ([ids] cluster_triangles = n): each draw is split into ceil(triangles / n) clusters,
// cluster c of a draw holding its triangles [c n, c n + n); the scene's clusters are numbered in
// draw order. visibilityFirstIds: per draw, the id its fragments add their cluster to (its first
// cluster), or with no clusters the draw's index. visibilityClusterTable: per cluster (draw,
// first triangle), which the resolve reads to map a cluster back (shaders/visibility_buffer.glsl).
std::vector<uint32_t> visibilityFirstIds(const GBufferWiring::VisibilityIds& ids,
                                         const std::vector<size_t>& drawTriangles);
std::vector<std::array<uint32_t, 2>> visibilityClusterTable(uint32_t clusterTriangles,
                                                            const std::vector<size_t>& drawTriangles);

// The fragment's ids and what its word(s) hold: the C++ twin of visibility_buffer.glsl's
// visibilityFields + packVisibilityIds (`firstId` from visibilityFirstIds, `primitive` the draw's
// gl_PrimitiveID, `depth` the window depth gl_FragCoord.z) and of unpackVisibilityIds (x the draw
// or cluster index, offset removed; y the triangle field; z the alpha-mask flag).
struct VisibilityFields {
    uint32_t draw = 0;      // the draw, or with clusters the cluster
    uint32_t triangle = 0;  // within the draw, or with clusters within the cluster
};
VisibilityFields visibilityFields(const GBufferWiring::VisibilityIds& ids, uint32_t firstId, uint32_t primitive);
std::array<uint32_t, 2> packVisibilityIds(const GBufferWiring::VisibilityIds& ids, uint32_t draw, uint32_t triangle,
                                          bool alphaMasked, float depth);
std::array<uint32_t, 3> unpackVisibilityIds(const GBufferWiring::VisibilityIds& ids, std::array<uint32_t, 2> words);

}  // namespace gbl
