// The layout language: a valid file reads into the expected data model, and every error message
// names file:line:col exactly (the place of the offending key or value) with what is wrong and
// what is allowed. Each test edits one line of a small valid layout; the expected place is found
// by searching the edited text for a marker, so the assertions stay exact if the base text moves.
#include "layout_test_support.h"

using namespace gbl;
using namespace gbl::layout_test;

// ---- the valid layout ---------------------------------------------------------------------------

TEST(LayoutParser, ValidLayoutReadsIntoTheModel) {
    const auto diags = checkLayout(kValid, kFile);
    ASSERT_TRUE(diags.empty()) << joined(diags);
    const Layout l = parseLayout(kValid, kFile);
    EXPECT_EQ(l.name, "test");
    EXPECT_EQ(l.title, "A test layout");
    EXPECT_EQ(l.source.game, "none");
    EXPECT_EQ(l.source.year, 2024);
    EXPECT_EQ(l.pipeline, Pipeline::DeferredShading);
    EXPECT_EQ(l.sourceFile, kFile);
    EXPECT_EQ(l.depth.format, "D24_UNORM_S8_UINT");
    EXPECT_EQ(l.depth.depthBits, 24);
    EXPECT_EQ(l.depth.stencilBits, 8);
    EXPECT_FALSE(l.depth.reversedZ);
    ASSERT_EQ(l.depth.stencil.size(), 1u);
    EXPECT_EQ(l.depth.stencil[0].attribute, Attribute::AmbientId);
    EXPECT_EQ(l.depth.stencil[0].value, std::vector<double>{2});
    ASSERT_EQ(l.targets.size(), 1u);
    const Target& t = l.targets[0];
    EXPECT_EQ(t.name, "rt0");
    EXPECT_EQ(t.bits(), 32);
    EXPECT_EQ(t.usedBits(), 32);
    ASSERT_EQ(t.channels.size(), 4u);
    EXPECT_EQ(t.channels[3].name, "a");
    EXPECT_EQ(t.channels[3].offset, 24);
    ASSERT_EQ(t.fields.size(), 3u);
    const Field& base = t.fields[2];
    EXPECT_EQ(base.attribute, Attribute::BaseColor);
    ASSERT_EQ(base.codes.size(), 3u);
    EXPECT_EQ(base.codes[0].bits(), 3);
    EXPECT_EQ(base.codes[1].pieces[0].first, 3);
    EXPECT_EQ(base.codes[2].bits(), 2);
    EXPECT_EQ(base.codes[2].text, "a[6:7]");
    EXPECT_EQ(l.fallbacks.size(), 6u);
    EXPECT_EQ(l.fallbacks.front().attribute, Attribute::SpecularColor);  // file order
    EXPECT_EQ(l.findFallback(Attribute::SpecularColor)->kind, FallbackKind::FromMetallic);
    EXPECT_EQ(l.findFallback(Attribute::Occlusion)->value, std::vector<double>{1.0});
    EXPECT_EQ(l.findFallback(Attribute::Emissive)->value, (std::vector<double>{0, 0, 0}));  // broadcast
    EXPECT_EQ(bytesPerPixel(l), 8);
    const auto bits = bitsPerAttribute(l);
    ASSERT_EQ(bits.size(), 4u);
    EXPECT_EQ(bits[0].attribute, Attribute::Normal);
    EXPECT_EQ(bits[0].bits, 17);
}

TEST(LayoutParser, TableFieldSyntaxAndSplitCodes) {
    // [[target.field]] tables instead of an inline array; a code split over two channels.
    const std::string text = edit(kValid, R"(field = [
  { attribute = "normal", encoding = "normal_xy_zsign", at = ["r", "g", "b[7]"] },
  { attribute = "roughness", encoding = "gloss", at = "b[0:6]" },
  { attribute = "base_color", encoding = "unorm", at = ["a[0:2]", "a[3:5]", "a[6:7]"] },
]
)",
                                  R"(
