// Every file in layouts/ validates, and the seed layouts have the sizes and bit positions their
// sources give (hand-computed below).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>

#include "cmd_layouts.h"
#include "layout.h"
#include "layout_atlas.h"
#include "layout_coverage.h"
#include "layout_catalog.h"

using namespace gbl;

namespace {

std::filesystem::path layoutsDir() { return GBL_SOURCE_LAYOUT_DIR; }

Layout load(const std::string& name) { return loadLayoutFile(layoutsDir() / (name + ".toml")); }

const Target& target(const Layout& l, const std::string& name) {
    for (const Target& t : l.targets)
        if (t.name == name) return t;
    throw std::runtime_error("no target " + name);
}

int bitsOf(const Layout& l, Attribute a) {
    for (const AttributeBits& ab : bitsPerAttribute(l))
        if (ab.attribute == a) return ab.bits;
    return 0;
}

// The bits of `a` on a pixel of model `m`: its unconditional fields' and those conditional on m,
// counted from the fields themselves (not bitsPerAttribute, which counts an attribute's widest).
int bitsUnder(const Layout& l, Attribute a, ShadingModel m) {
    int bits = 0;
    for (const Target& t : l.targets)
        for (const Field& f : t.fields)
            if (f.attribute == a && (!f.conditional() || ((f.models >> unsigned(m)) & 1u)))
                for (const CodePlace& c : f.codes) bits += c.bits();
    return bits;
}

// All colour-target bits a pixel of model m holds (each field's whose model set has m, or none).
int pixelBitsUnder(const Layout& l, ShadingModel m) {
    int bits = 0;
    for (const Target& t : l.targets)
        for (const Field& f : t.fields)
            if (!f.conditional() || ((f.models >> unsigned(m)) & 1u))
                for (const CodePlace& c : f.codes) bits += c.bits();
    return bits;
}

// The selector's table as "model id" pairs, in file order.
std::string selectorTable(const Layout& l) {
    std::string s;
    const Field* sel = l.selector();
    if (!sel) return s;
    for (const Field::ModelId& m : sel->selector)
        s += (s.empty() ? "" : ", ") + std::string(shadingModelInfo(m.model).name) + " " + std::to_string(m.id);
    return s;
}

}  // namespace

TEST(LayoutFiles, EveryFileValidates) {
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(layoutsDir())) {
        if (entry.path().extension() != ".toml") continue;
        ++files;
        const auto diags = checkLayoutFile(entry.path());
        std::string all;
        for (const auto& d : diags) all += d.text() + "\n";
        EXPECT_TRUE(diags.empty()) << all;
    }
    EXPECT_GE(files, 7);
}

TEST(LayoutFiles, SeedLayoutsArePresent) {
    const auto names = listLayoutNames(layoutsDir());
    for (const char* n :
         {"reference", "crysis2-slim", "crysis3-thin", "ryse", "ue4", "fat-naive", "compact-octahedral"})
        EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
}

// Hand-computed: targets' nominal sizes + the depth-stencil's (D24S8 = 4, D32 = 4, D32S8 = 5).
TEST(LayoutFiles, BytesPerPixel) {
    const std::map<std::string, int> expected = {
        {"reference", 8 * 16 + 4},         // eight RGBA32F (the material layers among them) + D32
        {"crysis2-slim", 4 + 4},           // A8B8G8R8 + D24S8
        {"crysis3-thin", 4 + 4 + 4},       // 2x A8B8G8R8 + D24S8
        {"ryse", 3 * 4 + 4},               // 3x RGBA8 + D24S8
        {"ue4", 5 * 4 + 5},                // GBufferA..E (4 bytes each) + D32S8
        {"fat-naive", 8 + 8 + 4 + 4},      // 2x RGBA16F + RGBA8 + D24S8
        {"compact-octahedral", 3 * 4 + 4},  // 3x RGBA8 + D32
        {"visibility-32", 4 + 4},           // R32_UINT ids + D32
        {"visibility-64", 8 + 4},           // R32G32_UINT ids + D32
    };
    for (const auto& [name, bytes] : expected) EXPECT_EQ(bytesPerPixel(load(name)), bytes) << name;
    // crysis2's light buffers: two RGBA16F on PC, two 32-bit A2B10G10R10F on the Xbox 360, two RGBA8 on the PS3
    EXPECT_EQ(lightBufferBytesPerPixel(load("crysis2-slim")), 16);
    EXPECT_EQ(lightBufferBytesPerPixel(load("crysis2-slim-x360")), 8);
    EXPECT_EQ(lightBufferBytesPerPixel(load("crysis2-slim-ps3")), 8);
    EXPECT_EQ(bytesPerPixel(load("crysis2-slim-x360")), 8);
    EXPECT_EQ(bytesPerPixel(load("crysis2-slim-ps3")), 8);
}

