// The visibility buffer's ids as the GPU packs them (shaders/visibility_buffer.glsl through each
// layout's generated wiring, run in a compute shader on lavapipe) against the C++ twin
// (visibility_wiring.h), bit for bit, for every visibility layout in layouts/: the fragment's
// (draw or cluster, triangle) from its draw's id and gl_PrimitiveID, the packed words (the depth
// word's float bits included) and the unpacked ids, on 2^20 random inputs and the edges.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <limits>
#include <random>

#include "shader_compiler.h"
#include "layout_files.h"
#include "visibility_wiring.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

class VisibilityBits : public test::VulkanTest {};

const std::string kShader = test::wiringKernel(R"(    uvec4 v = inputs[i];  // first id, gl_PrimitiveID, alpha-masked, depth bits
    uvec2 f = visibilityFields(v.x, v.y);
    uvec2 w = packVisibilityIds(f.x, f.y, v.z != 0u, uintBitsToFloat(v.w));
    outputs[2u * i] = uvec4(f, w);
    outputs[2u * i + 1u] = uvec4(unpackVisibilityIds(w), 0u);
)");

TEST_F(VisibilityBits, EveryVisibilityLayoutPacksAsItsCppTwin) {
    VulkanContext& c = ctx();
    constexpr uint32_t kIds = 1u << 20;
    std::vector<uint32_t> in(size_t(kIds) * 4);
    std::mt19937 rng(2807);
    const uint32_t edges[] = {0u, 1u, 127u, 128u, 255u, 256u, 0x7FFFFFu, 0x800000u, 0x1FFFFFFu, 0x2000000u,
                              0x7FFFFFFFu, 0x80000000u, 0xFFFFFF7Fu, 0xFFFFFF80u, 0xFFFFFFFEu, 0xFFFFFFFFu};
    const float depths[] = {0.0f, std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::min(), 0.5f,
                            std::nextafter(1.0f, 0.0f), 1.0f};
    for (uint32_t i = 0; i < kIds; ++i) {
        uint32_t first = rng(), primitive = rng(), depthBits = rng() % 0x3F800001u;
        if (i % 4 == 1) first &= 0xFFFFu;  // in range, as a scene's ids are
        if (i % 4 == 2) primitive &= 0xFFFFu;
        if (i < 16u * 16u * 6u) {  // every pair of edges, at every edge depth
            first = edges[i % 16];
            primitive = edges[(i / 16) % 16];
            std::memcpy(&depthBits, &depths[i / 256], 4);
        }
        in[size_t(i) * 4] = first;
        in[size_t(i) * 4 + 1] = primitive;
        in[size_t(i) * 4 + 2] = (i / 512u) % 2u;  // alpha-tested
        in[size_t(i) * 4 + 3] = depthBits;
    }
    const test::TestBuffer input = test::TestBuffer::holding(c, in);
    const test::TestBuffer out(c, size_t(kIds) * 8 * sizeof(uint32_t));
    size_t layouts = 0;
    for (const Layout& layout : test::shippedLayouts()) {
        if (layout.pipeline != Pipeline::VisibilityBuffer) continue;
        ++layouts;
        const GBufferWiring w = generateWiring(layout);
        ShaderSource cs{"visibility_bits.comp (test, " + layout.name + ")", kShader, VK_SHADER_STAGE_COMPUTE_BIT, {},
                        {{"gbuffer_wiring.glsl", w.glsl}}};
        test::ComputeKernel(c, cs, {{test::storage(input), test::storage(out)}}).dispatch(kIds / 64);
        const uint32_t* got = out.mapped<const uint32_t>();
        const GBufferWiring::VisibilityIds& ids = w.visibilityIds;
        size_t mismatches = 0, depthWords = 0;
        for (uint32_t i = 0; i < kIds; ++i) {
            const uint32_t* v = &in[size_t(i) * 4];
            float depth;
            std::memcpy(&depth, &v[3], 4);
            const VisibilityFields f = visibilityFields(ids, v[0], v[1]);
            const std::array<uint32_t, 2> words = packVisibilityIds(ids, f.draw, f.triangle, v[2] != 0u, depth);
            const std::array<uint32_t, 3> u = unpackVisibilityIds(ids, words);
            const uint32_t want[8] = {f.draw, f.triangle, words[0], ids.words == 2 ? words[1] : 0u, u[0], u[1], u[2], 0u};
            const uint32_t* g = got + size_t(i) * 8;
            uint32_t gotWords[8];
            std::memcpy(gotWords, g, sizeof(gotWords));
            if (ids.words == 1) gotWords[3] = 0u;  // GLSL's w.y is 0 then; the target holds w.x only
            depthWords += ids.depthWord && gotWords[3] == v[3];
            if (std::memcmp(gotWords, want, sizeof(want)) != 0 && mismatches++ < 5) {
                std::string a, b;
                for (int k = 0; k < 8; ++k) a += " " + std::to_string(gotWords[k]), b += " " + std::to_string(want[k]);
                ADD_FAILURE() << layout.name << " input (" << v[0] << ", " << v[1] << ", " << v[2] << ", " << v[3]
                              << "): GPU" << a << ", C++" << b;
            }
        }
        EXPECT_EQ(mismatches, 0u) << layout.name;
        if (ids.depthWord) EXPECT_EQ(depthWords, kIds) << layout.name << ": word 1 holds the depth's bits";
        std::printf("[ ids      ] %-24s %u fragments: GPU and C++ %zu mismatches\n", layout.name.c_str(), kIds,
                    mismatches);
    }
    EXPECT_GE(layouts, 4u);  // visibility-32, visibility-64, nanite-visbuffer, bevy-meshlet-visbuffer
}

}  // namespace
}  // namespace gbl
