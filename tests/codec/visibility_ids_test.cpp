// The 64-bit visibility buffers of shipped engines, each reimplemented here from its source, against
// gbufferlab's packing (the C++ twin of shaders/visibility_buffer.glsl, visibility_wiring.h) for the
// layouts that describe them, bit for bit on 2^20 random inputs and every pair of edge values; and
// the properties the rows rest on: a 64-bit max keeps the nearest fragment (what the depth test
// gbufferlab rasterises with keeps), and clusters map back to their draw and triangle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <vector>

#include "layout_catalog.h"
#include "layout_files.h"
#include "visibility_wiring.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

uint32_t asuint(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

// ---- Unreal Engine 5.3.2's Nanite (Mephisto1024/Toon_Engine @1a10ef19), written out from reading:
// NaniteRasterizer.usf:1395   PixelValue = ((VisibleIndex + 1) << 7) | TriIndex
// NaniteWritePixel.ush:48-53  Depth = saturate(Depth); DepthInt = asuint(Depth)
// NaniteRasterizer.usf:1499-1500 and D3DCommon.ush:113-121
//                             PackUlongType(uint2(PixelValue, DepthInt)) = (uint64(y) << 32) | x
// NaniteDataDecode.ush:593-606 UnpackVisPixel: x = (uint)Pixel, y = Pixel >> 32;
//                             VisibleClusterIndex = (x >> 7) - 1; TriIndex = x & 0x7F; DepthInt = y
float saturate(float x) { return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x); }

uint64_t nanitePackVisPixel(uint32_t visibleIndex, uint32_t triIndex, float deviceZ) {
    const uint32_t pixelValue = ((visibleIndex + 1u) << 7) | triIndex;
    const uint32_t depthInt = asuint(saturate(deviceZ));
    return (uint64_t(depthInt) << 32) | pixelValue;
}

struct NaniteVisPixel {
    uint32_t depthInt, visibleClusterIndex, triIndex;
};
NaniteVisPixel naniteUnpackVisPixel(uint64_t pixel) {
    const uint32_t x = uint32_t(pixel), y = uint32_t(pixel >> 32);
    NaniteVisPixel p{y, x >> 7, x & 0x7Fu};
    p.visibleClusterIndex--;
    return p;
}

// ---- Bevy 0.16.0 (bevyengine/bevy @e9418b38), crates/bevy_pbr/src/meshlet/:
// visibility_buffer_hardware_raster.wgsl:50   packed_ids = (cluster_id << 7u) | triangle_id
// visibility_buffer_hardware_raster.wgsl:57-59 depth = bitcast<u32>(position.z);
//                                             visibility = (u64(depth) << 32u) | u64(packed_ids)
// visibility_buffer_resolve.wgsl:107-112     cluster_id = packed_ids >> 7u;
//                                             triangle_id = extractBits(packed_ids, 0u, 7u)
// resolve_render_targets.wgsl:16-23          depth = u32(visibility >> 32u); 0 = no geometry
uint64_t bevyPackVisibility(uint32_t clusterId, uint32_t triangleId, float z) {
    const uint32_t packedIds = (clusterId << 7u) | triangleId;
    return (uint64_t(asuint(z)) << 32) | packedIds;
}

struct BevyVisibility {
    uint32_t depth, clusterId, triangleId;
};
BevyVisibility bevyResolve(uint64_t visibility) {
    const uint32_t packedIds = uint32_t(visibility);
    return {uint32_t(visibility >> 32), packedIds >> 7u, packedIds & 0x7Fu};
}

GBufferWiring::VisibilityIds idsOf(const char* name) {
    return generateWiring(test::shippedLayout(name))
        .visibilityIds;
}

uint64_t wordsAsU64(const std::array<uint32_t, 2>& w) { return (uint64_t(w[1]) << 32) | w[0]; }

// Window depths in [0, 1], where the two agree (the rasteriser's depth is clipped to [0, 1], so
// gbufferlab writes gl_FragCoord.z unsaturated): random bit patterns up to 1.0's (so denormals
// and tiny values too), uniform values, and the edges.
struct Inputs {
    std::vector<uint32_t> cluster, triangle;
    std::vector<float> depth;
};
Inputs randomInputs(uint32_t clusterLimit) {
    const uint32_t n = 1u << 20;
    const uint32_t clusterEdges[] = {0u, 1u, 2u, 127u, 128u, (1u << 24) - 1u, 1u << 24, clusterLimit - 1u, clusterLimit};
    const uint32_t triangleEdges[] = {0u, 1u, 63u, 64u, 126u, 127u};
    const float depthEdges[] = {0.0f,
                                std::numeric_limits<float>::denorm_min(),
                                std::numeric_limits<float>::min(),
                                1e-30f,
                                0.5f,
                                std::nextafter(1.0f, 0.0f),
                                1.0f};
    std::mt19937 rng(2028);
    Inputs in;
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t c = rng() % (clusterLimit + 1u), t = rng() & 0x7Fu;
        float z;
        const uint32_t bits = rng() % (asuint(1.0f) + 1u);
        if (i % 2) std::memcpy(&z, &bits, 4);
        else z = float(rng() >> 8) / float(1u << 24);
        constexpr uint32_t kEdgeCases = 9 * 6 * 7;
        if (i < kEdgeCases) {  // every triple of edges
            c = clusterEdges[i % 9];
            t = triangleEdges[(i / 9) % 6];
            z = depthEdges[i / 54];
        }
        in.cluster.push_back(c);
        in.triangle.push_back(t);
        in.depth.push_back(z);
    }
    return in;
}