// The atlas of shipped engines (issue 15), hand-computed from each engine's formats.
TEST(LayoutFiles, AtlasBytesPerPixel) {
    const std::map<std::string, int> expected = {
        // UE 5.3.2's base pass: GBufferA (10:10:10:2) + B..E (RGBA8) + D32S8; no GBufferF (a separate
        // anisotropy pass) and no velocity (the depth pass) by default.
        {"ue5", 4 + 4 * 4 + 5},
        {"ue5-velocity", 4 + 2 * 4 + 8 + 2 * 4 + 5},  // A, B, C, velocity (RGBA16 UNORM), D, E + D32S8
        {"ue5-anisotropy", 4 + 5 * 4 + 5},            // A..E + GBufferF (RGBA8, the anisotropy pass's) + D32S8
        {"ue5-nostatic", 4 + 3 * 4 + 5},              // no GBufferE without static lighting
        {"ue5-16bit", 3 * 8 + 2 * 4 + 5},             // A..C RGBA16F, D and E stay RGBA8
        {"ue5-16bit-unorm", 3 * 8 + 2 * 4 + 5},       // UE 5.0.x: A..C RGBA16 UNORM
        {"ue4-elemental", 4 * 4 + 4},                 // Mittring 2012: four 32-bit targets + D24S8
        {"hdrp-lit-apv", 4 * 4 + 5},                  // hdrp-lit's targets; probe volumes change bits only
        {"hdrp-lit", 4 * 4 + 5},               // GBuffer0..2 RGBA8 + GBuffer3 B10G11R11 + D32S8
        {"urp-deferred", 3 * 4 + 5},           // GBuffer0..2 RGBA8 + D32S8
        {"urp-deferred-accurate", 3 * 4 + 5},  // the same targets, GBuffer2 UNORM
        {"bevy-deferred", 16 + 1 + 4},         // Rgba32Uint + R8Uint pass id + Depth32Float
        {"bevy-deferred-webgl2", 16 + 1 + 4},  // the same targets; the depth also in word b's 20 bits
        {"bevy-deferred-clearcoat", 16 + 1 + 4},  // Bevy 0.19: the same targets, the clear coat in b's spare byte
        {"ue5-clearcoat", 4 + 4 * 4 + 5},      // ue5's targets; CustomData holds the coat
        {"ue5-cloth", 4 + 4 * 4 + 5},          // ue5's targets; CustomData holds the fuzz colour
        {"ue5-clearcoat-normal", 4 + 4 * 4 + 5},  // ue5's targets; CustomData.a, .z the bottom normal
        {"granite", 4 + 4 + 4 + 2 + 4},        // B10G11R11 + RGBA8 + A2B10G10R10 + RG8 + D24S8
        {"granite-2025", 4 + 4 + 4 + 2 + 4},   // the same targets + D32_SFLOAT (no stencil)
        // Valient, Develop 2007: four RGBA8 + D24S8 = 20 bytes; the talk's "36 MB" is this at
        // 1280x720 with 2x MSAA: 20 * 1280 * 720 * 2 = 36.9e6 bytes.
        {"killzone2", 4 * 4 + 4},
        {"niagara", 4 + 4 + 4},                // zeux/niagara: RGBA8 + A2B10G10R10 + D32
        // 64-bit ids with depth in word 1, and no depth attachment in the raster pass (Nanite's
        // render pass has no targets; Bevy's raster pass has depth_stencil_attachment None).
        {"nanite-visbuffer", 8},
        {"bevy-meshlet-visbuffer", 8},
    };
    for (const auto& [name, bytes] : expected) EXPECT_EQ(bytesPerPixel(load(name)), bytes) << name;
    EXPECT_NEAR(bytesPerPixel(load("killzone2")) * 1280.0 * 720.0 * 2.0 / 1e6, 36.0, 1.0);
    EXPECT_GE(listLayoutNames(layoutsDir()).size(), 25u);  // issue 28: at least 24 layouts + the reference
    EXPECT_EQ(listLayoutNames(layoutsDir()).size(), 34u);  // 33 and the reference: layouts/README.md's atlas
}

