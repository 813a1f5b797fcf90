// Generated wiring: the GLSL of every layouts/*.toml compiles inside its includers (G-buffer pass,
// material pass, lighting, decode), in both bit-exact and native-formats modes; and the CPU mirror
// round-trips random surfaces within each encoding's documented error bound; in a layout with a
// shading-model selector, each field on the pixels of the models it is stored under (every model the
// selector names occurs), not on the others'.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>

#include "cmd_layouts.h"
#include "cpu_codec.h"
#include "encoding_registry.h"
#include "encodings.h"
#include "layout_catalog.h"
#include "shader_compiler.h"
#include "layout_files.h"
#include "surface_support.h"
#include "wiring_codegen.h"

using namespace gbl;

namespace {

void compileWith(const std::string& shader, const GBufferWiring& w,
                 std::vector<std::pair<std::string, std::string>> defines = {}) {
    ShaderSource s = loadShaderFile(shader);
    s.defines.push_back({"TEXTURE_COUNT", "4"});
    for (auto& d : defines) s.defines.push_back(d);
    s.virtualFiles["gbuffer_wiring.glsl"] = w.glsl;
    s.name = shader + " (generated wiring of layout " + w.layoutName + ")";
    EXPECT_NO_THROW(compileGlsl(s)) << w.glsl;
}

// The angle between two directions in degrees, as 2 atan2(|x - y|, |x + y|) of the unit vectors
// in double: acos of a float dot product cannot resolve less than sqrt(2 * 2^-24) rad = 0.0198
// degrees, above the step of a 16-bit normal_xyz (ue5-16bit-unorm's, 0.0017 degrees).
double angleDeg(glm::vec3 a, glm::vec3 b) {
    const glm::dvec3 x = glm::normalize(glm::dvec3(a)), y = glm::normalize(glm::dvec3(b));
    return 2.0 * std::atan2(glm::length(x - y), glm::length(x + y)) * 57.29577951308232;
}

// Smooth random fields (checkerboard chroma reconstructs from neighbours) plus per-pixel noise
// where the attribute is not stored as checkerboard chroma.
std::vector<Surface> makeSurfaces(int w, int h, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Surface> v(size_t(w) * size_t(h));
    const float ph[6] = {u(rng) * 6, u(rng) * 6, u(rng) * 6, u(rng) * 6, u(rng) * 6, u(rng) * 6};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Surface& s = v[size_t(y) * size_t(w) + size_t(x)];
            glm::vec3 n;
            do n = glm::vec3(u(rng), u(rng), u(rng)) * 2.0f - 1.0f;
            while (glm::dot(n, n) > 1.0f || glm::dot(n, n) < 1e-4f);
            s.normal = glm::normalize(n);
            auto smooth = [&](int k) {
                return 0.5f + 0.45f * std::sin(0.07f * float(x) + ph[k]) * std::cos(0.05f * float(y) + ph[(k + 3) % 6]);
            };
            s.baseColor = glm::vec3(u(rng), u(rng), u(rng));
            s.metallic = u(rng);
            s.roughness = u(rng);
            s.specular = u(rng);
            s.specularColor = glm::vec3(u(rng), u(rng), u(rng));
            s.diffuseColor = glm::vec3(smooth(0), smooth(1), smooth(2));
            s.occlusion = u(rng);
            s.emissive = glm::vec3(u(rng), u(rng), u(rng)) * 4.0f;
            s.position = (glm::vec3(u(rng), u(rng), u(rng)) * 2.0f - 1.0f) * 50.0f;
            s.coat = u(rng);
            s.coatRoughness = u(rng);
            s.anisotropyStrength = u(rng);
            s.sheenColor = glm::vec3(u(rng), u(rng), u(rng));
            glm::vec3 t;
            do t = glm::vec3(u(rng), u(rng), u(rng)) * 2.0f - 1.0f;
            while (glm::dot(t, t) > 1.0f || glm::dot(t, t) < 1e-4f);
            s.anisotropyDirection = glm::normalize(t);
        }
    return v;
}

// Documented bounds (shaders/encodings.glsl comments), per code width.
double unormBound(int b) { return (0.5 + std::ldexp(1.0, b - 24)) / (std::ldexp(1.0, b) - 1.0) + 1e-7; }

}  // namespace