[[target.field]]
attribute = "normal"
encoding = "normal_octahedral"
bits = 12
at = ["r + b[0:3]", "g + b[4:7]"]

[[target.field]]
attribute = "roughness"
encoding = "unorm"
transform = "gloss"
at = "a"
)");
    const std::string withColor =
        edit(edit(text, "diffuse_color = \"from_base_color\"", "diffuse_color = 0.5\nbase_color = [0.5, 0.5, 0.5]"),
             "base_color = 0.0\n", "");
    const auto diags = checkLayout(withColor, kFile);
    ASSERT_TRUE(diags.empty()) << joined(diags);
    const Layout l = parseLayout(withColor, kFile);
    const Field* n = l.findField(Attribute::Normal);
    ASSERT_TRUE(n);
    ASSERT_EQ(n->codes.size(), 2u);
    EXPECT_EQ(n->codes[0].bits(), 12);
    ASSERT_EQ(n->codes[1].pieces.size(), 2u);
    EXPECT_EQ(n->codes[1].pieces[0].channel, 1);  // g: low 8 bits
    EXPECT_EQ(n->codes[1].pieces[1].channel, 2);  // b[4:7]: high 4 bits
    EXPECT_EQ(n->codes[1].pieces[1].first, 4);
    EXPECT_EQ(l.findField(Attribute::Roughness)->encoding, "gloss");  // unorm + transform gloss
}

// ---- bits ---------------------------------------------------------------------------------------

TEST(LayoutParser, BitsOverflowingAChannelSayByHowMuch) {
    const std::string text = edit(kValid, "\"a[6:7]\"", "\"a[6:9]\"");
    expectError(text, placeOf(text, "\"a[6:9]\""),
                {"bit range 'a[6:9]' overflows channel 'a' of R8G8B8A8_UNORM (8 bits) by 2 bits"});
    // and the target as a whole: 34 bits in 32
    expectError(text, placeOf(text, "\"R8G8B8A8_UNORM\""),
                {"fields of target 'rt0' need 34 bits but R8G8B8A8_UNORM holds 32 (2 bits over)"});
}

TEST(LayoutParser, OverlappingBitRangesNameBothFields) {
    const std::string text = edit(kValid, "\"b[0:6]\"", "\"b[0:7]\"");
    expectError(text, placeOf(text, "\"b[0:7]\""),
                {"bits b[7] of field 'roughness' at 'b[0:7]' overlap field 'normal' at 'b[7]' (line 14)"});
}

TEST(LayoutParser, CodeCountMismatch) {
    const std::string text = edit(kValid, "\"normal_xy_zsign\"", "\"normal_octahedral\"");
    expectError(text, placeOf(text, "[\"r\", \"g\", \"b[7]\"]"),
                {"encoding 'normal_octahedral' has 2 codes (u, v) for 'normal' but 3 places are given"});
}

TEST(LayoutParser, BitsOutsideTheEncodingsRange) {
    const std::string text = edit(kValid, "[\"r\", \"g\", \"b[7]\"]", "[\"r[0:0]\", \"g[0:0]\", \"b[7]\"]");
    expectError(text, placeOf(text, "\"r[0:0]\""),
                {"encoding 'normal_xy_zsign' takes 2..16 bits per code; code x of 'normal' at 'r[0:0]' has 1"});
}

TEST(LayoutParser, FixedWidthEncodingSaysItsWidth) {
    const std::string text =
        edit(kValid, "{ attribute = \"normal\", encoding = \"normal_xy_zsign\", at = [\"r\", \"g\", \"b[7]\"] }",
             "{ attribute = \"normal\", encoding = \"normal_bestfit\", at = [\"r\", \"g\", \"b[7]\"] }");
    expectError(text, placeOf(text, "\"b[7]\""),
                {"encoding 'normal_bestfit' takes 8 bits per code", "code z", "has 1"});
}

