// The packer: every layout it writes is one `layouts check` accepts, within the budget, made of
// real formats, and stores exactly the bits the genome asked for.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "bandwidth.h"
#include "layout.h"
#include "layout_packer.h"
#include "search_space.h"

namespace gbl::search {
namespace {

// Bytes per pixel of the formats the packer may use, written here from the Vulkan spec's format
// table (independent of layout.cpp's table and of the packer's list).
const std::map<std::string, int>& realFormatBytes() {
    static const std::map<std::string, int> m = {
        {"R8_UNORM", 1},           {"R8G8_UNORM", 2},     {"R16_UNORM", 2},
        {"R16_UINT", 2},           {"R8G8B8A8_UNORM", 4}, {"A2B10G10R10_UNORM_PACK32", 4},
        {"R16G16_UNORM", 4},       {"R32_UINT", 4},       {"R16G16B16A16_UNORM", 8},
        {"R32G32_UINT", 8},
    };
    return m;
}
const std::map<std::string, int>& depthBytes() {
    static const std::map<std::string, int> m = {{"D16_UNORM", 2}, {"D24_UNORM_S8_UINT", 4}, {"D32_SFLOAT", 4}};
    return m;
}

// Bits the genome stores per attribute, counted from the encodings' definitions (layouts/README.md).
std::map<std::string, int> expectedBits(const Genome& g) {
    std::map<std::string, int> m;
    const auto& n = normalEncodings()[size_t(g.normalEncoding)];
    m["normal"] = n.codes * g.normalBits + n.extraBits;
    m["roughness"] = g.roughnessBits;
    const auto& c = colourEncodings()[size_t(g.colourEncoding)];
    const auto& sc = colourEncodings()[size_t(g.specularColourEncoding)];
    if (g.workflow == Workflow::Metallic) {
        m["base_color"] = c.codes * g.colourBits;
        if (g.metallicBits) m["metallic"] = g.metallicBits;
        if (g.specularMode == SpecularMode::Scalar) m["specular"] = g.specularBits;
        if (g.specularMode == SpecularMode::Colour) m["specular_color"] = sc.codes * g.specularColourBits;
    } else {
        m["diffuse_color"] = c.codes * g.colourBits;
        m["specular_color"] = sc.codes * g.specularColourBits;
    }
    if (g.occlusionBits) m["occlusion"] = g.occlusionBits;
    // The layers (search_space.h): unorm amounts and colours, octahedral directions (2 codes).
    if (g.coatBits) {
        m["coat"] = m["coat_roughness"] = g.coatBits;
        if (g.coatNormalBits) m["coat_normal"] = 2 * g.coatNormalBits;
    }
    if (g.sheenBits) {
        m["sheen_color"] = 3 * g.sheenBits;
        m["sheen_roughness"] = g.sheenBits;
    }
    if (g.anisotropyBits) {
        m["anisotropy_strength"] = g.anisotropyBits;
        m["anisotropy_direction"] = 2 * g.anisotropyBits;
    }
    if (g.layerSelector) m["shading_model"] = 2;
    return m;
}

TEST(LayoutPacker, EveryPackedGenomeIsAValidLayoutWithinBudgetOfRealFormats) {
    SplitMix64 rng(7);
    int ok = 0, over = 0;
    std::set<std::string> formatsSeen;
    for (int i = 0; i < 3000; ++i) {
        Genome g = randomGenome(rng);
        for (int m = 0; m < i % 4; ++m) g = mutateGenome(g, rng);
        const int budget = 6 + (i % 5) * 4;  // 6, 10, 14, 18, 22
        const PackResult p = packGenome(g, budget);
        if (!p.ok) {
            over += p.bytesPerPixel > budget;
            continue;
        }
        ++ok;
        const std::string text = layoutText("candidate", "a comment\nof two lines", p.body);
        const auto diags = checkLayout(text, "candidate.toml");
        ASSERT_TRUE(diags.empty()) << diags.front().text() << "\n" << text;
        const Layout l = parseLayout(text, "candidate.toml");
        // Bytes: the budget, the packer's own count, layout.h's and bandwidth.h's, and the sum of
        // this test's table all agree.
        int bytes = depthBytes().at(l.depth.format);
        for (const Target& t : l.targets) {
            ASSERT_TRUE(realFormatBytes().count(t.format)) << t.format;
            bytes += realFormatBytes().at(t.format);
            formatsSeen.insert(t.format);
        }
        EXPECT_LE(bytes, budget);
        EXPECT_EQ(bytes, p.bytesPerPixel);
        EXPECT_EQ(bytesPerPixel(l), bytes);
        EXPECT_EQ(computeBandwidth(l, 480, 270).gbufferBytesPerPixel, bytes);
        EXPECT_LE(l.targets.size(), 8u);
        // Exactly the bits asked for, attribute by attribute.
        std::map<std::string, int> stored;
        for (const AttributeBits& ab : bitsPerAttribute(l)) stored[attributeName(ab.attribute)] = ab.bits;
        EXPECT_EQ(stored, expectedBits(g)) << describeGenome(g);
    }
    // The space is explored, not just its corner: most genomes fit the larger budgets, many
    // exceed the small ones, and every size class of format is used.
    EXPECT_GT(ok, 1000);
    EXPECT_GT(over, 300);
    for (const char* f : {"R8_UNORM", "R8G8B8A8_UNORM", "A2B10G10R10_UNORM_PACK32", "R32_UINT"})
        EXPECT_TRUE(formatsSeen.count(f)) << f;
}

// With layers (a scene that carries them): every packed genome is a valid layout storing exactly
// the bits asked for; under a selector, each layer's fields are held under its model (clear_coat,
// cloth, anisotropic: layouts/README.md, "Shading models"), all of them in one target whose bits
// every model starts from, and the selector names the four models.
TEST(LayoutPacker, LayersPackAsFieldsOfTheirOwnOrUnderASelector) {
    SplitMix64 rng(11);
    int ok = 0, selectors = 0, shared = 0;
    for (int i = 0; i < 1500; ++i) {
        Genome g = randomGenome(rng, true);
        for (int m = 0; m < i % 4; ++m) g = mutateGenome(g, rng, true);
        const int budget = 16 + (i % 4) * 8;  // 16 .. 40
        const PackResult p = packGenome(g, budget);
        if (!p.ok) continue;
        ++ok;
        const std::string text = layoutText("candidate", "", p.body);
        const auto diags = checkLayout(text, "candidate.toml");
        ASSERT_TRUE(diags.empty()) << diags.front().text() << "\n" << text;
        const Layout l = parseLayout(text, "candidate.toml");
        EXPECT_EQ(bytesPerPixel(l), p.bytesPerPixel);
        std::map<std::string, int> stored;
        for (const AttributeBits& ab : bitsPerAttribute(l)) stored[attributeName(ab.attribute)] = ab.bits;
        EXPECT_EQ(stored, expectedBits(g)) << describeGenome(g);
        if (!g.layerSelector) {
            EXPECT_EQ(l.selector(), nullptr);
            continue;
        }
        ++selectors;
        ASSERT_NE(l.selector(), nullptr);
        EXPECT_EQ(l.selectorModels(), 0xfu);
        const std::map<std::string, ShadingModel> modelOf = {
            {"coat", ShadingModel::ClearCoat},          {"coat_roughness", ShadingModel::ClearCoat},
            {"coat_normal", ShadingModel::ClearCoat},   {"sheen_color", ShadingModel::Cloth},
            {"sheen_roughness", ShadingModel::Cloth},   {"anisotropy_strength", ShadingModel::Anisotropic},
            {"anisotropy_direction", ShadingModel::Anisotropic}};
        std::set<std::string> layerTargets;
        int models = 0;
        for (const Target& t : l.targets)
            for (const Field& f : t.fields) {
                const auto it = modelOf.find(attributeName(f.attribute));
                if (it == modelOf.end()) {
                    EXPECT_FALSE(f.conditional()) << attributeName(f.attribute);
                    continue;
                }
                EXPECT_EQ(f.models, 1u << unsigned(it->second)) << attributeName(f.attribute);
                layerTargets.insert(t.name);
                models |= int(f.models);
            }
        EXPECT_EQ(layerTargets.size(), 1u);
        shared += __builtin_popcount(unsigned(models)) > 1;
    }
    EXPECT_GT(ok, 500);
    EXPECT_GT(selectors, 100);
    EXPECT_GT(shared, 50);  // two or more models' fields over the same bits
    // Without layers the genomes store none: the space of a scene without them is unchanged.
    SplitMix64 plain(11);
    for (int i = 0; i < 200; ++i) {
        const Genome g = mutateGenome(randomGenome(plain), plain);
        EXPECT_EQ(g.coatBits + g.sheenBits + g.anisotropyBits, 0);
        EXPECT_FALSE(g.layerSelector);
    }
}

TEST(LayoutPacker, OverBudgetSaysByHowMuch) {
    Genome g;
    g.normalEncoding = 8;  // float16 x 3 = 48 bits
    g.normalBits = 16;
    g.colourEncoding = 1;  // unorm 12 x 3
    g.colourBits = 12;
    clampGenome(g);
    const PackResult p = packGenome(g, 8);
    EXPECT_FALSE(p.ok);
    EXPECT_GT(p.bytesPerPixel, 8);
    EXPECT_NE(p.why.find("over the budget of 8"), std::string::npos) << p.why;
}

TEST(LayoutPacker, Crysis3ThinShapeWithoutItsExtrasFitsTenBytes) {
    // The thin G-buffer's choices: xy + z sign 8 bits (17), gloss 7, YCbCr checkerboard 8 (16), luma
    // specular 8: 48 bits. Without Crysis 3's translucency and per-project bytes they fill one RGBA8
    // (17 + 8 + 7 = 32 bits) and one RG8 (the chroma pair): 4 + 2 + D24S8's 4 = 10 bytes.
    Genome g;
    g.normalEncoding = 2;
    g.normalBits = 8;
    g.normalSpace = 1;
    g.roughnessEncoding = 1;
    g.roughnessBits = 7;
    g.workflow = Workflow::DiffuseSpecular;
    g.colourEncoding = 5;
    g.colourBits = 8;
    g.specularColourEncoding = 7;
    g.specularColourBits = 8;
    g.occlusionBits = 0;
    g.depthFormat = 1;
    const PackResult p = packGenome(g, 12);
    ASSERT_TRUE(p.ok) << p.why;
    EXPECT_EQ(p.bytesPerPixel, 10);
    const Layout l = parseLayout(layoutText("candidate", "", p.body), "candidate.toml");
    EXPECT_EQ(l.findField(Attribute::DiffuseColor)->encoding, "ycbcr_checkerboard");
    EXPECT_EQ(l.space.normal, StoredSpace::WorldZUp);
}

TEST(LayoutPacker, EqualGenomesGiveEqualTextAndTheCommentIsComments) {
    SplitMix64 a(3), b(3);
    const Genome ga = randomGenome(a), gb = randomGenome(b);
    EXPECT_EQ(ga, gb);
    const PackResult pa = packGenome(ga, 64), pb = packGenome(gb, 64);
    EXPECT_EQ(pa.body, pb.body);
    const std::string text = layoutText("found-9b", "line one\n\nline three", pa.body);
    EXPECT_EQ(text.rfind("# line one\n#\n# line three\nname = \"found-9b\"\n", 0), 0u) << text;
}

// The floor search refuses budgets below: no genome the search proposes packs into fewer bytes,
// and some genome packs into exactly that many.
TEST(LayoutPacker, SmallestPackedBytesIsTheFloorOfWhatTheSearchProposes) {
    const int smallest = smallestPackedBytes();
    ASSERT_GT(smallest, 0);
    SplitMix64 rng(17);
    int least = 1 << 20;
    for (int i = 0; i < 20000; ++i) {
        Genome g = i % 2 ? randomGenome(rng) : mutateGenome(randomGenome(rng), rng);
        const PackResult r = packGenome(g, 1 << 20);
        if (r.ok) least = std::min(least, r.bytesPerPixel);
    }
    EXPECT_GE(least, smallest);
    // Octahedral normal at 6 + 6 bits, roughness and luma at 3, nothing else stored, 16-bit depth:
    // 18 bits take a 4-byte target, plus 2 bytes of depth.
    Genome g;
    g.normalEncoding = 0;
    g.normalBits = 6;
    g.roughnessEncoding = 0;
    g.roughnessBits = 3;
    g.colourEncoding = int(colourEncodings().size()) - 1;  // luma
    g.colourBits = 3;
    g.metallicBits = 0;
    g.specularMode = SpecularMode::FromMetallic;
    g.occlusionBits = 0;
    g.depthFormat = 0;  // D16
    ASSERT_STREQ(colourEncodings()[size_t(g.colourEncoding)].name, "luma");
    ASSERT_STREQ(depthFormats()[0].format, "D16_UNORM");
    EXPECT_EQ(packGenome(g, smallest).bytesPerPixel, smallest);
    EXPECT_TRUE(packGenome(g, smallest).ok) << packGenome(g, smallest).why;
    EXPECT_FALSE(packGenome(g, smallest - 1).ok);
}

}  // namespace
}  // namespace gbl::search