TEST(WiringCodegen, GeneratedGlslCompilesForEveryLayout) {
    const std::vector<Layout> layouts = test::shippedAttributeLayouts();
    ASSERT_GE(layouts.size(), 7u);
    for (const Layout& l : layouts) {
        for (bool native : {false, true}) {
            SCOPED_TRACE(l.name + (native ? " (native formats)" : ""));
            const GBufferWiring w = generateWiring(l, WiringOptions{native});
            EXPECT_NE(w.glsl.find("generated from the layout '" + l.name + "' by gbufferlab"), std::string::npos);
            EXPECT_EQ(w.targetFormats.size(), l.targets.size());
            compileWith("gbuffer_pass.frag.glsl", w);
            compileWith("lighting_pass.comp.glsl", w);
            compileWith("decode_pass.comp.glsl", w);
            if (w.materialPass) compileWith("gbuffer_pass.frag.glsl", w, {{"MATERIAL_PASS_WRITE", "1"}});
        }
    }
}

TEST(WiringCodegen, CompileErrorNamesTheLayout) {
    GBufferWiring w = generateWiring(test::shippedLayout("ue4"));
    w.glsl += "\nthis is not glsl;\n";
    ShaderSource s = loadShaderFile("decode_pass.comp.glsl");
    s.virtualFiles["gbuffer_wiring.glsl"] = w.glsl;
    s.name = "decode_pass.comp.glsl (generated wiring of layout ue4)";
    try {
        compileGlsl(s);
        FAIL() << "expected a compile error";
    } catch (const ShaderCompileError& e) {
        EXPECT_NE(std::string(e.what()).find("ue4"), std::string::npos) << e.what();
    }
}

TEST(WiringCodegen, WiringFlagsAndFormats) {
    const GBufferWiring c2 = generateWiring(test::shippedLayout("crysis2-slim"));
    EXPECT_TRUE(c2.materialPass);
    EXPECT_EQ(c2.materialTargetFormats.size(), 4u);  // 15 floats
    const GBufferWiring c3 = generateWiring(test::shippedLayout("crysis3-thin"));
    EXPECT_TRUE(c3.emissiveForward);
    EXPECT_FALSE(c3.materialPass);
    EXPECT_EQ(c3.targetFormats, (std::vector<VkFormat>{VK_FORMAT_R32_UINT, VK_FORMAT_R32_UINT}));
    EXPECT_EQ(c3.depthFormat, VK_FORMAT_D24_UNORM_S8_UINT);
    const GBufferWiring fat = generateWiring(test::shippedLayout("fat-naive"), WiringOptions{true});
    EXPECT_EQ(fat.targetFormats, (std::vector<VkFormat>{VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT,
                                                        VK_FORMAT_R8G8B8A8_UNORM}));
    const GBufferWiring ref = makeReferenceWiring();
    EXPECT_EQ(ref.layoutName, "reference");
    EXPECT_EQ(ref.targetFormats.size(), 8u);  // five of the base attributes, three (and an alpha) of the layers
    // Bits inside a channel keep a target UINT under native formats, and the GLSL says why.
    const GBufferWiring c3n = generateWiring(test::shippedLayout("crysis3-thin"), WiringOptions{true});
    EXPECT_EQ(c3n.targetFormats[0], VK_FORMAT_R32_UINT);
    EXPECT_NE(c3n.glsl.find("stays UINT"), std::string::npos);
}

// The renderer binds a placeholder instead of the best-fit table (and never generates it) for a
// wiring whose flag is clear: the flag must hold exactly where the generated GLSL calls the
// encoder that reads the table.
TEST(WiringCodegen, BestFitTableFlagFollowsTheGeneratedGlsl) {
    int flagged = 0, clear = 0;
    for (const Layout& l : test::shippedAttributeLayouts()) {
        const GBufferWiring w = generateWiring(l);
        const bool calls = w.glsl.find("encodeNormalBestFit(") != std::string::npos;
        EXPECT_EQ(w.bestFitTable, calls) << l.name;
        EXPECT_EQ(usesBestFitTable(l), calls) << l.name;
        ++(w.bestFitTable ? flagged : clear);
    }
    EXPECT_GE(flagged, 4);  // crysis2-slim (3 platforms), ryse
    EXPECT_GE(clear, 10);
}