// Where the atlas layouts put their bits (each engine's source, as the layout files cite it).
TEST(LayoutFiles, AtlasBitsPerAttribute) {
    const Layout bevy = load("bevy-deferred");
    EXPECT_EQ(bitsOf(bevy, Attribute::BaseColor), 24);  // gamma 2.2, 8 bits each
    EXPECT_EQ(bitsOf(bevy, Attribute::Emissive), 32);   // RGB9E5
    EXPECT_EQ(bitsOf(bevy, Attribute::Normal), 24);     // oct 12:12
    EXPECT_EQ(bitsOf(bevy, Attribute::Flags), 8);
    EXPECT_EQ(bitsOf(bevy, Attribute::PassId), 8);
    // WebGL2: word b = depth20 << 12 | occlusion4 << 8 | metallic4 << 4 | reflectance4.
    const Layout webgl2 = load("bevy-deferred-webgl2");
    EXPECT_EQ(bitsOf(webgl2, Attribute::Specular), 4);
    EXPECT_EQ(bitsOf(webgl2, Attribute::Metallic), 4);
    EXPECT_EQ(bitsOf(webgl2, Attribute::Occlusion), 4);
    EXPECT_EQ(bitsOf(webgl2, Attribute::Depth), 20);
    ASSERT_TRUE(webgl2.findField(Attribute::Depth));
    EXPECT_EQ(webgl2.findField(Attribute::Depth)->codes[0].text, "b[12:31]");
    const Field* e = bevy.findField(Attribute::Emissive);
    ASSERT_TRUE(e);
    ASSERT_EQ(e->codes.size(), 4u);  // r, g, b mantissas, then the shared exponent in bits 27..31
    EXPECT_EQ(codeLabel(*e, 3), "e");
    EXPECT_EQ(e->codes[3].bits(), 5);
    EXPECT_EQ(e->codes[3].pieces.at(0).first, 27);
    const Layout hdrp = load("hdrp-lit");
    const Field* n = hdrp.findField(Attribute::Normal);
    ASSERT_TRUE(n);
    // PackFloat2To888: 12-bit u = R + B[0:3], v = G + B[4:7].
    ASSERT_EQ(n->codes.size(), 2u);
    EXPECT_EQ(n->codes[0].bits(), 12);
    EXPECT_EQ(n->codes[0].pieces.size(), 2u);
    EXPECT_EQ(n->codes[1].pieces.at(1).first, 4);
    EXPECT_EQ(bitsOf(hdrp, Attribute::Emissive), 32);  // B10G11R11
    // HDRP 13's material feature id is the selector (GBuffer2.a bits 5..7; MaterialGBufferMacros.hlsl
    // :29, 34: standard 0, anisotropic 4) and switches GBuffer0.rgb and GBuffer2.rgb (Lit.hlsl:541-543,
    // 575-661): the diffuse colour and fresnel0 on standard pixels, the base colour, the tangent's
    // angle (8), the signed anisotropy (8), storeSin (1) and a 5-bit metallic on anisotropic ones.
    for (const char* name : {"hdrp-lit", "hdrp-lit-apv"}) {
        SCOPED_TRACE(name);
        using M = ShadingModel;
        const Layout h = load(name);
        ASSERT_TRUE(h.selector());
        EXPECT_EQ(selectorTable(h), "default 0, anisotropic 4");
        EXPECT_EQ(h.selector()->codes.at(0).text, "a[5:7]");
        EXPECT_EQ(bitsOf(h, Attribute::MaterialFeature), 0);
        EXPECT_EQ(bitsUnder(h, Attribute::DiffuseColor, M::Default), 24);
        EXPECT_EQ(bitsUnder(h, Attribute::SpecularColor, M::Default), 24);
        EXPECT_EQ(bitsUnder(h, Attribute::BaseColor, M::Default), 0);
        EXPECT_EQ(bitsUnder(h, Attribute::DiffuseColor, M::Anisotropic), 0);
        EXPECT_EQ(bitsUnder(h, Attribute::BaseColor, M::Anisotropic), 24);
        EXPECT_EQ(bitsUnder(h, Attribute::AnisotropyDirection, M::Anisotropic), 17);
        EXPECT_EQ(bitsUnder(h, Attribute::Metallic, M::Anisotropic), 5);
        EXPECT_EQ(bitsUnder(h, Attribute::Coat, M::Anisotropic), 5);  // the coat is a flag beside either feature
        EXPECT_EQ(bitsUnder(h, Attribute::Coat, M::Default), 5);
        EXPECT_EQ(pixelBitsUnder(h, M::Anisotropic), pixelBitsUnder(h, M::Default) - 2);  // GBuffer2.b[6:7] spare there
    }
    EXPECT_EQ(bitsOf(hdrp, Attribute::Coat), 5);  // PackFloatInt8bit(coatMask, featureId, 8): the coat's 5 bits
    EXPECT_EQ(bitsOf(hdrp, Attribute::CoatRoughness), 0);  // a constant in HDRP ...
    ASSERT_TRUE(hdrp.findFallback(Attribute::CoatRoughness));
    EXPECT_EQ(hdrp.findFallback(Attribute::CoatRoughness)->value, std::vector<double>{0.1});  // ... sqrt(0.01)
    // Bevy 0.19: the spare byte of word b, strength in bits 24..27, roughness in 28..31.
    const Layout bevyCoat = load("bevy-deferred-clearcoat");
    EXPECT_EQ(bevyCoat.findField(Attribute::Coat)->codes[0].text, "b[24:27]");
    EXPECT_EQ(bevyCoat.findField(Attribute::CoatRoughness)->codes[0].text, "b[28:31]");
    EXPECT_EQ(bevyCoat.findField(Attribute::CoatRoughness)->encoding, "coat_roughness_bevy");
    EXPECT_EQ(bitsOf(bevyCoat, Attribute::CoatNormal), 0);  // the base normal serves
    EXPECT_EQ(bitsOf(bevy, Attribute::Coat), 0);            // Bevy 0.16: the byte spare
    // UE 5.3.2 with the shading model per pixel (ue5): GBufferB.a bits 0..3 the id (ShadingCommon.ush
    // :20-34), GBufferD CustomData per model (ShadingModelsMaterial.ush:37-40, 85-117, 133-139).
    {
        const Layout ue5 = load("ue5");
        using M = ShadingModel;
        EXPECT_EQ(selectorTable(ue5), "default 1, clear_coat 4, cloth 8");
        EXPECT_EQ(ue5.selector()->codes.at(0).text, "a[0:3]");
        EXPECT_EQ(ue5.selector()->totalBits(), 4);
        // Default Lit: CustomData's 32 bits, the zero it keeps; no layer.
        EXPECT_EQ(bitsUnder(ue5, Attribute::CustomData, M::Default), 32);
        EXPECT_EQ(bitsUnder(ue5, Attribute::Coat, M::Default), 0);
        EXPECT_EQ(bitsUnder(ue5, Attribute::SheenColor, M::Default), 0);
        // ClearCoat: coat in .x, coat roughness in .y, 8 bits each; .z, .w unwritten (no bottom
        // normal at r.ClearCoatNormal = 0); no sheen, no custom_data constant.
        EXPECT_EQ(bitsUnder(ue5, Attribute::Coat, M::ClearCoat), 8);
        EXPECT_EQ(bitsUnder(ue5, Attribute::CoatRoughness, M::ClearCoat), 8);
        EXPECT_EQ(bitsUnder(ue5, Attribute::CoatNormal, M::ClearCoat), 0);
        EXPECT_EQ(bitsUnder(ue5, Attribute::SheenColor, M::ClearCoat), 0);
        EXPECT_EQ(bitsUnder(ue5, Attribute::CustomData, M::ClearCoat), 0);
        // Cloth: the fuzz colour in .rgb, 24 bits; its roughness is the base one (no bits).
        EXPECT_EQ(bitsUnder(ue5, Attribute::SheenColor, M::Cloth), 24);
        EXPECT_EQ(bitsUnder(ue5, Attribute::SheenRoughness, M::Cloth), 0);
        EXPECT_EQ(bitsUnder(ue5, Attribute::Coat, M::Cloth), 0);
        ASSERT_TRUE(ue5.findFallback(Attribute::SheenRoughness));
        EXPECT_EQ(ue5.findFallback(Attribute::SheenRoughness)->kind, FallbackKind::FromRoughness);
        // What each model's pixel holds of GBufferD (the rest of A..E the same for all): 32 bits
        // for Default Lit's constant, 16 for ClearCoat, 24 for Cloth; the bytes per pixel count
        // the shared bits once (25, AtlasBytesPerPixel).
        const int shared = pixelBitsUnder(ue5, M::Default) - 32;
        EXPECT_EQ(pixelBitsUnder(ue5, M::ClearCoat), shared + 16);
        EXPECT_EQ(pixelBitsUnder(ue5, M::Cloth), shared + 24);
        EXPECT_EQ(shared, 4 * 32);  // GBufferA, B, C and E: every bit stored on every pixel
        EXPECT_EQ(bitsOf(ue5, Attribute::Coat), 8);
        EXPECT_EQ(bitsOf(ue5, Attribute::SheenColor), 24);
        // r.ClearCoatNormal = 1 (ue5-clearcoat-normal): on a ClearCoat pixel GBufferA's 30 bits hold
        // the coat's normal and CustomData.a, .z the bottom normal's delta (ShadingModelsMaterial.ush
        // :96-116), 16 bits more than ue5's ClearCoat pixel; the other models' pixels as ue5's.
        const Layout ccn = load("ue5-clearcoat-normal");
        EXPECT_EQ(selectorTable(ccn), selectorTable(ue5));
        for (M m : {M::Default, M::Cloth}) {
            EXPECT_EQ(bitsUnder(ccn, Attribute::Normal, m), 30);
            EXPECT_EQ(bitsUnder(ccn, Attribute::CoatNormal, m), 0);
            EXPECT_EQ(pixelBitsUnder(ccn, m), pixelBitsUnder(ue5, m));
        }
        EXPECT_EQ(bitsUnder(ccn, Attribute::CoatNormal, M::ClearCoat), 30);
        EXPECT_EQ(bitsUnder(ccn, Attribute::Normal, M::ClearCoat), 16);
        EXPECT_EQ(pixelBitsUnder(ccn, M::ClearCoat), pixelBitsUnder(ue5, M::ClearCoat) + 16);
        EXPECT_EQ(bytesPerPixel(ccn), bytesPerPixel(ue5));
        EXPECT_TRUE(ccn.storesConditionally(Attribute::Normal));
        EXPECT_TRUE(storesOnEveryModel(ccn, Attribute::Normal));
        std::ostringstream out, err;
        ASSERT_EQ(showLayoutCommand("ue5-clearcoat-normal", out, err), 0) << err.str();
        EXPECT_NE(out.str().find("normal                  30  (per model, at most: default, clear_coat, cloth)"),
                  std::string::npos) << out.str();
        EXPECT_FALSE(storesOnEveryModel(ccn, Attribute::CoatNormal));
        bool delta = false;
        for (const Target& t : ccn.targets)
            for (const Field& f : t.fields)
                if (f.attribute == Attribute::Normal && f.models == (1u << unsigned(M::ClearCoat))) {
                    delta = true;
                    EXPECT_EQ(t.name, "GBufferD");
                    EXPECT_EQ(f.encoding, "normal_octahedral_delta_ue");
                    ASSERT_EQ(f.codes.size(), 2u);
                    EXPECT_EQ(f.codes[0].text, "a");  // CustomData.a = oct3.x
                    EXPECT_EQ(f.codes[1].text, "b");  // CustomData.z = oct3.y
                }
        EXPECT_TRUE(delta);
    }
    // UE5's ClearCoat shading model: CustomData.x, .y.
    const Layout ue5Coat = load("ue5-clearcoat");
    EXPECT_EQ(bitsOf(ue5Coat, Attribute::Coat), 8);
    EXPECT_EQ(bitsOf(ue5Coat, Attribute::CoatRoughness), 8);
    EXPECT_EQ(ue5Coat.findField(Attribute::ShadingModelId)->value, std::vector<double>{4.0});
    const Layout ue5Cloth = load("ue5-cloth");  // Cloth: sqrt(fuzz colour) in CustomData.rgb
    EXPECT_EQ(bitsOf(ue5Cloth, Attribute::SheenColor), 24);
    EXPECT_EQ(ue5Cloth.findField(Attribute::SheenColor)->encoding, "unorm_sqrt");
    EXPECT_EQ(ue5Cloth.findField(Attribute::ShadingModelId)->value, std::vector<double>{8.0});
    EXPECT_EQ(bitsOf(load("killzone2"), Attribute::Normal), 32);  // two FP16
    EXPECT_EQ(bitsOf(load("urp-deferred"), Attribute::Roughness), 7);  // smoothness in an SNORM byte
    // UE 5's default base pass writes neither GBufferF nor velocity; r.VelocityOutputPass = 1 adds
    // velocity after GBufferC; GBufferC.a holds the precomputed irradiance, not occlusion.
    const Layout ue5 = load("ue5");
    EXPECT_EQ(bitsOf(ue5, Attribute::Tangent), 0);
    EXPECT_EQ(bitsOf(ue5, Attribute::Velocity), 0);
    EXPECT_EQ(bitsOf(ue5, Attribute::Occlusion), 0);
    EXPECT_EQ(ue5.findFallback(Attribute::Occlusion)->value, std::vector<double>{1.0});
    EXPECT_EQ(bitsOf(ue5, Attribute::PrecomputedIrradiance), 8);
    EXPECT_EQ(ue5.findField(Attribute::SelectiveOutputMask)->value, std::vector<double>{8.0});  // SKIP_VELOCITY
    EXPECT_EQ(bitsOf(ue5, Attribute::ShadingModel), 4);  // the selector, GBufferB.a bits 0..3
    EXPECT_EQ(bitsOf(ue5, Attribute::ShadingModelId), 0);  // no constant id any more
    const Layout velocity = load("ue5-velocity");
    EXPECT_EQ(bitsOf(velocity, Attribute::Velocity), 32);
    ASSERT_EQ(velocity.targets.size(), 6u);
    EXPECT_EQ(velocity.targets[3].name, "Velocity");  // after GBufferC, before GBufferD
    EXPECT_EQ(velocity.findField(Attribute::SelectiveOutputMask)->value, std::vector<double>{0.0});
    EXPECT_EQ(bitsOf(load("ue5-16bit"), Attribute::BaseColor), 48);
    EXPECT_EQ(bitsOf(load("ue5-16bit-unorm"), Attribute::Normal), 48);  // n * 0.5 + 0.5 in UNORM16
    EXPECT_EQ(bitsOf(load("hdrp-lit-apv"), Attribute::SpecularOcclusion), 7);  // PackFloatInt8bit(so, isLightmap, 2)
    EXPECT_EQ(bitsOf(load("hdrp-lit-apv"), Attribute::IsLightmap), 1);
    // HDRP keeps ambient occlusion in GBuffer3's AO tag: the emissive field stores it.
    for (const char* name : {"hdrp-lit", "hdrp-lit-apv"}) {
        const Layout l = load(name);
        const Field* ao = l.findField(Attribute::Occlusion);
        ASSERT_TRUE(ao) << name;
        EXPECT_EQ(ao, l.findField(Attribute::Emissive)) << name;
        EXPECT_EQ(ao->encoding, "float11_11_10_hdrp_ao_tag") << name;
        EXPECT_EQ(l.targets[3].name, "GBuffer3") << name;
        EXPECT_FALSE(l.findFallback(Attribute::Occlusion)) << name;
    }
    // r.AnisotropicMaterials = 1: GBufferF after E, the tangent and anisotropy carried and shaded.
    const Layout aniso = load("ue5-anisotropy");
    ASSERT_EQ(aniso.targets.size(), 6u);
    EXPECT_EQ(aniso.targets[5].name, "GBufferF");
    EXPECT_EQ(bitsOf(aniso, Attribute::AnisotropyDirection), 24);
    EXPECT_EQ(bitsOf(aniso, Attribute::AnisotropyStrength), 8);
    EXPECT_EQ(aniso.findField(Attribute::AnisotropyStrength)->encoding, "unorm_signed");
    // The selector takes the id and HAS_ANISOTROPY (1 << 4): Default Lit with anisotropy is 17, and
    // GBufferF holds the tangent and anisotropy on those pixels only; elsewhere the clear's 0.5
    // (the extras tangent and anisotropy, 24 + 8 bits), which UE does not read.
    EXPECT_EQ(selectorTable(aniso), "default 1, clear_coat 4, cloth 8, anisotropic 17");
    EXPECT_EQ(aniso.selector()->codes.at(0).text, "a[0:4]");
    EXPECT_EQ(aniso.findField(Attribute::SelectiveOutputMask)->value, std::vector<double>{4.0});  // bits 5..7: SKIP_VELOCITY
    EXPECT_EQ(bitsUnder(aniso, Attribute::AnisotropyDirection, ShadingModel::Anisotropic), 24);
    EXPECT_EQ(bitsUnder(aniso, Attribute::AnisotropyDirection, ShadingModel::Default), 0);
    EXPECT_EQ(bitsUnder(aniso, Attribute::Tangent, ShadingModel::Anisotropic), 0);
    for (ShadingModel m : {ShadingModel::Default, ShadingModel::ClearCoat, ShadingModel::Cloth}) {
        EXPECT_EQ(bitsUnder(aniso, Attribute::Tangent, m), 24);
        EXPECT_EQ(bitsUnder(aniso, Attribute::Anisotropy, m), 8);
        EXPECT_EQ(bitsUnder(aniso, Attribute::AnisotropyStrength, m), 0);
    }
    EXPECT_EQ(bitsUnder(aniso, Attribute::Coat, ShadingModel::ClearCoat), 8);
    EXPECT_EQ(bitsUnder(aniso, Attribute::SheenColor, ShadingModel::Cloth), 24);
    // ue5-cloth: every pixel Cloth; the sheen roughness is the base roughness.
    EXPECT_EQ(ue5Cloth.findFallback(Attribute::SheenRoughness)->kind, FallbackKind::FromRoughness);
    EXPECT_TRUE(load("granite-2025").depth.reversedZ);
    EXPECT_FALSE(load("granite").depth.reversedZ);
    // niagara: emissive is one 8-bit ratio to the albedo's luminance, read after the albedo.
    const Layout niagara = load("niagara");
    EXPECT_EQ(bitsOf(niagara, Attribute::Emissive), 8);
    EXPECT_EQ(bitsOf(niagara, Attribute::Normal), 20);  // dithered octahedral 10:10
    EXPECT_EQ(bitsOf(niagara, Attribute::Roughness), 10);
    EXPECT_EQ(niagara.findField(Attribute::Emissive)->encoding, "emissive_albedo_ratio");
    EXPECT_TRUE(niagara.depth.reversedZ);
}