TEST(EngineVisibilityIds, NanitePacksAndUnpacksAsUnrealEngine5) {
    const GBufferWiring::VisibilityIds ids = idsOf("nanite-visbuffer");
    const Inputs in = randomInputs((1u << 25) - 2u);  // + 1 must fit 25 bits
    size_t mismatches = 0;
    for (size_t i = 0; i < in.cluster.size(); ++i) {
        const uint64_t ue = nanitePackVisPixel(in.cluster[i], in.triangle[i], in.depth[i]);
        const std::array<uint32_t, 2> w = packVisibilityIds(ids, in.cluster[i], in.triangle[i], false, in.depth[i]);
        const NaniteVisPixel u = naniteUnpackVisPixel(ue);
        const std::array<uint32_t, 3> g = unpackVisibilityIds(ids, w);
        const bool ok = wordsAsU64(w) == ue && g[0] == u.visibleClusterIndex && g[1] == u.triIndex && g[2] == 0u &&
                        u.visibleClusterIndex == in.cluster[i] && u.triIndex == in.triangle[i] &&
                        w[1] == u.depthInt;
        if (!ok && mismatches++ < 5)
            ADD_FAILURE() << std::hex << "cluster 0x" << in.cluster[i] << " triangle 0x" << in.triangle[i] << " depth "
                          << in.depth[i] << ": gbufferlab 0x" << wordsAsU64(w) << ", UE 0x" << ue;
    }
    EXPECT_EQ(mismatches, 0u);
    // Any 64-bit value, the cleared 0 included, reads back as UnpackVisPixel reads it (an empty
    // pixel's cluster wraps to 0xFFFFFFFF in both).
    std::mt19937_64 rng(28);
    for (int i = 0; i < (1 << 20); ++i) {
        const uint64_t v = i == 0 ? 0u : rng();
        const NaniteVisPixel u = naniteUnpackVisPixel(v);
        const std::array<uint32_t, 3> g = unpackVisibilityIds(ids, {uint32_t(v), uint32_t(v >> 32)});
        ASSERT_EQ(g[0], u.visibleClusterIndex) << std::hex << v;
        ASSERT_EQ(g[1], u.triIndex) << std::hex << v;
    }
    EXPECT_EQ(naniteUnpackVisPixel(0).visibleClusterIndex, 0xFFFFFFFFu);
}

TEST(EngineVisibilityIds, BevyMeshletsPackAndResolveAsBevy016) {
    const GBufferWiring::VisibilityIds ids = idsOf("bevy-meshlet-visbuffer");
    const Inputs in = randomInputs((1u << 25) - 1u);  // cluster_buffer_slots <= 2^25
    size_t mismatches = 0;
    for (size_t i = 0; i < in.cluster.size(); ++i) {
        const uint64_t bevy = bevyPackVisibility(in.cluster[i], in.triangle[i], in.depth[i]);
        const std::array<uint32_t, 2> w = packVisibilityIds(ids, in.cluster[i], in.triangle[i], false, in.depth[i]);
        const BevyVisibility b = bevyResolve(bevy);
        const std::array<uint32_t, 3> g = unpackVisibilityIds(ids, w);
        const bool ok = wordsAsU64(w) == bevy && g[0] == b.clusterId && g[1] == b.triangleId && w[1] == b.depth &&
                        b.clusterId == in.cluster[i];
        if (!ok && mismatches++ < 5)
            ADD_FAILURE() << std::hex << "cluster 0x" << in.cluster[i] << " triangle 0x" << in.triangle[i] << " depth "
                          << in.depth[i] << ": gbufferlab 0x" << wordsAsU64(w) << ", Bevy 0x" << bevy;
    }
    EXPECT_EQ(mismatches, 0u);
    // Example from the packing by hand: cluster 5, triangle 3, depth 0.5 (0x3F000000).
    EXPECT_EQ(wordsAsU64(packVisibilityIds(ids, 5, 3, false, 0.5f)), 0x3F00000000000283ull);
}