TEST(LayoutParser, ZSignIsOneBit) {
    const std::string text = edit(kValid, "\"b[7]\"", "\"b[6:7]\"");
    expectError(text, placeOf(text, "\"b[6:7]\""),
                {"encoding 'normal_xy_zsign' stores code z_sign in exactly 1 bit; 'b[6:7]' has 2"});
}

TEST(LayoutParser, WholeValueEncodingsTakeOneBitCount) {
    const std::string text = edit(kValid, "[\"r\", \"g\", \"b[7]\"]", "[\"r\", \"g[0:6]\", \"b[7]\"]");
    expectError(text, placeOf(text, "\"g[0:6]\""), {"takes one bit count for all its codes", "code y", "has 7"});
}

// dither_per_frame: only on a dithered encoding, true or false; read into the field.
TEST(LayoutParser, DitherPerFrameIsForDitheredEncodings) {
    const std::string plain = edit(kValid, "encoding = \"gloss\", at", "encoding = \"gloss\", dither_per_frame = true, at");
    expectError(plain, placeOf(plain, "true"), {"'dither_per_frame' is for a dithered encoding", "'gloss' has no dither"});
    const std::string dithered =
        edit(kValid, "encoding = \"normal_xy_zsign\", at = [\"r\", \"g\", \"b[7]\"]",
             "encoding = \"normal_octahedral_dithered\", at = [\"r\", \"g\"], dither_per_frame = %s");
    const std::string notBool = edit(dithered, "%s", "\"yes\"");
    expectError(notBool, placeOf(notBool, "\"yes\""), {"'dither_per_frame' must be true or false"});
    for (const bool value : {true, false}) {
        const std::string text = edit(dithered, "%s", value ? "true" : "false");
        const auto diags = checkLayout(text, kFile);
        ASSERT_TRUE(diags.empty()) << joined(diags);
        const Layout l = parseLayout(text, kFile);
        const Field& f = l.targets[0].fields[0];
        EXPECT_EQ(f.encoding, "normal_octahedral_dithered");
        EXPECT_TRUE(f.ditherDeclared);
        EXPECT_EQ(f.ditherPerFrame, value);
    }
}

TEST(LayoutParser, DeclaredBitsMustMatchThePlaces) {
    const std::string text = edit(kValid, "encoding = \"gloss\", at", "encoding = \"gloss\", bits = 8, at");
    expectError(text, placeOf(text, "\"b[0:6]\""), {"field 'roughness': 'bits' says 8 but 'b[0:6]' holds 7 bits"});
}

TEST(LayoutParser, FloatChannelsHoldWholeFloatCodes) {
    const std::string text = edit(kValid, "\"R8G8B8A8_UNORM\"", "\"R16G16B16A16_SFLOAT\"");
    expectError(text, placeOf(text, "\"b[0:6]\""),
                {"channel 'b' of R16G16B16A16_SFLOAT is a float channel", "float16", "'gloss'"});
}

TEST(LayoutParser, SrgbChannelsHoldSrgb8) {
    const std::string text = edit(kValid, "\"R8G8B8A8_UNORM\"", "\"R8G8B8A8_SRGB\"");
    expectError(text, placeOf(text, "\"r\""), {"channel 'r' of R8G8B8A8_SRGB is an sRGB channel", "srgb8"});
}

// ---- attributes and encodings -------------------------------------------------------------------

TEST(LayoutParser, EncodingMustSuitTheAttribute) {
    const std::string colour = edit(kValid, "encoding = \"gloss\"", "encoding = \"srgb8\"");
    expectOnlyError(colour, placeOf(colour, "\"srgb8\""), {"'srgb8' encodes RGB colours, not 'roughness'"});
    const std::string normal =
        edit(kValid, "\"normal_xy_zsign\", at = [\"r\", \"g\", \"b[7]\"]", "\"unorm\", at = [\"r\", \"g\", \"b[7]\"]");
    expectOnlyError(normal, placeOf(normal, "\"unorm\""), {"'normal' has components in [-1,1]", "snorm"});
    const std::string gloss =
        edit(kValid, "\"base_color\", encoding = \"unorm\"", "\"base_color\", encoding = \"gloss\"");
    expectOnlyError(gloss, placeOf(gloss, "\"gloss\"", 1), {"'gloss' stores roughness only"});
}