// `layouts list` groups as the atlas does: each family once, its layouts under it by year.
TEST(LayoutFiles, ListGroupsByFamily) {
    setenv("GBL_LAYOUT_DIR", GBL_SOURCE_LAYOUT_DIR, 1);
    std::ostringstream out, err;
    ASSERT_EQ(listLayoutsCommand(out, err), 0) << err.str();
    unsetenv("GBL_LAYOUT_DIR");
    std::istringstream lines(out.str());
    std::string line, family;
    std::map<std::string, std::string> familyOf;
    std::map<std::string, int> yearOf;
    std::vector<std::string> families;
    int lastYear = 0;
    std::getline(lines, line);  // header
    EXPECT_EQ(line.rfind("family / layout", 0), 0u) << line;
    while (std::getline(lines, line)) {
        if (line.rfind("  ", 0) != 0) {
            family = line;
            EXPECT_EQ(std::count(families.begin(), families.end(), family), 0) << family << " listed twice";
            families.push_back(family);
            lastYear = 0;
            continue;
        }
        std::istringstream row(line);
        std::string name;
        int year = 0;
        row >> name >> year;
        familyOf[name] = family;
        yearOf[name] = year;
        EXPECT_GE(year, lastYear) << name << ": layouts of a family are listed by year";
        lastYear = year;
        if (name == "killzone2") {
            EXPECT_NE(line.find(" 20 "), std::string::npos) << line;
        }
        if (name == "crysis2-slim") {
            EXPECT_NE(line.find("8 +16 light"), std::string::npos) << line;
        }
    }
    EXPECT_EQ(familyOf.size(), listLayoutNames(layoutsDir()).size());
    EXPECT_EQ(familyOf["ue4"], "Unreal Engine");
    EXPECT_EQ(familyOf["ue5"], "Unreal Engine");
    EXPECT_EQ(familyOf["hdrp-lit"], "Unity");
    EXPECT_EQ(familyOf["urp-deferred"], "Unity");
    EXPECT_EQ(familyOf["crysis3-thin"], "CryENGINE");
    EXPECT_EQ(yearOf["killzone2"], 2007);
    EXPECT_EQ(familyOf["niagara"], "niagara");
    EXPECT_EQ(yearOf["niagara"], 2024);
    // Families by their earliest year: early deferred (2005) before Guerrilla (2007) before CryENGINE (2011).
    const auto pos = [&](const std::string& f) { return std::find(families.begin(), families.end(), f) - families.begin(); };
    EXPECT_LT(pos("early deferred"), pos("Guerrilla"));
    EXPECT_LT(pos("Guerrilla"), pos("CryENGINE"));
    // The same facts as the atlas entry of each file.
    const AtlasEntry ue5 = atlasEntryOf(load("ue5"));
    EXPECT_EQ(ue5.family, "Unreal Engine");
    EXPECT_EQ(ue5.bytesPerPixel, 25);
    EXPECT_EQ(ue5.bytesKind, "attributes");
    EXPECT_EQ(atlasAttributeSummary(atlasEntryOf(load("killzone2"))).find("normal 32 normal_xy_float16"), 0u);
}

