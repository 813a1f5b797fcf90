// The 8-bit tables as `layouts export` writes them (select trees, export_tables.h), read back from
// the emitted GLSL text by a small evaluator written here, against the C++ twin tables and
// encoders (src/encoding): every decode entry, and every encode at each threshold and the float
// just below it (the encoders are monotonic step functions, so those points decide them).
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "encodings.h"
#include "export_glsl_library.h"
#include "export_tables.h"
#include "shader_compiler.h"

namespace gbl {
namespace {

// A select tree as emitted: "((q & Nu) != 0u\n ? A\n : B)" or "uvec4(0x...u, ...)".
struct Node {
    uint32_t bit = 0;
    std::unique_ptr<Node> yes, no;
    uint32_t words[4] = {0, 0, 0, 0};
    const uint32_t* leaf(uint32_t q) const { return yes ? ((q & bit) ? yes->leaf(q) : no->leaf(q)) : words; }
};

struct Parser {
    const std::string& s;
    size_t p;
    void space() {
        while (p < s.size() && std::isspace(static_cast<unsigned char>(s[p]))) ++p;
    }
    void expect(const std::string& t) {
        space();
        if (s.compare(p, t.size(), t) != 0) throw std::runtime_error("expected '" + t + "' at " + s.substr(p, 40));
        p += t.size();
    }
    uint32_t number() {
        space();
        size_t used = 0;
        const unsigned long v = std::stoul(s.substr(p, 12), &used, 0);
        p += used;
        if (p < s.size() && s[p] == 'u') ++p;
        return uint32_t(v);
    }
    std::unique_ptr<Node> tree() {
        auto n = std::make_unique<Node>();
        space();
        if (s.compare(p, 6, "uvec4(") == 0) {
            p += 6;
            for (int k = 0; k < 4; ++k) {
                if (k) expect(",");
                n->words[k] = number();
            }
            expect(")");
            return n;
        }
        expect("((q &");
        n->bit = number();
        expect(") != 0u");
        expect("?");
        n->yes = tree();
        expect(":");
        n->no = tree();
        expect(")");
        return n;
    }
};

std::map<std::string, const exporting::GlslDeclaration*> byName(const exporting::GlslLibrary& lib) {
    std::map<std::string, const exporting::GlslDeclaration*> m;
    for (const exporting::GlslDeclaration& d : lib.declarations()) m[d.name] = &d;
    return m;
}

float asFloat(uint32_t w) {
    float f;
    std::memcpy(&f, &w, 4);
    return f;
}

// Entry i of `float NAME(uint i)`: the tree after "uvec4 v = ", then component i & 3.
float directEntry(const std::string& code, uint32_t i) {
    const size_t at = code.find("uvec4 v = ");
    Parser parser{code, at + 10};
    return asFloat(parser.tree()->leaf(i >> 2)[i & 3]);
}

// `float NAME(uint step, uint j)`: one tree per step.
std::vector<std::unique_ptr<Node>> stepTrees(const std::string& code) {
    std::vector<std::unique_ptr<Node>> trees;
    for (uint32_t step = 0; step < 8; ++step) {
        const std::string head = "(step == " + std::to_string(step) + "u) v = ";
        const size_t at = code.find(head);
        if (at == std::string::npos) throw std::runtime_error("no step " + std::to_string(step));
        Parser parser{code, at + head.size()};
        trees.push_back(parser.tree());
    }
    return trees;
}

// The unrolled search as the emitted encoder runs it: lo += 2^(7 - step) when the condition holds
// for entry (step, lo >> (8 - step)).
uint32_t unrolledSearch(const std::vector<std::unique_ptr<Node>>& trees, const std::function<bool(float)>& holds) {
    uint32_t lo = 0;
    for (uint32_t step = 0; step < 8; ++step) {
        const uint32_t j = lo >> (8 - step);
        if (holds(asFloat(trees[step]->leaf(j >> 2)[j & 3]))) lo += 128u >> step;
    }
    return lo;
}

TEST(ExportTables, DecodeTablesHoldTheCppTwinsEntries) {
    const exporting::GlslLibrary lib([](const std::string& n) { return resolveShaderInclude(n, {}); });
    const auto d = byName(lib);
    const std::map<std::string, const float*> twins = {
        {"kSrgbDecode", enc::kSrgbDecode}, {"kGamma22Decode", enc::kGamma22Decode}, {"kCryGlossRoughness", enc::kCryGlossRoughness},
        {"kKz2PowerRoughness", enc::kKz2PowerRoughness}};
    for (const auto& [name, twin] : twins) {
        ASSERT_TRUE(d.count(name)) << name;
        const std::string& code = d.at(name)->code;
        EXPECT_FALSE(d.at(name)->isConstant) << name << " is still an array";
        EXPECT_EQ(code.find("float["), std::string::npos) << name << ": no array left\n" << code;
        EXPECT_EQ(code.find("const "), std::string::npos) << name << ": no array left\n" << code;
        for (uint32_t i = 0; i < 256; ++i) {
            const float got = directEntry(code, i);
            ASSERT_EQ(std::memcmp(&got, &twin[i], 4), 0) << name << "[" << i << "]: " << got << " vs " << twin[i];
        }
    }
}

// `--tables arrays`: the declarations as the shader files have them (the renderer's own code,
// which gpu_cpu_bits_test holds to the CPU mirror on the device): every entry of every table the
// C++ twin's, bit for bit, and the searches still loops over them.
TEST(ExportTables, ArrayTablesAreTheCppTwins) {
    const exporting::GlslLibrary lib([](const std::string& n) { return resolveShaderInclude(n, {}); });
    std::map<std::string, const exporting::GlslDeclaration*> d;
    for (const exporting::GlslDeclaration& x : lib.declarations(exporting::ExportTables::Arrays)) d[x.name] = &x;
    const std::map<std::string, std::pair<const float*, size_t>> twins = {
        {"kSrgbDecode", {enc::kSrgbDecode, 256}},
        {"kGamma22Decode", {enc::kGamma22Decode, 256}},
        {"kCryGlossRoughness", {enc::kCryGlossRoughness, 256}},
        {"kSrgbEncodeThresholds", {enc::kSrgbEncodeThresholds, 255}},
        {"kGamma22EncodeThresholds", {enc::kGamma22EncodeThresholds, 255}},
        {"kSrgbFastHdrpEncodeThresholds", {enc::kSrgbFastHdrpEncodeThresholds, 255}},
        {"kCryGlossEncodeThresholds", {enc::kCryGlossEncodeThresholds, 255}},
        {"kKz2PowerRoughness", {enc::kKz2PowerRoughness, 256}},
        {"kKz2PowerEncodeThresholds", {enc::kKz2PowerEncodeThresholds, 255}}};
    for (const auto& [name, twin] : twins) {
        SCOPED_TRACE(name);
        ASSERT_TRUE(d.count(name));
        EXPECT_TRUE(d.at(name)->isConstant);
        const std::optional<exporting::ConstFloatTable> t = exporting::parseConstFloatTable(d.at(name)->code);
        ASSERT_TRUE(t.has_value()) << d.at(name)->code;
        ASSERT_EQ(t->values.size(), twin.second);
        for (size_t i = 0; i < twin.second; ++i)
            ASSERT_EQ(std::memcmp(&t->values[i], &twin.first[i], 4), 0) << name << "[" << i << "]";
    }
    for (const char* encoder : {"encodeSrgb8", "encodeGamma22", "encodeSrgb8FastHdrp", "encodeCryGlossPower", "encodeKz2LogPower"}) {
        ASSERT_TRUE(d.count(encoder)) << encoder;
        EXPECT_NE(d.at(encoder)->code.find("for ("), std::string::npos) << d.at(encoder)->code;
    }
}

TEST(ExportTables, UnrolledSearchesEncodeAsTheCppEncoders) {
    const exporting::GlslLibrary lib([](const std::string& n) { return resolveShaderInclude(n, {}); });
    const auto d = byName(lib);
    struct Case {
        const char* table;
        const char* encoder;
        const float* thresholds;
        bool descending;  // CryEngine's gloss, Killzone 2's power: count of thresholds >= r
        std::function<uint32_t(float)> cpu;
    };
    const Case cases[] = {
        {"kSrgbEncodeThresholds", "encodeSrgb8", enc::kSrgbEncodeThresholds, false, [](float x) { return enc::encodeSrgb8(x); }},
        {"kGamma22EncodeThresholds", "encodeGamma22", enc::kGamma22EncodeThresholds, false, [](float x) { return enc::encodeGamma22(x); }},
        {"kSrgbFastHdrpEncodeThresholds", "encodeSrgb8FastHdrp", enc::kSrgbFastHdrpEncodeThresholds, false,
         [](float x) { return enc::encodeSrgb8FastHdrp(x); }},
        {"kCryGlossEncodeThresholds", "encodeCryGlossPower", enc::kCryGlossEncodeThresholds, true,
         [](float x) { return enc::encodeCryGlossPower(x); }},
        {"kKz2PowerEncodeThresholds", "encodeKz2LogPower", enc::kKz2PowerEncodeThresholds, true,
         [](float x) { return enc::encodeKz2LogPower(x); }},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.table);
        ASSERT_TRUE(d.count(c.table) && d.count(c.encoder));
        const std::string& enc = d.at(c.encoder)->code;
        EXPECT_EQ(enc.find("for ("), std::string::npos) << enc;  // the loop is unrolled
        const std::string cmp = c.descending ? ">=" : "<=";
        EXPECT_NE(enc.find(std::string(c.table) + "(7u, lo >> 1u) " + cmp), std::string::npos) << enc;
        const auto trees = stepTrees(d.at(c.table)->code);
        std::vector<float> probes = {0.0f, -0.0f, -1.0f, 2.0f, 1e30f, -1e30f, std::nanf("")};
        for (int i = 0; i < 255; ++i) {
            probes.push_back(c.thresholds[i]);
            probes.push_back(std::nextafter(c.thresholds[i], -1e30f));
            probes.push_back(std::nextafter(c.thresholds[i], 1e30f));
        }
        size_t bad = 0;
        for (float x : probes) {
            // encodeSrgb8FastHdrp compares |x|, as its GLSL does before the search.
            const float a = std::string(c.encoder) == "encodeSrgb8FastHdrp" ? std::abs(x) : x;
            const uint32_t got = unrolledSearch(trees, [&](float t) { return c.descending ? t >= a : t <= a; });
            if (got != c.cpu(x) && bad++ < 5) ADD_FAILURE() << c.encoder << "(" << x << "): " << got << " vs " << c.cpu(x);
        }
        EXPECT_EQ(bad, 0u);
    }
}

}  // namespace
}  // namespace gbl