TEST(LayoutParser, MissingRequiredAttributeNamesIt) {
    const std::string text = edit(
        edit(kValid, "normal = [0.0, 0.0, 1.0]\n", ""),
        "  { attribute = \"normal\", encoding = \"normal_xy_zsign\", at = [\"r\", \"g\", \"b[7]\"] },\n", "");
    expectOnlyError(text, std::string(kFile) + ":1:1",
                    {"the layout stores no 'normal'", "must store normal and roughness"});
}

TEST(LayoutParser, AttributeStoredTwice) {
    const std::string text =
        edit(kValid, "\"base_color\", encoding = \"unorm\"", "\"roughness\", encoding = \"unorm\"");
    expectError(text, placeOf(text, "{ attribute = \"roughness\", encoding = \"unorm\""),
                {"attribute 'roughness' is already stored (line 15)"});
}

TEST(LayoutParser, ExtrasNeedAValue) {
    const std::string text = edit(kValid, ", value = 2 }", " }");
    expectOnlyError(text, placeOf(text, "{ attribute = \"ambient_id\""), {"field 'ambient_id' needs a 'value'"});
}

TEST(LayoutParser, IdValueMustFitItsBits) {
    const std::string text = edit(kValid, "value = 2", "value = 16");
    expectOnlyError(text, placeOf(text, "\"s[0:3]\""), {"value 16 does not fit in 4 bits", "max 15"});
}

TEST(LayoutParser, ValueIsForExtrasOnly) {
    const std::string text = edit(kValid, "at = \"b[0:6]\" }", "at = \"b[0:6]\", value = 0.5 }");
    expectOnlyError(text, placeOf(text, "0.5 }"), {"'value' is for extra attributes", "'roughness'"});
}

TEST(LayoutParser, StencilNeedsAStencilFormat) {
    const std::string text = edit(kValid, "\"D24_UNORM_S8_UINT\"", "\"D32_SFLOAT\"");
    expectOnlyError(text, placeOf(text, "[ { attribute = \"ambient_id\""), {"D32_SFLOAT has no stencil bits"});
}

TEST(LayoutParser, StencilHoldsIntegerExtrasOnly) {
    const std::string text = edit(kValid, "\"ambient_id\", at", "\"occlusion\", at");
    expectError(text, placeOf(text, "\"occlusion\""), {"the stencil holds integer extras only; 'occlusion'"});
}

TEST(LayoutParser, InterleaveNeedsAnEncodingThatHasIt) {
    const std::string text =
        edit(kValid, "encoding = \"unorm\", at", "encoding = \"unorm\", interleave = \"checkerboard\", at");
    expectOnlyError(text, placeOf(text, "\"checkerboard\""),
                    {"encoding 'unorm' has no such variant", "ycbcr + interleave checkerboard"});
}

TEST(LayoutParser, UnknownTransform) {
    const std::string text = edit(kValid, "encoding = \"gloss\"", "encoding = \"unorm\", transform = \"gamma\"");
    expectOnlyError(text, placeOf(text, "\"gamma\""), {"unknown transform 'gamma'", "cry_smoothness"});
}

TEST(LayoutParser, TooManyTargets) {
    std::string text = kValid;
    std::string extra;
    for (int i = 1; i <= 8; ++i)
        extra +=
            "[[target]]\nname = \"t" + std::to_string(i) +
            "\"\nformat = \"R8_UNORM\"\nfield = [ { attribute = \"per_project\", encoding = \"unorm\", at = \"r\", "
            "value = 0.0 } ]\n";
    text = edit(text, "[fallback]", extra + "[fallback]");
    expectError(text, placeOf(text, "[[target]]", 8), {"more than 8 render targets"});  // the 9th
}