TEST(LayoutFiles, BitsPerAttribute) {
    const Layout c3 = load("crysis3-thin");
    EXPECT_EQ(bitsOf(c3, Attribute::Normal), 8 + 8 + 1);
    EXPECT_EQ(bitsOf(c3, Attribute::Roughness), 7);
    EXPECT_EQ(bitsOf(c3, Attribute::DiffuseColor), 16);  // Y + one chroma per pixel
    EXPECT_EQ(bitsOf(c3, Attribute::SpecularColor), 8);  // luma only
    EXPECT_EQ(bitsOf(c3, Attribute::AmbientId), 4);
    const Layout ue4 = load("ue4");
    EXPECT_EQ(bitsOf(ue4, Attribute::Normal), 30);
    EXPECT_EQ(bitsOf(ue4, Attribute::PerObject), 2);
    EXPECT_EQ(bitsOf(ue4, Attribute::ShadingModelId), 4);
    EXPECT_EQ(bitsOf(ue4, Attribute::SelectiveOutputMask), 4);
    EXPECT_EQ(bitsOf(ue4, Attribute::BaseColor), 24);
    const Layout c2 = load("crysis2-slim");
    EXPECT_EQ(bitsOf(c2, Attribute::Normal), 24);
    EXPECT_EQ(bitsOf(c2, Attribute::Roughness), 8);
    EXPECT_EQ(bitsOf(c2, Attribute::BaseColor), 0);  // deferred lighting: no albedo
    EXPECT_EQ(bitsOf(c2, Attribute::SpecularColor), 0);
    EXPECT_EQ(bitsOf(load("compact-octahedral"), Attribute::Normal), 24);
    EXPECT_EQ(bitsOf(load("reference"), Attribute::Normal), 96);
}

