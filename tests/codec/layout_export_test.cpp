// `gbufferlab layouts export` without a GPU: every shipped layout's HLSL and GLSL compile (glslang,
// its GLSL and HLSL front ends), only the helpers a layout needs are in it, names from the layout
// text are escaped, and the UNORM / SNORM scale leaves the hardware's conversion no room.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "export_glsl_library.h"
#include "layout_catalog.h"
#include "layout_export.h"
#include "layout_text.h"
#include "shader_compiler.h"
#include "layout_files.h"

namespace gbl {
namespace {

std::string exportOf(const Layout& layout, ExportLanguage lang, bool kernel,
                     exporting::ExportTables tables = exporting::ExportTables::Selects) {
    ExportOptions o;
    o.language = lang;
    o.kernel = kernel;
    o.tables = tables;
    return exportLayout(layout, o, [](const std::string& n) { return resolveShaderInclude(n, {}); });
}

// The kernel's GLSL starts with its #version; HLSL has none.
void compile(const std::string& text, ExportLanguage lang, const std::string& name) {
    ShaderSource s{name, text, VK_SHADER_STAGE_COMPUTE_BIT, {}, {}};
    if (lang == ExportLanguage::Glsl) compileGlslUncached(s);
    else compileHlslUncached(s, "main");
}

// Vulkan's float -> UNORM conversion returns "one of the two closest integers" to f * (2^b - 1),
// round to nearest recommended. For every code of every width the exported value f = code * k
// must put that product in [code, code + 0.25) whether the shader's multiply rounds to nearest or
// towards zero, so that round-to-nearest and truncation both give the code back; the product is
// taken exactly (double holds a float times a 16-bit integer) and in float.
TEST(LayoutExport, NormScaleLeavesTheConversionNoRoom) {
    size_t checked = 0;
    for (int isSigned = 0; isSigned < 2; ++isSigned)
        for (int bits = isSigned ? 2 : 1; bits <= 16; ++bits) {
            const float k = exportNormScale(bits, isSigned != 0);
            const double m = isSigned ? std::ldexp(1.0, bits - 1) - 1.0 : std::ldexp(1.0, bits) - 1.0;
            for (int c = isSigned ? -int(m) : 0; c <= int(m); ++c) {
                const double exact = double(c) * double(k);
                const float nearest = float(c) * k;
                float towardZero = nearest;
                if (std::abs(double(towardZero)) > std::abs(exact)) towardZero = std::nextafter(towardZero, 0.0f);
                for (float f : {nearest, towardZero}) {
                    const double clamped = std::clamp(double(f), isSigned ? -1.0 : 0.0, 1.0);
                    const double r = clamped * m;  // exact
                    const double mag = std::abs(r), cm = std::abs(double(c));
                    ASSERT_GE(mag, cm) << bits << " bits, code " << c;
                    ASSERT_LT(mag, cm + 0.25) << bits << " bits, code " << c;
                    const float rf = float(clamped) * float(m);  // the product in float
                    ASSERT_EQ(std::nearbyint(double(rf)), double(c));
                    ASSERT_EQ(std::trunc(double(rf)), double(c));
                    ++checked;
                }
            }
        }
    std::printf("[ unorm    ] %zu (code, rounding) pairs of 1..16-bit UNORM and 2..16-bit SNORM convert back exactly\n",
                checked);
}

TEST(LayoutExport, HlslTranslationOfConstructorsAndArrays) {
    using exporting::translateGlslToHlsl;
    EXPECT_EQ(translateGlslToHlsl("vec3 a = vec3(0.5);"), "float3 a = ((float3)(0.5));");
    EXPECT_EQ(translateGlslToHlsl("uvec2 b = uvec2(f(x, y), 1u);"), "uint2 b = uint2(f(x, y), 1u);");
    EXPECT_EQ(translateGlslToHlsl("const float k[2] = float[2](1.0, 2.0);"), "const float k[2] = {1.0, 2.0};");
    EXPECT_EQ(translateGlslToHlsl("uint u = floatBitsToUint(fract(x)); // vec3(y)"),
              "uint u = asuint(frac(x)); // vec3(y)");
    EXPECT_EQ(translateGlslToHlsl("vec4 w = vec4(1.0) - step(vec4(k), abs(v));"),
              "float4 w = ((float4)(1.0)) - step(((float4)(k)), abs(v));");
}

// Every shipped layout, both languages, with the compute kernel (which calls encode and decode):
// glslang compiles them. The HLSL also through glslangValidator itself, as docs/export.md says.
TEST(LayoutExport, EveryShippedLayoutCompilesInBothLanguages) {
    size_t n = 0;
    for (const Layout& layout : test::shippedLayouts()) {
        const std::string& name = layout.name;
        SCOPED_TRACE(name);
        for (ExportLanguage lang : {ExportLanguage::Glsl, ExportLanguage::Hlsl})
            for (exporting::ExportTables tables : {exporting::ExportTables::Selects, exporting::ExportTables::Arrays}) {
                const std::string text = exportOf(layout, lang, true, tables);
                EXPECT_EQ(text.find("#include"), std::string::npos);
                EXPECT_NO_THROW(compile(text, lang, name + (lang == ExportLanguage::Hlsl ? ".hlsl" : ".glsl")));
                ++n;
            }
    }
    EXPECT_GE(n, 100u);
    // The arrays as arrays: ue4's sRGB decode table and its search loop, in both languages.
    const std::string glsl = exportOf(loadLayout("ue4"), ExportLanguage::Glsl, false, exporting::ExportTables::Arrays);
    EXPECT_NE(glsl.find("const float gbl_kSrgbDecode[256] = float[256]("), std::string::npos);
    EXPECT_EQ(glsl.find("uvec4 v = "), std::string::npos);  // no select tree
    const std::string hlsl = exportOf(loadLayout("ue4"), ExportLanguage::Hlsl, false, exporting::ExportTables::Arrays);
    EXPECT_NE(hlsl.find("static const float gbl_kSrgbDecode[256] = {"), std::string::npos);
    const Layout ue5 = loadLayout("ue5");
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "gbl_export_ue5_test.hlsl";
    std::ofstream(file) << exportOf(ue5, ExportLanguage::Hlsl, true);
    const std::string cmd = "glslangValidator -D -e main -S comp -V -o /dev/null " + file.string() + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    std::filesystem::remove(file);
}

// Only what the layout reaches: ue4 has no CryEngine gloss table nor best-fit normals, crysis2-slim
// has both best-fit normals and its table's buffer; every helper carries the gbl_ prefix.
TEST(LayoutExport, OnlyTheHelpersTheLayoutNeeds) {
    const std::string ue4 = exportOf(loadLayout("ue4"), ExportLanguage::Glsl, false);
    EXPECT_EQ(ue4.find("CryGloss"), std::string::npos);
    EXPECT_EQ(ue4.find("BestFit"), std::string::npos);
    EXPECT_NE(ue4.find("uint gbl_encodeSrgb8(float x)"), std::string::npos);
    EXPECT_EQ(ue4.find(" quantizeUnorm("), std::string::npos);  // renamed everywhere
    const std::string crysis = exportOf(loadLayout("crysis2-slim"), ExportLanguage::Hlsl, false);
    EXPECT_NE(crysis.find("gbl_encodeNormalBestFit"), std::string::npos);
    EXPECT_NE(crysis.find("StructuredBuffer<uint> gbl_bestFitNormalTable"), std::string::npos);
    EXPECT_EQ(crysis.find("gbl_kSrgbDecode"), std::string::npos);
}

// Layout text that would break out of a comment or name nothing valid: a title and target names
// with "*/", a trailing backslash (continues a // comment), quotes, "#" and non-ASCII. None of it
// may appear outside a // comment, identifiers stay valid, and both languages compile.
TEST(LayoutExport, LayoutTextIsEscapedAndNamesArePrefixed) {
    const std::string text =
        test::LayoutText("x--y__z", R"(*/ #error boom \\ \"q\" caf\u00e9)", R"({ engine = "E */", talk = "T \\", year = 2020 })")
            .target(R"(*/ #define x 1 \\)", "R8G8B8A8_UNORM",
                    {R"(attribute = "normal", encoding = "normal_octahedral", at = ["r", "g"])",
                     R"(attribute = "roughness", encoding = "unorm", at = "b")",
                     R"(attribute = "shading_model_id", at = "a", value = 7)"})
            .target("9 lives", "R8G8B8A8_SRGB", {R"(attribute = "base_color", encoding = "srgb8", at = ["r", "g", "b"])"})
            .clear("base_color = 0.0");
    const Layout layout = parseLayout(text, "x--y__z.toml");
    EXPECT_EQ(exportPrefix(layout), "gbl_x_y_z");
    for (ExportLanguage lang : {ExportLanguage::Glsl, ExportLanguage::Hlsl}) {
        const std::string out = exportOf(layout, lang, true);
        std::istringstream in(out);
        std::string line;
        while (std::getline(in, line)) {
            const size_t comment = line.find("//");
            const std::string code = line.substr(0, comment);
            EXPECT_EQ(code.find("*/"), std::string::npos) << line;
            EXPECT_EQ(code.find("boom"), std::string::npos) << line;
            if (comment != std::string::npos) {
                EXPECT_NE(line.back(), '\\') << line;
                for (char c : line) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << line;
            }
        }
        EXPECT_NE(out.find("rt0_define_x_1"), std::string::npos);
        EXPECT_NE(out.find("uint shadingModelId;"), std::string::npos);
        EXPECT_NO_THROW(compile(out, lang, "hostile"));
    }
}

}  // namespace
}  // namespace gbl