// ---- clear values (issue 11 item 3) -------------------------------------------------------------

TEST(LayoutParser, ClearIsDeclaredForEveryStoredAttribute) {
    const std::string noTable = kValid.substr(0, kValid.find("[clear]"));
    expectOnlyError(noTable, std::string(kFile) + ":1:1", {"declares no [clear] table"});
    const std::string missing = edit(kValid, "base_color = 0.0\n", "");
    expectOnlyError(missing, placeOf(missing, "[clear]"), {"no value for 'base_color'", "line 16"});
    const std::string unstored = edit(kValid, "base_color = 0.0\n", "base_color = 0.0\nspecular = 0.5\n");
    expectOnlyError(unstored, placeOf(unstored, "0.5\n", 1), {"clear value for 'specular'", "no target stores"});
    const std::string outside = edit(kValid, "roughness = 1.0\n", "roughness = 2.0\n");
    expectOnlyError(outside, placeOf(outside, "2.0"), {"clear value of 'roughness'", "outside"});
}

// ---- normal space (issue 11 item 4) -------------------------------------------------------------

TEST(LayoutParser, NormalSpaceIsDeclared) {
    const Layout ok = parseLayout(kValid, kFile);
    EXPECT_EQ(ok.space.normal, StoredSpace::WorldZUp);
    EXPECT_EQ(parseLayout(edit(kValid, "up = \"z\"", "up = \"y\""), kFile).space.normal, StoredSpace::WorldYUp);
    EXPECT_EQ(parseLayout(edit(kValid, "normal = \"world\"\nup = \"z\"\n", "normal = \"view\"\n"), kFile).space.normal,
              StoredSpace::View);
    // No [space] at all: refused at 1:1.
    const std::string noTable = edit(kValid, "[space]\nnormal = \"world\"\nup = \"z\"\n", "");
    expectOnlyError(noTable, std::string(kFile) + ":1:1", {"declares no [space] table"});
    // [space] without `normal`: refused at the table.
    const std::string noNormal = edit(kValid, "normal = \"world\"\n", "");
    expectError(noNormal, placeOf(noNormal, "[space]"), {"[space] has no 'normal'"});
    // World space without an up axis, an unknown space, an unknown axis: at the value.
    const std::string noUp = edit(kValid, "up = \"z\"\n", "");
    expectOnlyError(noUp, placeOf(noUp, "\"world\""), {"declare the engine's up axis"});
    const std::string bad = edit(kValid, "\"world\"", "\"object\"");
    expectError(bad, placeOf(bad, "\"object\""), {"unknown normal space 'object'", "world, view"});
    const std::string badUp = edit(kValid, "up = \"z\"", "up = \"x\"");
    expectOnlyError(badUp, placeOf(badUp, "\"x\""), {"unknown up axis 'x'"});
    // A position space without a stored position.
    const std::string pos = edit(kValid, "up = \"z\"\n", "up = \"z\"\nposition = \"view\"\n");
    expectOnlyError(pos, placeOf(pos, "\"view\""), {"stores no 'position'"});
}

// ---- fallbacks ----------------------------------------------------------------------------------

TEST(LayoutParser, MissingFallbackNamesTheAttribute) {
    const std::string text = edit(kValid, "emissive = 0.0\n", "");
    expectOnlyError(text, placeOf(text, "[fallback]"),
                    {"the layout does not store 'emissive' and declares no fallback for it", "\"forward\""});
}

TEST(LayoutParser, UnknownFallbackListsTheAllowedOnes) {
    const std::string text = edit(kValid, "\"from_metallic\"", "\"from_metalic\"");
    expectError(text, placeOf(text, "\"from_metalic\""),
                {"unknown fallback 'from_metalic' for 'specular_color'",
                 "allowed: from_metallic, ue4, material_pass, or a constant"});
}