// Crysis 3 RT0's third byte: gloss in bits 0..6, the normal's z sign in bit 7.
TEST(LayoutFiles, Crysis3GlossAndZSignShareOneByte) {
    const Layout l = load("crysis3-thin");
    const Target& rt0 = target(l, "RT0");
    EXPECT_EQ(rt0.format, "A8B8G8R8_UNORM_PACK32");
    const Field* normal = l.findField(Attribute::Normal);
    const Field* gloss = l.findField(Attribute::Roughness);
    ASSERT_TRUE(normal && gloss);
    EXPECT_EQ(normal->encoding, "normal_xy_zsign");
    EXPECT_EQ(gloss->encoding, "gloss");
    ASSERT_EQ(normal->codes.size(), 3u);
    const int b = 2;  // channel index of "b"
    ASSERT_EQ(rt0.channels[b].name, "b");
    EXPECT_EQ(rt0.channels[b].offset, 16);
    const BitRange sign = normal->codes[2].pieces.at(0);
    EXPECT_EQ(sign.channel, b);
    EXPECT_EQ(sign.first, 7);
    EXPECT_EQ(sign.count, 1);
    ASSERT_EQ(gloss->codes.size(), 1u);
    const BitRange g = gloss->codes[0].pieces.at(0);
    EXPECT_EQ(g.channel, b);
    EXPECT_EQ(g.first, 0);
    EXPECT_EQ(g.count, 7);
    EXPECT_EQ(codeLabel(*normal, 2), "z_sign");
    // x and y fill r and g
    EXPECT_EQ(normal->codes[0].pieces.at(0).channel, 0);
    EXPECT_EQ(normal->codes[0].bits(), 8);
    EXPECT_EQ(normal->codes[1].pieces.at(0).channel, 1);
    // the chroma checkerboard resolved to the registry's interleaved encoding
    EXPECT_EQ(l.findField(Attribute::DiffuseColor)->encoding, "ycbcr_checkerboard");
}

