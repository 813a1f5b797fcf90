// The shading-model selector in the layout language (layouts/README.md, "Shading models: the
// selector"): the test layout reads into the model (ids, models, bits shared between models counted
// once), and each inconsistency is refused at its file:line:col with what is wrong. Each case edits
// one line of tests/layout/data/shading-models.toml.
#include <fstream>
#include <sstream>

#include "layout_coverage.h"
#include "layout_files.h"
#include "layout_test_support.h"

using namespace gbl;
using namespace gbl::layout_test;

namespace {

std::string selectorText() {
    std::ifstream in(test::testLayoutDir() / "shading-models.toml");
    std::stringstream s;
    s << in.rdbuf();
    EXPECT_FALSE(s.str().empty());
    return s.str();
}

const Field* fieldOf(const Layout& l, const std::string& target, Attribute a, uint32_t models) {
    for (const Target& t : l.targets)
        if (t.name == target)
            for (const Field& f : t.fields)
                if (f.attribute == a && f.models == models) return &f;
    return nullptr;
}

constexpr uint32_t bit(ShadingModel m) { return 1u << unsigned(m); }

}  // namespace

TEST(ShadingModelLayout, TheTestLayoutReadsIntoTheModel) {
    const std::string text = selectorText();
    const auto diags = checkLayout(text, kFile);
    ASSERT_TRUE(diags.empty()) << joined(diags);
    const Layout l = parseLayout(text, kFile);
    const Field* sel = l.selector();
    ASSERT_NE(sel, nullptr);
    ASSERT_EQ(sel->selector.size(), 4u);
    EXPECT_EQ(sel->selector[0].model, ShadingModel::Default);
    EXPECT_EQ(sel->selector[0].id, 1u);
    EXPECT_EQ(l.selectorModels(), 0xfu);
    // UE's ids: default lit 1, clear coat 4, cloth 8; and 13 for anisotropic
    EXPECT_EQ(l.selectorIds(bit(ShadingModel::ClearCoat)), 1u << 4);
    EXPECT_EQ(l.selectorIds(bit(ShadingModel::Default) | bit(ShadingModel::Cloth)), (1u << 1) | (1u << 8));
    EXPECT_EQ(l.selectorIds(bit(ShadingModel::Anisotropic)), 1u << 13);

    EXPECT_NE(fieldOf(l, "D", Attribute::Coat, bit(ShadingModel::ClearCoat)), nullptr);
    EXPECT_NE(fieldOf(l, "C", Attribute::Specular, bit(ShadingModel::Default) | bit(ShadingModel::Cloth)), nullptr);
    EXPECT_NE(fieldOf(l, "D", Attribute::Specular, bit(ShadingModel::Anisotropic)), nullptr);
    EXPECT_TRUE(l.storesConditionally(Attribute::Specular));
    EXPECT_TRUE(l.storesConditionally(Attribute::Coat));
    EXPECT_TRUE(l.storesAlways(Attribute::Metallic));
    EXPECT_FALSE(l.storesAlways(Attribute::SheenColor));
    EXPECT_EQ(l.conditionalModels(Attribute::Specular),
              bit(ShadingModel::Default) | bit(ShadingModel::Cloth) | bit(ShadingModel::Anisotropic));

    // Target D holds four models' fields in the same 32 bits: counted once.
    for (const Target& t : l.targets)
        if (t.name == "D") {
            EXPECT_EQ(t.usedBits(), 32);
        }
    EXPECT_EQ(bytesPerPixel(l), 4 + 4 * 4);
    for (const AttributeBits& b : bitsPerAttribute(l)) {
        if (b.attribute == Attribute::Specular) {
            EXPECT_EQ(b.bits, 8);  // the widest of its fields: 8 under default and cloth, 6 under anisotropic
            EXPECT_EQ(b.models, l.conditionalModels(Attribute::Specular));
        }
        if (b.attribute == Attribute::ShadingModel) {
            EXPECT_EQ(b.bits, 4);
        }
        if (b.attribute == Attribute::Metallic) {
            EXPECT_EQ(b.models, 0u);
        }
    }
}

TEST(ShadingModelLayout, AConditionalFieldNeedsASelector) {
    std::string text = selectorText();
    text = edit(text, R"(  { attribute = "shading_model", at = "a[0:3]", models = { default = 1, clear_coat = 4, cloth = 8, anisotropic = 13 } },
)",
                "");
    expectError(text, placeOf(text, "\"clear_coat\" },\n  { attribute = \"coat_roughness\""),
                {"field 'coat' is held under clear_coat but the layout has no selector", "attribute = \"shading_model\""});
}