TEST(WiringCodegen, LayoutsGlslCommandPrintsTheWiring) {
    std::ostringstream out, err;
    EXPECT_EQ(runLayoutsCommand({"glsl", "crysis3-thin"}, out, err), 0) << err.str();
    EXPECT_NE(out.str().find("generated from the layout 'crysis3-thin'"), std::string::npos);
    EXPECT_NE(out.str().find("// file: " + (layoutDirectory() / "crysis3-thin.toml").string() + "\n"), std::string::npos);
    EXPECT_NE(out.str().find("void writeGBuffer(Surface s, ivec2 pixel)"), std::string::npos);
    std::ostringstream out2, err2;
    EXPECT_EQ(runLayoutsCommand({"glsl", "no-such-layout"}, out2, err2), 1);
}

TEST(WiringCodegen, CpuRoundTripWithinDocumentedBounds) {
    constexpr int W = 64, H = 48;
    for (const Layout& l : test::shippedAttributeLayouts()) {
        SCOPED_TRACE(l.name);
        std::vector<Surface> in = makeSurfaces(W, H, 7u);
        if (l.selector()) test::assignLayerPatterns(in);  // every model of the rule, on its own pixels
        // As the renderer writes them (material_eval.glsl: Gram-Schmidt against the shading
        // normal), anisotropy directions lie across the normal; HDRP's encoder assumes it too
        // (LitData.hlsl:293 Orthonormalize before Lit.hlsl:583-584).
        for (Surface& s : in) {
            const glm::vec3 across = s.anisotropyDirection - s.normal * glm::dot(s.normal, s.anisotropyDirection);
            if (glm::length(across) > 1e-3f) s.anisotropyDirection = glm::normalize(across);
        }
        std::vector<ShadingModel> model(in.size());
        for (size_t i = 0; i < in.size(); ++i) model[i] = test::statedModel(l, in[i]);
        const CpuGBuffer g = encodeGBuffer(l, in, W, H);
        ASSERT_EQ(g.targetWords.size(), l.targets.size());
        for (size_t t = 0; t < l.targets.size(); ++t)
            EXPECT_EQ(g.targetWords[t].size(), size_t(W * H * wordsPerPixel(l.targets[t])));
        const std::vector<Surface> out = decodeGBuffer(l, g);
        if (const Field* sel = l.selector()) {  // the stored id is the model's, and every model occurs
            uint32_t seen = 0;
            for (size_t i = 0; i < in.size(); ++i) {
                seen |= 1u << unsigned(model[i]);
                uint32_t id = 0;
                for (const Field::ModelId& m : sel->selector) id = m.model == model[i] ? m.id : id;
                if (out[i].shadingModel != float(id)) {
                    ADD_FAILURE() << "pixel " << i << ": stored id " << out[i].shadingModel << ", model's " << id;
                    break;
                }
            }
            EXPECT_EQ(seen, l.selectorModels());
        }
        int checked = 0;
        for (const Target& t : l.targets)
            for (const Field& f : t.fields) {
                const char* m = surfaceMemberName(f.attribute);
                if (!m) continue;
                ++checked;
                const std::string& e = f.encoding;
                const int b = f.bitsOfCode(0);
                size_t held = 0;
                for (size_t i = 0; i < in.size(); ++i) {
                    if (!test::fieldHolds(f, model[i])) continue;  // another model's bits on this pixel
                    ++held;
                    const Surface& a = in[i];
                    const Surface& d = out[i];
                    auto vec = [&](const Surface& s) -> glm::vec3 {
                        switch (f.attribute) {
                            case Attribute::Normal: return s.normal;
                            case Attribute::BaseColor: return s.baseColor;
                            case Attribute::SpecularColor: return s.specularColor;
                            case Attribute::DiffuseColor: return s.diffuseColor;
                            case Attribute::Emissive: return s.emissive;
                            case Attribute::Position: return s.position;
                            case Attribute::Metallic: return glm::vec3(s.metallic);
                            case Attribute::Roughness: return glm::vec3(s.roughness);
                            case Attribute::Specular: return glm::vec3(s.specular);
                            case Attribute::Occlusion: return glm::vec3(s.occlusion);
                            case Attribute::Coat: return glm::vec3(s.coat);
                            case Attribute::CoatRoughness: return glm::vec3(s.coatRoughness);
                            case Attribute::AnisotropyStrength: return glm::vec3(s.anisotropyStrength);
                            case Attribute::AnisotropyDirection: return s.anisotropyDirection;
                            case Attribute::CoatNormal: return s.coatNormal;
                            case Attribute::SheenColor: return s.sheenColor;
                            default: return glm::vec3(0.0f);
                        }
                    };
                    const glm::vec3 x = vec(a), y = vec(d);
                    double err = 0.0, bound = 0.0;
                    const bool direction = f.attribute == Attribute::Normal || f.attribute == Attribute::AnisotropyDirection ||
                                           f.attribute == Attribute::CoatNormal;
                    if (e == "normal_octahedral_delta_ue") {
                        // UE's bottom normal as an 8-bit octahedral delta from the coat's normal
                        // (ClearCoatCommon.ush:5-14): 4/255 of octahedral space a code, 1.9 degrees
                        // at worst within 15 degrees of the coat normal (layer_packings_test); far
                        // from it the delta crosses the octahedron's folds, as in UE: not held.
                        if (angleDeg(a.coatNormal, x) > 15.0) continue;
                        err = angleDeg(x, y);
                        bound = 2.0;
                    } else if (direction && e.rfind("normal_", 0) == 0) {
                        err = angleDeg(x, y);
                        const double s8 = 255.0 / (std::ldexp(1.0, b) - 1.0);
                        const double o8 = 127.0 / (std::ldexp(1.0, b - 1) - 1.0);
                        if (e == "normal_xyz") bound = 0.39 * s8 * 1.1;
                        else if (e == "normal_bestfit") bound = 0.31 * 1.05;
                        else if (e == "normal_xy_zsign") bound = b >= 16 ? 0.35 : b >= 10 ? 2.9 : 5.8 * 1.05;
                        else if (e == "normal_octahedral_unity" || e == "normal_octahedral_dithered")
                            bound = 2.0 * 0.95 * o8 * 1.1;  // truncation / noise: up to a whole step, not half
                        else if (e == "normal_octahedral_hdrp")  // and |z| raised to 1/1024: 0.056 deg
                            bound = 2.0 * 0.95 * o8 * 1.1 + 0.057;
                        else if (e.rfind("normal_octahedral", 0) == 0) bound = 0.95 * o8 * 1.1;
                        else if (e == "normal_spheremap") bound = 11.5 * std::sqrt(s8) * 1.1;
                        else if (e == "normal_xy_float16") {
                            // No sign bit: z comes back >= 0; near z = 0 sqrt amplifies x, y's 2^-11.
                            err = angleDeg(glm::vec3(x.x, x.y, std::abs(x.z)), y);
                            bound = 2.5;
                        }
                        else bound = 180.0;  // stereographic: not a full-sphere mapping
                    } else if (e == "anisotropy_angle_hdrp") {
                        // HDRP's tangent angle in GetLocalFrame(normal): the input direction (across
                        // its normal, above) against the decoded one, as axes (the decode turns a
                        // negated strength into the bitangent). Below one code of strength the sign, and so the
                        // axis, may flip with no effect on the lobe: not held. The bound: the
                        // angle's 8-bit cell (half of it: 0.11 degrees at 45) plus the frame's
                        // turn with the decoded normal (normal_octahedral_hdrp's 12-bit error);
                        // 0.127 degrees at worst on these surfaces (2026-12-08).
                        if (a.anisotropyStrength < 1.0f / 127.5f || glm::length(x) < 0.5f) continue;
                        const double c = std::min(1.0, std::abs(double(glm::dot(glm::normalize(x), glm::normalize(y)))));
                        err = std::acos(c) * 57.29577951308232;
                        bound = 0.2;
                    } else if (e == "snorm" && f.attribute == Attribute::Normal) {
                        // Per component snorm (URP's SNORM normal): a step of 1/(2^(b-1)-1) in n, as
                        // normal_xyz's 2/(2^b-1): normal_xyz's 8-bit bound, scaled.
                        err = angleDeg(x, y);
                        bound = 0.39 * (127.0 / (std::ldexp(1.0, b - 1) - 1.0)) * 1.1;
                    } else if (e == "float32") {
                        err = glm::length(x - y);
                        bound = 0.0;
                    } else if (e == "float16") {
                        for (int c = 0; c < 3; ++c)
                            err = std::max(err, double(std::abs(x[c] - y[c])) / std::max(1e-3, double(std::abs(x[c]))));
                        bound = std::ldexp(1.0, -11) * 1.01;
                    } else if (e == "unorm" || e == "gloss") {
                        // unorm clamps to [0, 1] (killzone2's emissive in an 8-bit target).
                        for (int c = 0; c < 3; ++c)
                            err = std::max(err, double(std::abs(std::clamp(x[c], 0.0f, 1.0f) - y[c])));
                        bound = unormBound(b);
                    } else if (e == "unorm_round_even") {  // ties to even: still half a step
                        err = std::abs(std::clamp(x.x, 0.0f, 1.0f) - y.x);
                        bound = unormBound(b);
                    } else if (e == "coat_roughness_bevy") {  // clamps to [0, 0.5], half a step of 2 (2^b - 1)
                        err = std::abs(std::clamp(x.x, 0.0f, 0.5f) - y.x);
                        bound = 0.5 / (2.0 * (std::ldexp(1.0, b) - 1.0)) + 1e-7;
                    } else if (e == "unorm_sqrt") {  // half a code in sqrt(x), times 2 sqrt(x) <= 2
                        for (int c = 0; c < 3; ++c)
                            err = std::max(err, double(std::abs(std::clamp(x[c], 0.0f, 1.0f) - y[c])));
                        bound = 1.0 / 255.0 + 1e-6;
                    } else if (e == "unorm_signed") {  // a step of 2 / (2^b - 1) in x
                        err = std::abs(x.x - y.x);
                        bound = 2.0 * unormBound(b);
                    } else if (e == "cry_gloss_power") {
                        // Clamps to the engine's range, then half a gloss step (encodings.h).
                        err = std::abs(std::clamp(x.x, 0.17673357f, 0.84089643f) - y.x);
                        bound = 0.0019;
                    } else if (e == "kz2_log_power") {
                        // Clamps to Killzone 2's range (n = 1 .. 2^10.5), then half a code (engine_encodings.h).
                        err = std::abs(std::clamp(x.x, 0.19270985f, 0.90360200f) - y.x);
                        bound = 0.0020;
                    } else if (e == "smoothness_cry") {
                        err = std::abs(x.x - y.x);
                        bound = 2.0 * unormBound(b);
                    } else if (e == "reflectance") {
                        // specular = 2 r^2: half a step of r times d(2 r^2)/dr = 4 r <= 2.83.
                        err = std::abs(x.x - y.x);
                        bound = 2.83 * unormBound(b) * 1.01;
                    } else if (e == "reflectance_bevy_webgl2") {
                        // r is read half a 4-bit step (1/30) low on top of half a code of rounding:
                        // |2 r^2 - 2 r'^2| = 2 |r - r'| (r + r') <= 2 d (2 sqrt(1/2) + d).
                        err = std::abs(x.x - y.x);
                        const double dr = unormBound(b) + 1.0 / 30.0;
                        bound = 2.0 * dr * (1.4143 + dr) * 1.01;
                    } else if (e == "gamma22") {
                        // Half a code of 255 x^(1/2.2) times the slope 2.2 x^1.2 <= 2.2.
                        for (int c = 0; c < 3; ++c) err = std::max(err, double(std::abs(x[c] - y[c])));
                        bound = 2.2 * 0.5 / 255.0 * 1.01;
                    } else if (e == "rgb9e5") {
                        // Half a step of the shared exponent: <= 2^-9 of the largest channel.
                        const double brightest = std::max({double(x.x), double(x.y), double(x.z)});
                        for (int c = 0; c < 3; ++c) err = std::max(err, double(std::abs(x[c] - y[c])));
                        bound = brightest * std::ldexp(1.0, -9) * 1.01 + 1e-30;
                    } else if (e == "float11_11_10" || e == "float11_11_10_hdrp_ao_tag") {
                        // float11 2^-7 relative (r, g), float10 2^-6 (b), plus the subnormal step
                        // (HDRP's AO tag replaces only an exact 0, which reads back 0).
                        for (int c = 0; c < 3; ++c)
                            err = std::max(err, double(std::abs(x[c] - y[c])) -
                                                    std::ldexp(1.0, c < 2 ? -7 : -6) * std::abs(double(x[c])));
                        bound = std::ldexp(1.0, -20);
                    } else if (e == "srgb8") {
                        for (int c = 0; c < 3; ++c) err = std::max(err, double(std::abs(x[c] - y[c])));
                        bound = 0.0045;
                    } else if (e == "srgb8_fast_hdrp") {  // HDRP's cubic decode's misfit, plus half a code
                        for (int c = 0; c < 3; ++c)
                            err = std::max(err, double(std::abs(std::clamp(x[c], 0.0f, 1.0f) - y[c])));
                        bound = 0.0050;
                    } else if (e == "luma") {
                        err = std::abs(enc::lumaBt601(x) - y.x);
                        bound = unormBound(b);
                    } else if (e == "ycbcr" || e == "ycbcr_sqrt" || e == "ycocg") {
                        for (int c = 0; c < 3; ++c) err = std::max(err, double(std::abs(x[c] - y[c])));
                        const double s8 = 255.0 / (std::ldexp(1.0, b) - 1.0);
                        bound = (e == "ycbcr" ? 0.0054 : e == "ycocg" ? 0.0058 : 0.011) * s8 * 1.05;
                    } else if (e == "emissive_albedo_ratio") {
                        // niagara: only the ratio of luminances survives, clamped to 31, within half
                        // a code step in log2(1 + ratio) / 5; the hue is the decoded albedo's.
                        auto L = [](glm::vec3 c) { return 0.3 * c.x + 0.6 * c.y + 0.1 * c.z; };
                        const double want = std::min(L(x) / (L(a.baseColor) + 0.001), 31.0);
                        const double got = L(d.baseColor) > 1e-6 ? L(y) / L(d.baseColor) : want;
                        err = std::abs(std::log2(1.0 + got) - std::log2(1.0 + want)) / 5.0;
                        bound = 0.5 / (std::ldexp(1.0, b) - 1.0) + 1e-6;
                    } else if (e == "ycbcr_checkerboard" || e == "ycocg_checkerboard") {
                        // Smooth input: the quantisation bound plus the neighbours' chroma change.
                        for (int c = 0; c < 3; ++c) err = std::max(err, double(std::abs(x[c] - y[c])));
                        bound = 0.0058 * 255.0 / (std::ldexp(1.0, b) - 1.0) + 0.03;
                    } else {
                        ADD_FAILURE() << "no bound for " << e;
                    }
                    if (err > bound) {
                        ADD_FAILURE() << l.name << " " << attributeName(f.attribute) << " (" << e << ") pixel " << i
                                      << ": error " << err << " > bound " << bound;
                        break;
                    }
                }
                EXPECT_GT(held, in.size() / 16) << attributeName(f.attribute) << ": its models' pixels";
            }
        EXPECT_GT(checked, 0);
        // sheen_roughness = "from_roughness" (UE's cloth lobe): the decoded roughness itself, on every pixel.
        const Fallback* sr = l.findFallback(Attribute::SheenRoughness);
        if (sr && sr->kind == FallbackKind::FromRoughness)
            for (size_t i = 0; i < out.size(); ++i)
                ASSERT_EQ(out[i].sheenRoughness, out[i].roughness) << "pixel " << i;
        // Emissive forward reads back 0, the material pass at full precision.
        const Fallback* em = l.findFallback(Attribute::Emissive);
        if (em && em->kind == FallbackKind::Forward) {
            EXPECT_EQ(out[5].emissive, glm::vec3(0.0f));
        }
        if (em && em->kind == FallbackKind::MaterialPass) {
            EXPECT_EQ(out[5].emissive, in[5].emissive);
        }
    }
}

TEST(WiringCodegen, BitPlacementLowBitsFirst) {
    // compact-octahedral: normal u at "r + b[0:3]" -> low 8 bits in r (bits 0..7), high 4 in b[0:3] (16..19).
    const Layout l = test::shippedLayout("compact-octahedral");
    Surface s;
    s.normal = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
    const CpuGBuffer g = encodeGBuffer(l, {s}, 1, 1);
    const glm::uvec2 c = enc::encodeNormalOctahedral(s.normal, 12);
    const uint32_t w = g.targetWords[1][0];
    EXPECT_EQ(w & 0xffu, c.x & 0xffu);
    EXPECT_EQ((w >> 16) & 0xfu, c.x >> 8);
    EXPECT_EQ((w >> 8) & 0xffu, c.y & 0xffu);
    EXPECT_EQ((w >> 20) & 0xfu, c.y >> 8);
}