TEST(LayoutFiles, Ue4ShadingModelAndMaskShareGBufferBAlpha) {
    const Layout l = load("ue4");
    const Field* id = l.findField(Attribute::ShadingModelId);
    const Field* mask = l.findField(Attribute::SelectiveOutputMask);
    ASSERT_TRUE(id && mask);
    EXPECT_EQ(id->encoding, kIdEncoding);
    EXPECT_EQ(id->value.at(0), 1.0);
    const Target& b = target(l, "GBufferB");
    EXPECT_EQ(b.channels[static_cast<size_t>(id->codes[0].pieces[0].channel)].name, "a");
    EXPECT_EQ(id->codes[0].pieces[0].first, 0);
    EXPECT_EQ(id->codes[0].pieces[0].count, 4);
    EXPECT_EQ(mask->codes[0].pieces[0].first, 4);
    EXPECT_EQ(mask->codes[0].pieces[0].count, 4);
    EXPECT_TRUE(l.depth.reversedZ);
    EXPECT_EQ(l.findFallback(Attribute::SpecularColor)->kind, FallbackKind::Ue4);
}

TEST(LayoutFiles, CompactNormalSpansChannels) {
    const Layout l = load("compact-octahedral");
    const Field* n = l.findField(Attribute::Normal);
    ASSERT_TRUE(n);
    ASSERT_EQ(n->codes.size(), 2u);
    for (const CodePlace& c : n->codes) {
        EXPECT_EQ(c.bits(), 12);
        ASSERT_EQ(c.pieces.size(), 2u);
        EXPECT_EQ(c.pieces[0].count, 8);  // low byte first
        EXPECT_EQ(c.pieces[1].count, 4);
    }
    EXPECT_EQ(n->codes[0].pieces[1].first, 0);
    EXPECT_EQ(n->codes[1].pieces[1].first, 4);
}