// sheen_roughness = "from_roughness" (UE's cloth lobe takes the base roughness): accepted there,
// decoded as the roughness; refused for any other attribute, with the allowed ones listed.
TEST(LayoutParser, FromRoughnessIsTheSheenRoughnessOnly) {
    const std::string ok = edit(kValid, "occlusion = 1.0", "occlusion = 1.0\nsheen_roughness = \"from_roughness\"");
    EXPECT_TRUE(checkLayout(ok, kFile).empty());
    const Layout l = parseLayout(ok, kFile);
    ASSERT_TRUE(l.findFallback(Attribute::SheenRoughness));
    EXPECT_EQ(l.findFallback(Attribute::SheenRoughness)->kind, FallbackKind::FromRoughness);
    const std::string bad = edit(kValid, "occlusion = 1.0", "occlusion = \"from_roughness\"");
    expectError(bad, placeOf(bad, "\"from_roughness\""),
                {"unknown fallback 'from_roughness' for 'occlusion'", "allowed: material_pass, or a constant"});
}

TEST(LayoutParser, FallbackForAStoredAttribute) {
    const std::string text = edit(kValid, "occlusion = 1.0", "occlusion = 1.0\nroughness = 0.5");
    expectOnlyError(text, placeOf(text, "roughness = 0.5"), {"'roughness' cannot fall back"});
    const std::string stored =
        edit(kValid, "diffuse_color = \"from_base_color\"", "diffuse_color = \"from_base_color\"\nbase_color = 0.5");
    expectOnlyError(stored, placeOf(stored, "0.5\n", 0),
                    {"fallback for 'base_color' but the layout stores it (line 16)"});
}

TEST(LayoutParser, FallbackConstantsAreChecked) {
    const std::string range = edit(kValid, "occlusion = 1.0", "occlusion = 1.5");
    expectError(range, placeOf(range, "1.5"), {"fallback for 'occlusion'", "outside [0,1]"});
    const std::string count = edit(kValid, "occlusion = 1.0", "occlusion = [1.0, 1.0]");
    expectError(count, placeOf(count, "[1.0, 1.0]"), {"fallback for 'occlusion' has 2 components, 'occlusion' has 1"});
}

TEST(LayoutParser, FallbackCycle) {
    const std::string text = edit(kValid, "metallic = 0.0", "metallic = \"from_specular_color\"");
    expectOnlyError(text, placeOf(text, "\"from_metallic\""),
                    {"fallbacks form a cycle: specular_color -> metallic -> specular_color"});
}

TEST(LayoutParser, MaterialPassNeedsDeferredLighting) {
    const std::string text = edit(kValid, "occlusion = 1.0", "occlusion = \"material_pass\"");
    expectOnlyError(text, placeOf(text, "\"material_pass\""), {"'material_pass'", "deferred-lighting"});
}

TEST(LayoutParser, DeferredLightingRules) {
    std::string text = edit(kValid, "\"deferred-shading\"", "\"deferred-lighting\"");
    // base_color is stored and there are no light buffers: two errors
    expectError(text, placeOf(text, "{ attribute = \"base_color\""),
                {"a deferred-lighting layout does not store 'base_color'", "material_pass"});
    expectError(text, std::string(kFile) + ":1:1", {"declares its light buffers", "[[light_buffer]]"});
    // a light buffer with diffuse only
    text += "\n[[light_buffer]]\nname = \"diffuse\"\nformat = \"R16G16B16A16_SFLOAT\"\nencoding = \"float16\"\n"
            "holds = [\"diffuse_rgb\"]\n";
    expectError(text, placeOf(text, "[[light_buffer]]"), {"the light buffers hold no specular light"});
    const std::string bad = edit(text, "[\"diffuse_rgb\"]", "[\"diffuse_rgb\", \"ambient\"]");
    expectError(bad, placeOf(bad, "\"ambient\""), {"unknown light quantity 'ambient'", "specular_luminance"});
}