TEST(ShadingModelLayout, AModelTheSelectorDoesNotNameIsRefused) {
    const std::string text = edit(selectorText(), ", anisotropic = 13 }", " }");
    expectError(text, placeOf(text, "\"anisotropic\" }"),
                {"field 'anisotropy_strength' is held under anisotropic, which the selector (line 35) does not name",
                 "known: default, clear_coat, cloth"});
}

TEST(ShadingModelLayout, AnIdMustFitTheSelectorsBits) {
    const std::string text = edit(selectorText(), "anisotropic = 13", "anisotropic = 16");
    expectOnlyError(text, placeOf(text, "16 }"), {"id 16 of 'anisotropic' does not fit the selector's 4 bits (0..15)"});
}

TEST(ShadingModelLayout, TwoModelsOfOneIdAreRefused) {
    const std::string text = edit(selectorText(), "cloth = 8", "cloth = 4");
    expectOnlyError(text, placeOf(text, "4, anisotropic"),
                    {"models 'clear_coat' and 'cloth' have the same id 4", "could not tell their pixels apart"});
}

TEST(ShadingModelLayout, TheSelectorNamesDefault) {
    const std::string text = edit(selectorText(), "{ default = 1, clear_coat", "{ clear_coat");
    expectError(text, placeOf(text, "{ clear_coat"), {"the selector's 'models' has no 'default'"});
}

TEST(ShadingModelLayout, UnknownModelNamesAreRefused) {
    std::string text = edit(selectorText(), "cloth = 8", "hair = 8");
    expectError(text, placeOf(text, "hair"), {"unknown shading model 'hair'", "known: default, clear_coat, cloth, anisotropic"});
    text = edit(selectorText(), "model = \"clear_coat\" },", "model = \"clearcoat\" },");
    expectError(text, placeOf(text, "\"clearcoat\""), {"unknown shading model 'clearcoat'"});
}

TEST(ShadingModelLayout, TheSelectorTakesAtMostFiveBits) {
    const std::string text = edit(selectorText(), R"(at = "a[0:3]", models)", R"(at = "a[0:5]", models)");
    expectError(text, placeOf(text, "\"a[0:5]\""), {"the selector at 'a[0:5]' has 6 bits; it takes 1..5 bits"});
}

TEST(ShadingModelLayout, FieldsMayShareBitsOnlyUnderDisjointModels) {
    // cloth's sheen and clear_coat's coat share D.r: fine. Sheen roughness under clear_coat too clashes
    // with the coat normal's v code in D.a.
    std::string text = edit(selectorText(), R"(at = "a", model = "cloth" })", R"(at = "a", model = ["cloth", "clear_coat"] })");
    const auto diags = checkLayout(text, kFile);
    bool found = false;
    for (const auto& d : diags)
        found = found || (d.message.find("of field 'sheen_roughness' at 'a' overlap field 'coat_normal'") != std::string::npos &&
                          d.message.find("both are held under clear_coat") != std::string::npos);
    EXPECT_TRUE(found) << joined(diags);
    // An unconditional field shares bits with none: metallic over D.r
    text = edit(selectorText(), R"({ attribute = "coat",                 encoding = "unorm", at = "r", model = "clear_coat" },)",
                R"({ attribute = "coat",                 encoding = "unorm", at = "r" },)");
    const auto d2 = checkLayout(text, kFile);
    found = false;
    for (const auto& d : d2)
        found = found || d.message.find("is written on every pixel") != std::string::npos;
    EXPECT_TRUE(found) << joined(d2);
}

TEST(ShadingModelLayout, AnAttributeIsStoredOncePerModel) {
    std::string text = edit(selectorText(), R"(at = "a[0:5]", model = "anisotropic" })", R"(at = "a[0:5]", model = ["anisotropic", "cloth"] })");
    expectError(text, placeOf(text, "[\"anisotropic\", \"cloth\"]"),
                {"attribute 'specular' is already stored under cloth (line 44); store each attribute once per model"});
    text = edit(selectorText(), R"(at = "g", model = ["default", "cloth"] })", R"(at = "g" })");
    expectError(text, placeOf(text, "{ attribute = \"specular\",             encoding"),
                {"attribute 'specular' is already stored (line 44) by an unconditional field"});
}