// What the rows model in place of the engines' 64-bit atomic max: the depth test GREATER
// (reversed Z). For two fragments of different depth in [0, 1], the larger 64-bit word is the one
// of greater depth, the nearer, whatever their ids; the test keeps the same one. Only at equal
// depth do they part: the max keeps the larger id word, the test the fragment drawn first.
TEST(EngineVisibilityIds, SixtyFourBitMaxKeepsTheNearestFragmentAsTheDepthTest) {
    const GBufferWiring::VisibilityIds ids = idsOf("nanite-visbuffer");
    const Inputs in = randomInputs((1u << 25) - 2u);
    size_t pairs = 0, ties = 0;
    for (size_t i = 0; i + 1 < in.cluster.size(); i += 2) {
        const std::array<uint32_t, 2> a = packVisibilityIds(ids, in.cluster[i], in.triangle[i], false, in.depth[i]);
        const std::array<uint32_t, 2> b =
            packVisibilityIds(ids, in.cluster[i + 1], in.triangle[i + 1], false, in.depth[i + 1]);
        const uint64_t kept = std::max(wordsAsU64(a), wordsAsU64(b));
        if (in.depth[i] == in.depth[i + 1]) {
            ++ties;
            EXPECT_EQ(uint32_t(kept), std::max(a[0], b[0]));
            continue;
        }
        const bool firstPassesTest = in.depth[i] > in.depth[i + 1];  // VK_COMPARE_OP_GREATER
        ASSERT_EQ(kept, wordsAsU64(firstPassesTest ? a : b)) << "depths " << in.depth[i] << ", " << in.depth[i + 1];
        ++pairs;
    }
    EXPECT_GT(pairs, 500000u);
    EXPECT_GT(ties, 0u);  // the edge triples repeat depths
    // And the cleared 0 loses to every fragment but one at the far plane with id 0 (Bevy's cluster
    // 0, triangle 0 at depth 0): Nanite's + 1 keeps even that one apart from the clear.
    EXPECT_GT(wordsAsU64(packVisibilityIds(ids, 0, 0, false, 0.0f)), 0u);
    EXPECT_EQ(wordsAsU64(packVisibilityIds(idsOf("bevy-meshlet-visbuffer"), 0, 0, false, 0.0f)), 0u);
}

// Clusters: cluster c of a draw holds its triangles [128c, 128c + 128); a fragment's cluster and
// triangle (visibilityFields, from its draw's first cluster and gl_PrimitiveID) map back through
// the cluster table to its draw and its triangle in the draw.
TEST(EngineVisibilityIds, ClustersMapBackToTheirDrawAndTriangle) {
    const GBufferWiring::VisibilityIds ids = idsOf("nanite-visbuffer");
    const std::vector<size_t> triangles = {288, 1, 0, 128, 129, 127, 5000};
    const std::vector<uint32_t> first = visibilityFirstIds(ids, triangles);
    const std::vector<std::array<uint32_t, 2>> table = visibilityClusterTable(ids.clusterTriangles, triangles);
    EXPECT_EQ(first, (std::vector<uint32_t>{0, 3, 4, 4, 5, 7, 8}));
    ASSERT_EQ(table.size(), 8u + 40u);  // 3 + 1 + 0 + 1 + 2 + 1 + ceil(5000 / 128)
    for (size_t d = 0; d < triangles.size(); ++d)
        for (uint32_t p = 0; p < triangles[d]; ++p) {
            const VisibilityFields f = visibilityFields(ids, first[d], p);
            ASSERT_LT(f.triangle, 128u);
            ASSERT_EQ(table.at(f.draw)[0], d) << "draw " << d << " triangle " << p;
            ASSERT_EQ(table.at(f.draw)[1] + f.triangle, p) << "draw " << d << " triangle " << p;
            ASSERT_EQ(table.at(f.draw)[1] % 128u, 0u);
        }
    // Without clusters a draw's id is its index and the triangle its gl_PrimitiveID.
    const GBufferWiring::VisibilityIds v64 = idsOf("visibility-64");
    EXPECT_EQ(visibilityFirstIds(v64, triangles), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6}));
    EXPECT_TRUE(visibilityClusterTable(v64.clusterTriangles, triangles).empty());
    EXPECT_EQ(visibilityFields(v64, 6, 4999).triangle, 4999u);
}

// How many clusters the ids hold: 2^25 - 1 for Nanite (its + 1), 2^25 for Bevy; a draw of any
// size fits; past the limit, one line naming the layout, the count, the limit and the fix.
TEST(EngineVisibilityIds, ClusterCapacityIsTheFieldLessTheOffset) {
    GBufferWiring w = generateWiring(test::shippedLayout("nanite-visbuffer"));
    const size_t full = 128u * ((size_t(1) << 25) - 1u);
    EXPECT_EQ(visibilityCapacityProblem(w, {full}), "");
    EXPECT_EQ(visibilityCapacityProblem(w, {full - 128, 100}), "");  // draws of partial clusters count whole
    const std::string m = visibilityCapacityProblem(w, {full, 1});
    for (const char* word : {"layout 'nanite-visbuffer'", "33554432 clusters of up to 128 triangles",
                             "25-bit cluster ids (with draw_offset 1) hold 33554431", "visibility-64"})
        EXPECT_NE(m.find(word), std::string::npos) << "missing [" << word << "] in: " << m;
    EXPECT_EQ(m.find('\n'), std::string::npos);
    w = generateWiring(test::shippedLayout("bevy-meshlet-visbuffer"));
    EXPECT_EQ(visibilityCapacityProblem(w, {full, 128}), "");
    EXPECT_NE(visibilityCapacityProblem(w, {full, 129}), "");
}

}  // namespace
}  // namespace gbl
