// Run-time GLSL: #include from shaders/ and from in-memory files, and compile errors that show
// the shader's name, the offending lines with numbers, and glslang's log.
#include <gtest/gtest.h>

#include "shader_compiler.h"

namespace gbl {
namespace {

ShaderSource computeShader(const std::string& body) {
    ShaderSource s;
    s.name = "test.comp.glsl";
    s.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    s.text = "#version 450\n#extension GL_GOOGLE_include_directive : require\n"
             "layout(local_size_x = 1) in;\n" + body;
    return s;
}

TEST(ShaderCompiler, CompilesEveryShippedShaderWithTheReferenceWiring) {
    // The pipeline shaders need the generated wiring; a minimal one compiles them standalone.
    const std::string wiring = R"(
#ifdef GBUFFER_WRITE
layout(location = 0) out uvec4 gbufferTarget0;
void writeGBuffer(Surface s, ivec2 pixel) { gbufferTarget0 = floatBitsToUint(vec4(s.normal, s.roughness)); }
#endif
#ifdef GBUFFER_READ
layout(set = 1, binding = 0) uniform usampler2D gbufferTarget0;
Surface readGBuffer(ivec2 pixel) { Surface s; s.normal = vec3(0, 0, 1); return s; }
#endif
)";
    for (const char* file : {"gbuffer_pass.vert.glsl", "gbuffer_pass.frag.glsl", "lighting_pass.comp.glsl"}) {
        ShaderSource s = loadShaderFile(file);
        s.defines.push_back({"TEXTURE_COUNT", "2"});
        s.virtualFiles["gbuffer_wiring.glsl"] = wiring;
        const auto spirv = compileGlsl(s);
        ASSERT_GT(spirv.size(), 5u) << file;
        EXPECT_EQ(spirv[0], 0x07230203u) << file << ": SPIR-V magic";
    }
}

TEST(ShaderCompiler, VirtualIncludesAndDefines) {
    ShaderSource s = computeShader("#include \"generated.glsl\"\nvoid main() { float x = VALUE + helper(); }\n");
    s.virtualFiles["generated.glsl"] = "float helper() { return 1.0; }\n";
    s.defines.push_back({"VALUE", "2.0"});
    EXPECT_NO_THROW(compileGlsl(s));
}

TEST(ShaderCompiler, ErrorNamesShaderAndShowsNumberedLines) {
    ShaderSource s = computeShader("void main() {\n    float x = 1.0;\n    vec3 y = x + undefinedThing;\n}\n");
    try {
        compileGlsl(s);
        FAIL() << "expected a compile error";
    } catch (const ShaderCompileError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("test.comp.glsl"), std::string::npos) << msg;
        EXPECT_NE(msg.find("undefinedThing"), std::string::npos) << msg;
        // Line 6 holds the error (3 header lines, then main): shown with its number and a marker.
        EXPECT_NE(msg.find(" >6 |     vec3 y = x + undefinedThing;"), std::string::npos) << msg;
        EXPECT_NE(msg.find("glslang log:"), std::string::npos) << msg;
    }
}

TEST(ShaderCompiler, ErrorInsideAnIncludedFileShowsThatFile) {
    ShaderSource s = computeShader("#include \"broken.glsl\"\nvoid main() {}\n");
    s.virtualFiles["broken.glsl"] = "float ok() { return 1.0; }\nfloat bad() { return nope; }\n";
    try {
        compileGlsl(s);
        FAIL() << "expected a compile error";
    } catch (const ShaderCompileError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("broken.glsl"), std::string::npos) << msg;
        EXPECT_NE(msg.find(" >2 | float bad() { return nope; }"), std::string::npos) << msg;
    }
}

TEST(ShaderCompiler, MissingIncludeIsReported) {
    ShaderSource s = computeShader("#include \"no_such_file.glsl\"\nvoid main() {}\n");
    try {
        compileGlsl(s);
        FAIL() << "expected a compile error";
    } catch (const ShaderCompileError& e) {
        EXPECT_NE(std::string(e.what()).find("no_such_file.glsl"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace gbl
