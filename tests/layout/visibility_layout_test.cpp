// The visibility buffer in the layout language: pipeline = "visibility-buffer" and [ids], the two
// shipped layouts, and the errors a wrong one gets, each at its file:line:col.
#include <gtest/gtest.h>

#include "layout.h"
#include "layout_catalog.h"
#include "layout_files.h"
#include "layout_test_support.h"
#include "layout_text.h"

namespace gbl {
namespace {

using layout_test::edit;
using layout_test::expectError;
using layout_test::expectOnlyError;
using layout_test::joined;
using layout_test::kFile;
using layout_test::placeOf;

// A visibility buffer: The Forge's split of R32_UINT.
const std::string kVisibility = test::LayoutText("vis", "A visibility buffer", test::kTestSource, "visibility-buffer")
                                    .ids("format = \"R32_UINT\"\ntriangle_bits = 23\ndraw_bits = 8\nalpha_mask_bit = true\n");

TEST(VisibilityLayout, TheSmallOneIsValidAndReadsAsWritten) {
    EXPECT_TRUE(checkLayout(kVisibility, kFile).empty()) << joined(checkLayout(kVisibility, kFile));
    const Layout l = parseLayout(kVisibility, kFile);
    EXPECT_EQ(l.pipeline, Pipeline::VisibilityBuffer);
    EXPECT_STREQ(pipelineName(l.pipeline), "visibility-buffer");
    EXPECT_TRUE(l.ids.declared);
    EXPECT_EQ(l.ids.bits, 32);
    EXPECT_EQ(l.ids.triangleBits, 23);
    EXPECT_EQ(l.ids.drawBits, 8);
    EXPECT_TRUE(l.ids.alphaMaskBit);
    EXPECT_TRUE(l.targets.empty());
    EXPECT_EQ(bytesPerPixel(l), 4 + 4);  // R32_UINT ids + D32 depth
}

// The shipped layouts: The Forge's 1 / 8 / 23 split of R32_UINT (packVisBufData:
// ((drawId << 23) & 0x7F800000) | (triangleId & 0x007FFFFF), bit 31 for alpha-tested geometry) and
// full 32-bit ids in R32G32_UINT.
TEST(VisibilityLayout, ShippedLayoutsAreTheForgesAndSixtyFourBit) {
    const Layout v32 = test::shippedLayout("visibility-32");
    EXPECT_EQ(v32.ids.format, "R32_UINT");
    EXPECT_EQ(v32.ids.triangleBits, 23);  // mask 0x007FFFFF
    EXPECT_EQ(v32.ids.drawBits, 8);       // mask 0x7F800000 >> 23 = 0xFF
    EXPECT_TRUE(v32.ids.alphaMaskBit);    // 1 << 31
    EXPECT_EQ(bytesPerPixel(v32), 8);
    const Layout v64 = test::shippedLayout("visibility-64");
    EXPECT_EQ(v64.ids.format, "R32G32_UINT");
    EXPECT_EQ(v64.ids.bits, 64);
    EXPECT_EQ(v64.ids.triangleBits, 32);
    EXPECT_EQ(v64.ids.drawBits, 32);
    EXPECT_FALSE(v64.ids.alphaMaskBit);
    EXPECT_EQ(bytesPerPixel(v64), 12);
    // UE 5's Nanite: ((visible cluster + 1) << 7) | triangle in word 0, asuint(DeviceZ) in word 1;
    // Bevy 0.16's meshlets: the same without the + 1. 128-triangle clusters, reversed Z, 8 bytes.
    for (const char* name : {"nanite-visbuffer", "bevy-meshlet-visbuffer"}) {
        const Layout l = test::shippedLayout(name);
        EXPECT_EQ(l.ids.format, "R32G32_UINT") << name;
        EXPECT_EQ(l.ids.triangleBits, 7) << name;
        EXPECT_EQ(l.ids.drawBits, 25) << name;
        EXPECT_EQ(l.ids.clusterTriangles, 128u) << name;
        EXPECT_EQ(l.ids.depthWord, 1) << name;
        EXPECT_EQ(l.ids.drawOffset, std::string(name) == "nanite-visbuffer" ? 1u : 0u) << name;
        EXPECT_FALSE(l.ids.alphaMaskBit) << name;
        EXPECT_TRUE(l.depth.reversedZ) << name;
        EXPECT_EQ(bytesPerPixel(l), 8) << name;
    }
}

TEST(VisibilityLayout, IdsThatDoNotFitAreOneErrorAtTheFormat) {
    const std::string t = edit(kVisibility, "draw_bits = 8", "draw_bits = 9");
    expectOnlyError(t, placeOf(t, "\"R32_UINT\""),
                    {"ids need 33 bits", "23 triangle + 9 draw + 1 alpha-mask flag", "R32_UINT holds 32", "1 over"});
    // Without the flag the same widths fit.
    const std::string noFlag = edit(t, "alpha_mask_bit = true", "alpha_mask_bit = false");
    EXPECT_TRUE(checkLayout(noFlag, kFile).empty()) << joined(checkLayout(noFlag, kFile));
}

TEST(VisibilityLayout, BadIdsAreErrorsAtTheirPlace) {
    std::string t = edit(kVisibility, "\"R32_UINT\"", "\"R16_UINT\"");
    expectOnlyError(t, placeOf(t, "\"R16_UINT\""), {"unknown id format 'R16_UINT'", "R32G32_UINT"});
    t = edit(kVisibility, "triangle_bits = 23", "triangle_bits = 0");
    expectOnlyError(t, placeOf(t, "0\n"), {"'triangle_bits' 0 must be 1 to 32 bits"});
    t = edit(kVisibility, "draw_bits = 8", "draw_bits = \"8\"");
    expectOnlyError(t, placeOf(t, "\"8\""), {"'draw_bits' must be an integer"});
    t = edit(kVisibility, "alpha_mask_bit = true", "alpha_mask_bit = 1");
    expectOnlyError(t, placeOf(t, "1\n"), {"'alpha_mask_bit' must be true or false"});
    t = edit(kVisibility, "draw_bits = 8\n", "");
    expectOnlyError(t, placeOf(t, "[ids]"), {"[ids] has no 'draw_bits'"});
    t = edit(kVisibility, "alpha_mask_bit", "alpha_bit");
    expectError(t, placeOf(t, "alpha_bit"), {"unknown key 'alpha_bit' in [ids]"});
}

// Nanite's and Bevy's meshlet ids: a depth word, an offset on the draw (cluster) field, clusters.
const std::string kNanite = test::LayoutText("vis", "Nanite-like ids", test::kTestSource, "visibility-buffer")
                                .depth("format = \"D32_SFLOAT\"\nreversed_z = true\n")
                                .ids("format = \"R32G32_UINT\"\ntriangle_bits = 7\ndraw_bits = 25\ndraw_offset = 1\n"
                                     "cluster_triangles = 128\ndepth_word = 1\n");

TEST(VisibilityLayout, DepthWordOffsetAndClustersReadAsWritten) {
    EXPECT_TRUE(checkLayout(kNanite, kFile).empty()) << joined(checkLayout(kNanite, kFile));
    const Layout l = parseLayout(kNanite, kFile);
    EXPECT_EQ(l.ids.drawOffset, 1u);
    EXPECT_EQ(l.ids.clusterTriangles, 128u);
    EXPECT_EQ(l.ids.depthWord, 1);
    // The ids' 8 bytes only: the depth lives in word 1, and the raster pass has no depth attachment.
    EXPECT_EQ(depthAttachmentBytes(l), 0);
    EXPECT_EQ(bytesPerPixel(l), 8);
    // Without the new keys nothing changes: no offset, no clusters, no depth word, depth counted.
    const Layout plain = parseLayout(kVisibility, kFile);
    EXPECT_EQ(plain.ids.drawOffset, 0u);
    EXPECT_EQ(plain.ids.clusterTriangles, 0u);
    EXPECT_EQ(plain.ids.depthWord, -1);
    EXPECT_EQ(depthAttachmentBytes(plain), 4);
}

// Each bad value is one error at its own file:line:col, naming the fix.
TEST(VisibilityLayout, BadDepthWordOffsetAndClustersAreErrorsAtTheirPlace) {
    std::string t = edit(kNanite, "depth_word = 1", "depth_word = 0");
    expectOnlyError(t, placeOf(t, "0\n"), {"'depth_word' 0 must be 1", "high half", "word 0"});
    t = edit(kNanite, "depth_word = 1", "depth_word = true");
    expectOnlyError(t, placeOf(t, "true", 1), {"'depth_word' must be an integer"});
    // A depth word needs the second word, and the ids must then fit word 0.
    t = edit(edit(kNanite, "\"R32G32_UINT\"", "\"R32_UINT\""), "draw_bits = 25", "draw_bits = 20");
    expectOnlyError(t, placeOf(t, "1\n", 1), {"'depth_word' needs a second word", "R32G32_UINT", "not R32_UINT"});
    t = edit(kNanite, "draw_bits = 25", "draw_bits = 26");
    expectOnlyError(t, placeOf(t, "\"R32G32_UINT\""),
                    {"ids need 33 bits", "7 triangle + 26 draw", "depth in word 1 leaves word 0, 32", "1 over"});
    // The depth in the word is a float32, and a 64-bit max keeps the nearest only with reversed Z.
    t = edit(kNanite, "\"D32_SFLOAT\"", "\"D24_UNORM_S8_UINT\"");
    expectOnlyError(t, placeOf(t, "\"D24_UNORM_S8_UINT\""), {"float32 in word 1", "D32_SFLOAT", "'D24_UNORM_S8_UINT'"});
    t = edit(kNanite, "reversed_z = true", "reversed_z = false");
    expectOnlyError(t, placeOf(t, "false"), {"64-bit max", "nearest surface only with reversed Z", "reversed_z = true"});
    t = edit(kNanite, "reversed_z = true\n", "");
    expectOnlyError(t, placeOf(t, "[depth]"), {"reversed_z = true"});
    // The offset must leave ids in the field, and fit 32 bits at all.
    t = edit(kNanite, "draw_bits = 25", "draw_bits = 1");
    t = edit(t, "draw_offset = 1", "draw_offset = 2");
    expectOnlyError(t, placeOf(t, "2\n"), {"'draw_offset' 2 leaves no id", "1-bit draw fields hold 0 to 1", "below 2"});
    t = edit(kNanite, "draw_offset = 1", "draw_offset = -1");
    expectOnlyError(t, placeOf(t, "-1"), {"'draw_offset' -1 must be 0 to 4294967295"});
    t = edit(kNanite, "draw_offset = 1", "draw_offset = 4294967296");
    expectOnlyError(t, placeOf(t, "4294967296"), {"'draw_offset' 4294967296 must be 0 to 4294967295"});
    t = edit(kNanite, "draw_offset = 1", "draw_offset = 1.5");
    expectOnlyError(t, placeOf(t, "1.5"), {"'draw_offset' must be an integer"});
    // Clusters must fit the triangle field.
    t = edit(kNanite, "cluster_triangles = 128", "cluster_triangles = 129");
    expectOnlyError(t, placeOf(t, "129"), {"'cluster_triangles' 129 is more than 7-bit triangle ids hold (128)", "at most 128"});
    t = edit(kNanite, "cluster_triangles = 128", "cluster_triangles = 0");
    expectOnlyError(t, placeOf(t, "0\n"), {"'cluster_triangles' 0 must be 1 or more"});
    t = edit(kNanite, "cluster_triangles", "cluster_tris");
    expectError(t, placeOf(t, "cluster_tris"), {"unknown key 'cluster_tris' in [ids]"});
}

TEST(VisibilityLayout, PipelineRulesBothWays) {
    // A visibility buffer stores no attribute.
    std::string t = kVisibility + "\n[[target]]\nname = \"rt0\"\nformat = \"R8_UNORM\"\n"
                                  "field = [ { attribute = \"roughness\", encoding = \"unorm\", at = \"r\" } ]\n";
    expectOnlyError(t, placeOf(t, "[[target]]"), {"remove [[target]]", "rebuilds the Surface"});
    t = kVisibility + "\n[space]\nnormal = \"view\"\n";
    expectOnlyError(t, placeOf(t, "[space]"), {"remove [space]"});
    // ... and needs its ids.
    const std::string head = kVisibility.substr(0, kVisibility.find("[ids]"));
    expectOnlyError(head, std::string(kFile) + ":1:1", {"add [ids]", "R32_UINT"});
    // A G-buffer layout has no [ids].
    const std::string gbuffer = layout_test::kValid + "\n[ids]\nformat = \"R32_UINT\"\ntriangle_bits = 23\ndraw_bits = 8\n";
    expectOnlyError(gbuffer, placeOf(gbuffer, "[ids]"), {"[ids] belongs to pipeline = \"visibility-buffer\""});
    // The pipeline's name is listed when misspelt.
    t = edit(kVisibility, "\"visibility-buffer\"", "\"visibility\"");
    expectError(t, placeOf(t, "\"visibility\""), {"unknown pipeline 'visibility'", "visibility-buffer"});
}

}  // namespace
}  // namespace gbl