TEST(LayoutFiles, Crysis2IsDeferredLighting) {
    const Layout l = load("crysis2-slim");
    EXPECT_EQ(l.pipeline, Pipeline::DeferredLighting);
    EXPECT_FALSE(l.stores(Attribute::BaseColor));
    EXPECT_FALSE(l.stores(Attribute::SpecularColor));
    EXPECT_EQ(l.findFallback(Attribute::BaseColor)->kind, FallbackKind::MaterialPass);
    ASSERT_EQ(l.lightBuffers.size(), 2u);
    EXPECT_EQ(l.lightBuffers[0].encoding, LightBufferEncoding::Float16);
    EXPECT_EQ(l.materialPass.fresnel, MaterialFresnel::None);
    EXPECT_EQ(load("crysis2-slim-x360").lightBuffers[1].encoding, LightBufferEncoding::Float7e3);
    EXPECT_EQ(load("crysis2-slim-ps3").lightBuffers[1].encoding, LightBufferEncoding::Rgbk);
    EXPECT_EQ(load("crysis2-slim-ps3").lightBuffers[1].range, 32.0);
    EXPECT_EQ(l.depth.format, "D24_UNORM_S8_UINT");
    ASSERT_EQ(l.depth.stencil.size(), 1u);
    EXPECT_EQ(l.depth.stencil[0].attribute, Attribute::Indoor);
}

TEST(LayoutFiles, CatalogFindsByNameAndPath) {
    setenv("GBL_LAYOUT_DIR", GBL_SOURCE_LAYOUT_DIR, 1);
    EXPECT_EQ(loadLayout("ue4").name, "ue4");
    EXPECT_EQ(loadLayout((layoutsDir() / "ryse.toml").string()).name, "ryse");
    try {
        loadLayout("ue6");  // not (yet) a layout: ue5 is
        FAIL() << "expected an error";
    } catch (const UserError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("unknown layout 'ue6'"), std::string::npos) << m;
        EXPECT_NE(m.find("crysis3-thin"), std::string::npos) << m;
    }
    setenv("GBL_LAYOUT_DIR", "/nonexistent/layouts", 1);
    EXPECT_THROW(layoutDirectory(), UserError);
    unsetenv("GBL_LAYOUT_DIR");
}

TEST(LayoutFiles, Commands) {
    setenv("GBL_LAYOUT_DIR", GBL_SOURCE_LAYOUT_DIR, 1);
    std::ostringstream out, err;
    EXPECT_EQ(checkLayoutsCommand({}, out, err), 0) << err.str();
    EXPECT_NE(out.str().find("ok "), std::string::npos);
    EXPECT_TRUE(err.str().empty()) << err.str();

    out.str("");
    EXPECT_EQ(listLayoutsCommand(out, err), 0) << err.str();
    EXPECT_NE(out.str().find("crysis3-thin"), std::string::npos);
    EXPECT_NE(out.str().find("12"), std::string::npos);

    out.str("");
    EXPECT_EQ(showLayoutCommand("crysis3-thin", out, err), 0) << err.str();
    const std::string show = out.str();
    EXPECT_NE(show.find("b[7]"), std::string::npos) << show;
    EXPECT_NE(show.find("b[0:6]"), std::string::npos) << show;
    EXPECT_NE(show.find("bytes per pixel: 12"), std::string::npos) << show;

    out.str("");
    err.str("");
    EXPECT_EQ(runLayoutsCommand({"frobnicate"}, out, err), 2);
    EXPECT_NE(err.str().find("usage"), std::string::npos);
    unsetenv("GBL_LAYOUT_DIR");
}

// `layouts show` of a layout with a shading-model selector (tests/layout/data/shading-models.toml):
// every model of the selector with its id and the fields it holds, each conditional field's bits
// with its models, the bits per attribute of those stored under some models only, and where their
// fallbacks apply, all as the parsed layout says.
TEST(LayoutFiles, ShowNamesTheSelectorsModelsAndTheConditionalFields) {
    const std::filesystem::path file =
        std::filesystem::path(GBL_SOURCE_LAYOUT_DIR).parent_path() / "tests" / "layout" / "data" / "shading-models.toml";
    const Layout layout = loadLayoutFile(file);
    std::ostringstream out, err;
    ASSERT_EQ(showLayoutCommand(file.string(), out, err), 0) << err.str();
    const std::string show = out.str();
    EXPECT_NE(show.find("shading models (selector 'a[0:3]', 4 bits"), std::string::npos) << show;
    for (const Field::ModelId& m : layout.selector()->selector) {
        const std::string name = shadingModelInfo(m.model).name;
        const size_t at = show.find("\n  " + name + " ");
        ASSERT_NE(at, std::string::npos) << name << "\n" << show;
        const std::string line = show.substr(at + 1, show.find('\n', at + 1) - at - 1);
        EXPECT_NE(line.find("id " + std::to_string(m.id)), std::string::npos) << line;
        for (const Target& t : layout.targets)
            for (const Field& f : t.fields)
                if ((f.models >> unsigned(m.model)) & 1u) {
                    EXPECT_NE(line.find(attributeName(f.attribute)), std::string::npos) << line;
                }
    }
    // a conditional field's row: its bits, then "under" its models
    size_t conditionalRows = 0;
    std::istringstream lines(show);
    for (std::string line; std::getline(lines, line);)
        if (line.find("  under ") != std::string::npos) ++conditionalRows;
    size_t codes = 0;
    for (const Target& t : layout.targets)
        for (const Field& f : t.fields)
            if (f.conditional()) codes += f.codes.size();
    EXPECT_EQ(conditionalRows, codes) << show;
    EXPECT_NE(show.find("specular                8  (under default, cloth, anisotropic only)"), std::string::npos) << show;
    EXPECT_NE(show.find("not under default, cloth, anisotropic"), std::string::npos) << show;
    EXPECT_NE(show.find("the selector"), std::string::npos) << show;
    EXPECT_NE(show.find("bytes per pixel: 20"), std::string::npos) << show;
}