TEST(LayoutParser, LightBuffersOnlyForDeferredLighting) {
    const std::string text =
        kValid + "\n[[light_buffer]]\nname = \"l\"\nformat = \"R16G16B16A16_SFLOAT\"\nencoding = \"float16\"\n"
                 "holds = [\"diffuse_rgb\"]\n";
    expectOnlyError(text, placeOf(text, "[[light_buffer]]"),
                    {"light buffers belong to pipeline = \"deferred-lighting\""});
}

// A shipped deferred-lighting layout as text, renamed to the test file's name.
std::string lightingLayoutText(const char* name) {
    std::ifstream in(std::filesystem::path(GBL_SOURCE_LAYOUT_DIR) / (std::string(name) + ".toml"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return edit(text, std::string("name = \"") + name + "\"", "name = \"test\"");
}

TEST(LayoutParser, ShippedLightPrePassLayoutsAreValid) {
    for (const char* name : {"crysis2-slim", "crysis2-slim-x360", "crysis2-slim-ps3"}) {
        const auto diags = checkLayout(lightingLayoutText(name), kFile);
        EXPECT_TRUE(diags.empty()) << name << ":\n" << joined(diags);
    }
}

TEST(LayoutParser, LightBufferEncodingMustFitItsFormat) {
    const std::string x360 = lightingLayoutText("crysis2-slim-x360");
    // 7e3 in a 16-bit float format
    std::string t = edit(x360, "A2B10G10R10_UNORM_PACK32", "R16G16B16A16_SFLOAT");
    expectOnlyError(t, placeOf(t, "\"float7e3\""),
                    {"light buffer 'diffuse_acc'", "encoding 'float7e3' does not fit R16G16B16A16_SFLOAT", "10:10:10:2"});
    // float16 in a 32-bit 10:10:10:2 format
    t = edit(x360, "encoding = \"float7e3\"", "encoding = \"float16\"");
    expectOnlyError(t, placeOf(t, "\"float16\""), {"encoding 'float16' does not fit A2B10G10R10_UNORM_PACK32"});
    // R11G11B10F needs B10G11R11_UFLOAT_PACK32
    t = edit(x360, "encoding = \"float7e3\"", "encoding = \"float11_11_10\"");
    expectOnlyError(t, placeOf(t, "\"float11_11_10\""), {"does not fit", "B10G11R11_UFLOAT_PACK32"});
    // the 2-bit alpha of 7e3 holds no light: Engel's luminance does not fit
    t = edit(x360, "holds = [\"specular_rgb\"]", "holds = [\"specular_rgb\", \"specular_luminance\"]");
    expectOnlyError(t, placeOf(t, "[\"specular_rgb\", \"specular_luminance\"]"),
                    {"holds 4 channels but encoding 'float7e3' stores 3"});
    // unknown encoding
    t = edit(x360, "\"float7e3\"", "\"float8e2\"");
    expectOnlyError(t, placeOf(t, "\"float8e2\""), {"unknown light-buffer encoding 'float8e2'", "rgbk"});

    const std::string ps3 = lightingLayoutText("crysis2-slim-ps3");
    // RGBK in an sRGB format, and in a 16-bit one
    t = edit(ps3, "format = \"A8B8G8R8_UNORM_PACK32\"\nencoding", "format = \"A8B8G8R8_SRGB_PACK32\"\nencoding");
    expectOnlyError(t, placeOf(t, "\"rgbk\""), {"encoding 'rgbk' does not fit A8B8G8R8_SRGB_PACK32", "UNORM"});
    // RGBK needs its range; a float encoding takes none
    t = edit(ps3, "range = 32\n", "");
    expectOnlyError(t, placeOf(t, "\"rgbk\""), {"encoding 'rgbk' needs 'range'"});
    t = edit(ps3, "range = 32", "range = 0.5");
    expectOnlyError(t, placeOf(t, "0.5"), {"'range' 0.5 must lie in [1, 65025]"});
    t = edit(lightingLayoutText("crysis2-slim"), "encoding = \"float16\"\n", "encoding = \"float16\"\nrange = 8\n");
    expectOnlyError(t, placeOf(t, "8\nholds"), {"'range' is for encoding = \"rgbk\""});
    // the encoding is required
    t = edit(ps3, "encoding = \"rgbk\"\nrange = 32\n", "");
    expectOnlyError(t, placeOf(t, "[[light_buffer]]"), {"[[light_buffer]] has no 'encoding'"});
}

TEST(LayoutParser, MaterialPassTableIsDeclaredForDeferredLighting) {
    const std::string c2 = lightingLayoutText("crysis2-slim");
    std::string t = edit(c2, "[material_pass]\nfresnel = \"none\"\nstatus = \"assumed\"\n", "");
    expectOnlyError(t, std::string(kFile) + ":1:1", {"[material_pass]", "schlick_nv"});
    t = edit(c2, "[material_pass]\nfresnel = \"none\"", "[material_pass]\nfresnel = \"per_light\"");
    expectOnlyError(t, placeOf(t, "\"per_light\""), {"unknown fresnel 'per_light'"});
    t = kValid + "\n[material_pass]\nfresnel = \"none\"\n";
    expectOnlyError(t, placeOf(t, "[material_pass]"), {"[material_pass] belongs to pipeline = \"deferred-lighting\""});
}

// ---- source citation ----------------------------------------------------------------------------

TEST(LayoutParser, SourceIsRequired) {
    const std::string text = edit(kValid, "source = { game = \"none\", talk = \"unit test\", year = 2024 }\n", "");
    expectOnlyError(text, std::string(kFile) + ":1:1", {"has no 'source'", "year"});
    const std::string noYear = edit(kValid, ", year = 2024 }", " }");
    expectOnlyError(noYear, placeOf(noYear, "{ game"), {"source has no 'year'"});
}

// ---- all problems at once, in file order; the exception ------------------------------------------

TEST(LayoutParser, ReportsEveryProblemInFileOrder) {
    std::string text = edit(kValid, "\"normal_xy_zsign\"", "\"octt\"");
    text = edit(text, "\"base_color\", encoding", "\"base_colour\", encoding");
    text = edit(text, "emissive = 0.0\n", "");
    const auto diags = checkLayout(text, kFile);
    ASSERT_GE(diags.size(), 3u) << joined(diags);
    for (size_t i = 1; i < diags.size(); ++i) EXPECT_LE(diags[i - 1].place.line, diags[i].place.line);
    try {
        (void)parseLayout(text, kFile);
        FAIL() << "expected LayoutError";
    } catch (const LayoutError& e) {
        EXPECT_EQ(e.diagnostics.size(), diags.size());
        const std::string what = e.what();
        EXPECT_NE(what.find("unknown encoding 'octt'"), std::string::npos);
        EXPECT_NE(what.find("\n"), std::string::npos);  // one line per problem
    }
}

TEST(LayoutParser, FileNameMustMatchLayoutName) {
    const auto dir = std::filesystem::temp_directory_path() / ("gbl_layout_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto path = dir / "other.toml";
    {
        std::ofstream f(path);
        f << kValid;
    }
    const auto diags = checkLayoutFile(path);
    ASSERT_EQ(diags.size(), 1u) << joined(diags);
    EXPECT_EQ(diags[0].text().rfind(path.string() + ":1:8: layout name 'test' differs from the file name 'other'", 0),
              0u)
        << diags[0].text();
    EXPECT_THROW(loadLayoutFile(path), LayoutError);
    EXPECT_THROW(loadLayoutFile(dir / "missing.toml"), UserError);
    std::filesystem::remove_all(dir);
}
