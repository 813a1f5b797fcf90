// The storage buffer of the encodings' 8-bit tables (src/encoding/codec_tables.h) holds, at the
// offsets shaders/codec_tables.glsl reads it at, the very floats of the shaders' own constant
// arrays: so a pass that reads the buffer (the renderer's, to spare llvmpipe's JIT) decodes and
// encodes exactly as one compiled with the constant arrays (gpu_cpu_bits_test's). Checked against
// the shader text itself, each literal parsed as glslang parses it (strtod, then rounded to float).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "codec_tables.h"
#include "shader_compiler.h"

namespace gbl {
namespace {

// The literals of `const float name[N] = float[N](...);` in `text`, as floats.
std::vector<float> glslArray(const std::string& text, const std::string& name) {
    const std::regex decl("const float " + name + R"(\[(\d+)\] = float\[\d+\]\(([^;]*)\);)");
    std::smatch m;
    if (!std::regex_search(text, m, decl)) return {};
    std::vector<float> values;
    const std::string body = m[2].str();
    const char* p = body.c_str();
    while (*p) {
        char* end = nullptr;
        const double v = std::strtod(p, &end);
        if (end == p) {
            ++p;  // a comma, a space or a newline
            continue;
        }
        values.push_back(float(v));
        p = end;
    }
    EXPECT_EQ(values.size(), size_t(std::stoul(m[1].str()))) << name;
    return values;
}

uint32_t bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

TEST(CodecTables, OffsetsMatchTheShader) {
    const std::string text = loadShaderFile("codec_tables.glsl").text;
    const std::map<std::string, uint32_t> expected = {
        {"SRGB_DECODE", enc::kCodecTableSrgbDecode},          {"SRGB_ENCODE", enc::kCodecTableSrgbEncode},
        {"CRY_GLOSS_DECODE", enc::kCodecTableCryGlossDecode}, {"CRY_GLOSS_ENCODE", enc::kCodecTableCryGlossEncode},
        {"GAMMA22_DECODE", enc::kCodecTableGamma22Decode},    {"GAMMA22_ENCODE", enc::kCodecTableGamma22Encode},
        {"SRGB_FAST_HDRP_ENCODE", enc::kCodecTableSrgbFastHdrpEncode},
        {"KZ2_POWER_DECODE", enc::kCodecTableKz2PowerDecode}, {"KZ2_POWER_ENCODE", enc::kCodecTableKz2PowerEncode},
    };
    for (const auto& [name, offset] : expected) {
        std::smatch m;
        ASSERT_TRUE(std::regex_search(text, m, std::regex("#define GBL_CODEC_TABLE_" + name + R"( (\d+)u)"))) << name;
        EXPECT_EQ(std::stoul(m[1].str()), offset) << name;
    }
    EXPECT_EQ(enc::codecTableFloats().size(), size_t(enc::kCodecTableFloats));
}

TEST(CodecTables, BufferHoldsTheShadersConstantArrays) {
    struct Table {
        const char* file;
        const char* array;
        uint32_t offset;
        size_t size;
    };
    const Table tables[] = {
        {"scalar_encodings.glsl", "kSrgbDecode", enc::kCodecTableSrgbDecode, 256},
        {"scalar_encodings.glsl", "kSrgbEncodeThresholds", enc::kCodecTableSrgbEncode, 255},
        {"color_encodings.glsl", "kCryGlossRoughness", enc::kCodecTableCryGlossDecode, 256},
        {"color_encodings.glsl", "kCryGlossEncodeThresholds", enc::kCodecTableCryGlossEncode, 255},
        {"engine_encodings.glsl", "kGamma22Decode", enc::kCodecTableGamma22Decode, 256},
        {"engine_encodings.glsl", "kGamma22EncodeThresholds", enc::kCodecTableGamma22Encode, 255},
        {"engine_encodings.glsl", "kSrgbFastHdrpEncodeThresholds", enc::kCodecTableSrgbFastHdrpEncode, 255},
        {"engine_encodings.glsl", "kKz2PowerRoughness", enc::kCodecTableKz2PowerDecode, 256},
        {"engine_encodings.glsl", "kKz2PowerEncodeThresholds", enc::kCodecTableKz2PowerEncode, 255},
    };
    const std::vector<float>& buffer = enc::codecTableFloats();
    for (const Table& t : tables) {
        SCOPED_TRACE(t.array);
        const std::vector<float> glsl = glslArray(loadShaderFile(t.file).text, t.array);
        ASSERT_EQ(glsl.size(), t.size);
        int differ = 0;
        for (size_t i = 0; i < t.size; ++i)
            if (bits(glsl[i]) != bits(buffer[t.offset + i]) && differ++ < 5)
                ADD_FAILURE() << "entry " << i << ": shader " << glsl[i] << ", buffer " << buffer[t.offset + i];
        // Sorted (the encoders binary-search them; decodes increase with the code, the gloss
        // roughness decreases with it): a shuffled copy would fail here too.
        for (size_t i = 1; i < t.size; ++i)
            EXPECT_NE(glsl[i], glsl[i - 1]) << "entry " << i << " repeats";
        if (t.size == 255) {
            EXPECT_EQ(buffer[t.offset + 255], 0.0f) << "padding";
        }
    }
}

}  // namespace
}  // namespace gbl