TEST(ShadingModelLayout, AConditionalNonLayerAttributeNeedsAFallback) {
    const std::string text = edit(selectorText(), "specular = 0.5                 #", "#");
    expectError(text, placeOf(text, "[fallback]"),
                {"the layout stores 'specular' under default, cloth, anisotropic only and declares no fallback"});
}

TEST(ShadingModelLayout, NormalAndRoughnessAreStoredOnEveryPixel) {
    const std::string text = edit(selectorText(), R"(at = "b" },
  { attribute = "per_object")", R"(at = "b", model = "default" },
  { attribute = "per_object")");
    expectError(text, placeOf(text, "\"default\" },\n  { attribute = \"per_object\""),
                {"'roughness' is stored under default only: normal and roughness are stored on every pixel"});
}

TEST(ShadingModelLayout, GeometryIsStoredOnEveryPixel) {
    const std::string text = edit(selectorText(), R"({ attribute = "occlusion", encoding = "unorm", at = "b" },)",
                                  R"({ attribute = "depth", encoding = "unorm", at = "b", model = "default" },)");
    expectError(text, placeOf(text, "\"default\" },\n  { attribute = \"flags\""),
                {"field 'depth' is geometry", "stored on every pixel (remove 'model')"});
}

TEST(ShadingModelLayout, AConditionalFieldEncodesItsOwnValueOnly) {
    const std::string text = edit(selectorText(), R"({ attribute = "base_color", encoding = "srgb8", at = ["r", "g", "b"] },)",
                                  R"({ attribute = "base_color", encoding = "ycocg_checkerboard", at = ["r", "g"], model = "default" },)");
    expectError(text, placeOf(text, "\"ycocg_checkerboard\""),
                {"encoding 'ycocg_checkerboard' of the conditional field 'base_color' reads the neighbouring pixels"});
}

TEST(ShadingModelLayout, TheSelectorIsNotConditionalNorInTheStencilNorCleared) {
    std::string text = edit(selectorText(), "anisotropic = 13 } },", "anisotropic = 13 }, model = \"default\" },");
    expectError(text, placeOf(text, "\"default\" },\n  { attribute = \"selective"), {"the selector itself is not conditional"});
    text = edit(selectorText(), "roughness = 1.0\n", "roughness = 1.0\nshading_model = 11\n");
    expectError(text, placeOf(text, "11\nbase_color"), {"the selector takes no clear value"});
    text = edit(selectorText(), "[[target]]\nname = \"C\"", "[[target]]\nname = \"C\"");
    text = edit(text, "format = \"D32_SFLOAT\"",
                "format = \"D32_SFLOAT_S8_UINT\"\nstencil = [ { attribute = \"shading_model\", at = \"s[0:3]\", models = { default = 1 } } ]");
    expectError(text, placeOf(text, "{ attribute = \"shading_model\", at = \"s[0:3]\""),
                {"the shading-model selector lives in a colour target, not in the stencil"});
}

TEST(ShadingModelLayout, ASecondSelectorIsRefused) {
    const std::string text = edit(selectorText(), R"({ attribute = "flags", at = "a[0:2]", value = 3, model = "clear_coat" },)",
                                  R"({ attribute = "shading_model", at = "a[0:2]", models = { default = 0 } },)");
    expectError(text, placeOf(text, "{ attribute = \"shading_model\", at = \"a[0:2]\""),
                {"a second shading-model selector (the first is on line 35)"});
}

// Fallbacks that derive from each other are refused only where some model stores none of them:
// HDRP keeps fresnel0 (specular_color) under its standard feature and metallic under anisotropy,
// each deriving the other where it is not stored.
TEST(ShadingModelLayout, FallbacksMayDeriveFromEachOtherWhereEveryModelStoresOne) {
    const std::string base = edit(selectorText(), R"({ attribute = "metallic",  encoding = "unorm", at = "r" },)",
                                  R"({ attribute = "metallic",  encoding = "unorm", at = "r", model = ["anisotropic", "clear_coat"] },)");
    // metallic from specular_color, specular_color (ue4) from metallic: default and cloth pixels store neither
    std::string text = edit(base, "specular_color = \"ue4\"         #", "metallic = \"from_specular_color\"\nspecular_color = \"ue4\"         #");
    expectError(text, placeOf(text, "\"from_specular_color\"\nspecular_color"),
                {"fallbacks form a cycle: metallic -> specular_color -> metallic on pixels of model 'default'"});
    // ... with specular_color stored under default and cloth, every model stores one of the two
    text = edit(text, "[fallback]", R"([[target]]
name = "E"
format = "R8G8B8A8_UNORM"
field = [
  { attribute = "specular_color", encoding = "unorm", at = ["r", "g", "b"], model = ["default", "cloth"] },
]

[fallback])");
    text = edit(text, "occlusion = 1.0\n", "occlusion = 1.0\nspecular_color = 0.04\n");
    const auto diags = checkLayout(text, kFile);
    EXPECT_TRUE(diags.empty()) << joined(diags);
}

// HDRP's anisotropic feature (layouts/hdrp-lit.toml): a conditional field whose encoding reads an
// attribute every pixel stores (anisotropy_angle_hdrp reads the normal, stored before it) and
// carries a material layer (anisotropy_strength), which is then held under the field's models
// and decodes as "no layer" elsewhere.
namespace {
std::string hdrpText() {
    std::ifstream in(test::shippedLayoutDir() / "hdrp-lit.toml");
    std::stringstream s;
    s << in.rdbuf();
    EXPECT_FALSE(s.str().empty());
    return s.str();
}
const char* kHdrpAniso = R"({ attribute = "anisotropy_direction", encoding = "anisotropy_angle_hdrp")";
}  // namespace

TEST(ShadingModelLayout, AConditionalFieldMayReadTheNormalAndCarryALayer) {
    const std::string text = hdrpText();
    const auto diags = checkLayout(text, kFile);
    ASSERT_TRUE(diags.empty()) << joined(diags);
    const Layout l = parseLayout(text, kFile);
    EXPECT_TRUE(l.storesConditionally(Attribute::AnisotropyStrength));
    EXPECT_EQ(l.conditionalModels(Attribute::AnisotropyStrength), bit(ShadingModel::Anisotropic));
    EXPECT_EQ(l.conditionalModels(Attribute::AnisotropyDirection), bit(ShadingModel::Anisotropic));
    EXPECT_EQ(l.conditionalModels(Attribute::Metallic), bit(ShadingModel::Anisotropic));
    EXPECT_TRUE(l.storesAlways(Attribute::Coat));  // the coat mask: a flag beside either feature
}

TEST(ShadingModelLayout, TheHdrpAnisotropyEncodingStoresTheTangentOnly) {
    const std::string text = edit(hdrpText(), kHdrpAniso, R"({ attribute = "coat_normal", encoding = "anisotropy_angle_hdrp")");
    expectError(text, placeOf(text, "\"anisotropy_angle_hdrp\""),
                {"'anisotropy_angle_hdrp' stores anisotropy_direction (with anisotropy_strength), not 'coat_normal'"});
}

TEST(ShadingModelLayout, TheHdrpAnisotropyEncodingReadsANormalStoredOnEveryPixel) {
    std::string text = edit(hdrpText(), R"(encoding = "normal_octahedral_hdrp", at = ["r + b[0:3]", "g + b[4:7]"],)",
                            R"(encoding = "normal_octahedral_hdrp", at = ["r + b[0:3]", "g + b[4:7]"], model = "default",)");
    expectError(text, placeOf(text, "\"anisotropy_angle_hdrp\""),
                {"reads 'normal', which the layout stores under default only (not under anisotropic, where "
                 "'anisotropy_direction' is held)"});
}

TEST(ShadingModelLayout, AConditionalFieldCarriesNoNonLayerAttribute) {
    const std::string text = edit(hdrpText(), R"(encoding = "float11_11_10_hdrp_ao_tag", at = ["r", "g", "b"],)",
                                  R"(encoding = "float11_11_10_hdrp_ao_tag", at = ["r", "g", "b"], model = "default",)");
    expectError(text, placeOf(text, "\"float11_11_10_hdrp_ao_tag\""),
                {"encoding 'float11_11_10_hdrp_ao_tag' of the conditional field 'emissive' reads 'occlusion' with it"});
}

// UE's ClearCoat with r.ClearCoatNormal = 1 (layouts/ue5-clearcoat-normal.toml): the normal is stored
// per model, in GBufferA under default and cloth and as a delta in CustomData under clear_coat, whose
// encoding reads the coat normal GBufferA holds under clear_coat, before it.
namespace {
std::string ueCoatNormalText() {
    std::ifstream in(test::shippedLayoutDir() / "ue5-clearcoat-normal.toml");
    std::stringstream s;
    s << in.rdbuf();
    EXPECT_FALSE(s.str().empty());
    return s.str();
}
const char* kCoatTop = R"({ attribute = "coat_normal", encoding = "normal_xyz", bits = 10, at = ["r", "g", "b"], model = "clear_coat",)";
const char* kBaseTop = R"({ attribute = "normal", encoding = "normal_xyz", bits = 10, at = ["r", "g", "b"], model = ["default", "cloth"],)";
const char* kBottom = R"({ attribute = "normal", encoding = "normal_octahedral_delta_ue")";
}  // namespace

TEST(ShadingModelLayout, AConditionalFieldMayReadWhatItsModelsStoreBeforeIt) {
    const std::string text = ueCoatNormalText();
    const auto diags = checkLayout(text, kFile);
    ASSERT_TRUE(diags.empty()) << joined(diags);
    const Layout l = parseLayout(text, kFile);
    using M = ShadingModel;
    EXPECT_TRUE(l.storesConditionally(Attribute::Normal));
    EXPECT_EQ(l.conditionalModels(Attribute::Normal), bit(M::Default) | bit(M::ClearCoat) | bit(M::Cloth));
    EXPECT_TRUE(storesOnEveryModel(l, Attribute::Normal));
    EXPECT_EQ(l.conditionalModels(Attribute::CoatNormal), bit(M::ClearCoat));
    EXPECT_TRUE(storesUnder(l, Attribute::CoatNormal, bit(M::ClearCoat)));
    EXPECT_FALSE(storesUnder(l, Attribute::CoatNormal, bit(M::ClearCoat) | bit(M::Cloth)));
    EXPECT_FALSE(storesOnEveryModel(l, Attribute::CoatNormal));
}

TEST(ShadingModelLayout, TheNormalIsStoredUnderEveryModelOfTheSelector) {
    const std::string text = edit(ueCoatNormalText(), kBaseTop,
                                  R"({ attribute = "normal", encoding = "normal_xyz", bits = 10, at = ["r", "g", "b"], model = "default",)");
    expectError(text, placeOf(text, R"("default", from = "gbi:418-421)"),
                {"'normal' is stored under default, clear_coat only", "under the selector's other models too: cloth"});
}

TEST(ShadingModelLayout, AConditionalFieldReadsWhatEachOfItsModelsStores) {
    // the coat normal under cloth, the bottom's delta under clear_coat: no coat normal to read there
    std::string text = edit(ueCoatNormalText(), kCoatTop,
                            R"({ attribute = "coat_normal", encoding = "normal_xyz", bits = 10, at = ["r", "g", "b"], model = "cloth",)");
    text = edit(text, kBaseTop,
                R"({ attribute = "normal", encoding = "normal_xyz", bits = 10, at = ["r", "g", "b"], model = ["default", "clear_coat"],)");
    expectError(text, placeOf(text, "\"normal_octahedral_delta_ue\""),
                {"reads 'coat_normal', which the layout stores under cloth only (not under clear_coat, where 'normal' is held)"});
}

TEST(ShadingModelLayout, AConditionalFieldReadsWhatItsModelsStoreBeforeIt) {
    // GBufferA holds the coat normal under cloth only, and under clear_coat it moves to GBufferE,
    // after GBufferD's delta: stored under the delta's model, but not before it.
    std::string text = edit(ueCoatNormalText(), kCoatTop,
                            R"({ attribute = "coat_normal", encoding = "normal_xyz", bits = 10, at = ["r", "g", "b"], model = "cloth",)");
    text = edit(text, kBaseTop,
                R"({ attribute = "normal", encoding = "normal_xyz", bits = 10, at = ["r", "g", "b"], model = "default",)");
    text = edit(text, R"({ attribute = "precomputed_shadow", encoding = "unorm", at = ["r", "g", "b", "a"], value = 1.0,)",
                R"({ attribute = "precomputed_shadow", encoding = "unorm", at = "r", value = 1.0, from = "lmc:230-290", status = "verified" },
  { attribute = "coat_normal", encoding = "normal_xyz", bits = 8, at = ["g", "b", "a"], model = "clear_coat",)");
    expectError(text, placeOf(text, "\"normal_octahedral_delta_ue\""),
                {"encoding 'normal_octahedral_delta_ue' of 'normal' reads 'coat_normal', which is stored after it"});
}

TEST(ShadingModelLayout, TheUeDeltaEncodingStoresTheNormalOnly) {
    const std::string text =
        edit(ueCoatNormalText(), kBottom, R"({ attribute = "coat_normal", encoding = "normal_octahedral_delta_ue")");
    expectError(text, placeOf(text, "\"normal_octahedral_delta_ue\""),
                {"'normal_octahedral_delta_ue' stores normal (relative to coat_normal), not 'coat_normal'"});
}
