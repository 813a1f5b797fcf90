// "Whatever `layouts check` accepts also compiles": every shipped layout is mutated line by line
// (each number replaced by hostile values, each string by hostile text) and every mutant that
// checkLayout accepts must generate GLSL that glslang compiles, on the write and the read side.
// Also: what check refuses, it refuses with file:line:col, and messages stay one line.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <regex>
#include <map>
#include <set>
#include <sstream>

#include "layout.h"
#include "layout_catalog.h"
#include "layout_export.h"
#include "renderer_passes.h"
#include "shader_compiler.h"
#include "wiring_codegen.h"

using namespace gbl;

namespace {

std::string readAll(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Whether a message is safe to print as one line: printable ASCII, or well-formed UTF-8 of code
// points that neither break the line nor hide or reorder text (no C0/C1 controls, no U+2028/2029,
// no zero-width or bidirectional marks, no BOM). Names print as UTF-8 (base/error.h).
bool printableOnOneLine(const std::string& line) {
    for (size_t i = 0; i < line.size();) {
        const auto c = static_cast<unsigned char>(line[i]);
        if (c < 0x80) {
            if (c < 0x20 || c == 0x7f) return false;
            ++i;
            continue;
        }
        const size_t n = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 ? 2 : 0;
        if (n == 0 || i + n > line.size()) return false;
        uint32_t cp = c & (n == 2 ? 0x1F : n == 3 ? 0x0F : 0x07);
        for (size_t k = 1; k < n; ++k) {
            const auto b = static_cast<unsigned char>(line[i + k]);
            if ((b & 0xC0) != 0x80) return false;
            cp = cp << 6 | (b & 0x3F);
        }
        if (cp <= 0x9F || cp == 0xAD || (cp >= 0x200B && cp <= 0x200F) || (cp >= 0x2028 && cp <= 0x202E) ||
            (cp >= 0x2060 && cp <= 0x206F) || cp == 0xFEFF || (cp >= 0xD800 && cp <= 0xDFFF) || cp > 0x10FFFF)
            return false;
        i += n;
    }
    return true;
}

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::stringstream ss(text);
    for (std::string l; std::getline(ss, l);) lines.push_back(l);
    return lines;
}

std::string joinLines(const std::vector<std::string>& lines) {
    std::string s;
    for (const std::string& l : lines) s += l + "\n";
    return s;
}

// Hostile numbers: non-finite, beyond float range, negative, huge integers, denormals, fractions.
const char* kNumbers[] = {"nan", "inf", "-inf", "1e39", "-1e39", "3.4e38", "1e300", "4294967297",
                          "9223372036854775807", "-1", "1e-45", "2.5", "0.999999", "1"};
// Hostile text (TOML basic-string escapes): newlines with directives, backslashes, quotes, bytes.
const char* kStrings[] = {"x\\n#error injected", "a\\\\", "\\\\", "*/ #error x", "caf\\u00e9", "q\\\"q",
                          "tab\\there", "\\u0000", "rtl\\u202egnp", "line\\u2028break"};

// The mutants of one layout text: each number token on a line replaced by each hostile number,
// the first string on a line replaced by each hostile string.
struct Mutant {
    std::string text;
    int hostileString = -1;  // index in kStrings, or -1 for a number mutant
};

std::vector<Mutant> mutants(const std::string& text) {
    const std::vector<std::string> lines = splitLines(text);
    const std::regex number(R"((=\s*|\[\s*|,\s*)(-?[0-9][0-9.eE+-]*))");
    const std::regex string(R"("([^"\\]|\\.)*")");
    std::vector<Mutant> out;
    for (size_t i = 0; i < lines.size(); ++i) {
        if (lines[i].empty() || lines[i][0] == '#') continue;
        std::smatch m;
        if (std::regex_search(lines[i], m, number)) {
            for (const char* n : kNumbers) {
                std::vector<std::string> copy = lines;
                copy[i] = m.prefix().str() + m[1].str() + n + m.suffix().str();
                out.push_back({joinLines(copy), -1});
            }
        }
        if (std::regex_search(lines[i], m, string)) {
            for (int k = 0; k < int(std::size(kStrings)); ++k) {
                std::vector<std::string> copy = lines;
                copy[i] = m.prefix().str() + "\"" + kStrings[k] + "\"" + m.suffix().str();
                out.push_back({joinLines(copy), k});
            }
        }
    }
    return out;
}

// The wiring without its comments' text: two wirings that differ only inside comments compile
// alike unless a comment was broken out of, and then the escaped text is code, so it shows here.
std::string withoutCommentText(const std::string& glsl) {
    std::string out;
    out.reserve(glsl.size());
    for (size_t i = 0; i < glsl.size();) {
        if (glsl.compare(i, 2, "//") == 0) {
            i = glsl.find('\n', i);
            if (i == std::string::npos) break;
        } else if (glsl.compare(i, 2, "/*") == 0) {
            const size_t end = glsl.find("*/", i + 2);
            out += "/**/";
            if (end == std::string::npos) break;
            i = end + 2;
        } else {
            out += glsl[i++];
        }
    }
    return out;
}

void compiles(const std::string& shader, const GBufferWiring& w, const std::string& mutant) {
    ShaderSource s = loadShaderFile(shader);
    if (w.visibilityBuffer && shader == "decode_pass.comp.glsl") {
        // What the renderer compiles a visibility buffer's resolve with on lavapipe: 4 textures,
        // each a candidate in every material slot.
        TargetReadScene scene;
        scene.visibility = true;
        scene.textureCount = 4;
        for (std::vector<uint32_t>& slot : scene.texturesBySlot) slot = {0, 1, 2, 3};
        addTargetReadDefines(s, scene);
    } else {
        s.defines.push_back({"TEXTURE_COUNT", "4"});
    }
    s.virtualFiles["gbuffer_wiring.glsl"] = w.glsl;
    s.name = shader + " (mutant of layout " + w.layoutName + ")";
    EXPECT_NO_THROW(compileGlsl(s)) << "layout text accepted by check:\n" << mutant;
}

// `layouts export` of the mutant, in both languages with the kernel (which calls encode and
// decode), compiled by glslang's GLSL and HLSL front ends.
void exportCompiles(const Layout& layout, ExportLanguage lang, const std::string& text, const std::string& mutant) {
    ShaderSource s{"export of mutant of " + layout.name, text, VK_SHADER_STAGE_COMPUTE_BIT, {}, {}};
    if (lang == ExportLanguage::Glsl) EXPECT_NO_THROW(compileGlslUncached(s)) << "layout text accepted by check:\n" << mutant;
    else EXPECT_NO_THROW(compileHlslUncached(s, "main")) << "layout text accepted by check:\n" << mutant;
}

std::string exportText(const Layout& layout, ExportLanguage lang) {
    ExportOptions o;
    o.language = lang;
    o.kernel = true;
    static const exporting::GlslLibrary library([](const std::string& n) { return resolveShaderInclude(n, {}); });
    return exportLayout(layout, o, library);
}

}  // namespace

TEST(LayoutMutants, WhatCheckAcceptsCompiles) {
    const std::filesystem::path dir = GBL_SOURCE_LAYOUT_DIR;
    const std::vector<std::string> names = listLayoutNames(dir);
    ASSERT_GE(names.size(), 7u);
    size_t total = 0, accepted = 0, compiled = 0;
    // A wiring is compiled once per distinct code (comments' text left out, see
    // withoutCommentText) and, for hostile strings, once per hostile string: every hostile text
    // still reaches glslang inside the comments of every shipped layout's code, but the same code
    // is not compiled again for each of its comment variants (17 layouts: 1030 compiles -> far fewer).
    std::set<std::string> seenGlsl, seenExports;
    std::map<std::string, int> perLayout;
    size_t exported = 0;
    const std::regex place(R"(^mutant\.toml:[0-9]+:[0-9]+: )");
    // ... and the tests' selector layout (tests/layout/data/shading-models.toml): its ids, bits and
    // models mutated too, every accepted mutant's gblModel / gblSel wiring compiled.
    std::vector<std::filesystem::path> files;
    for (const std::string& name : names) files.push_back(dir / (name + ".toml"));
    files.push_back(dir.parent_path() / "tests" / "layout" / "data" / "shading-models.toml");
    for (const std::filesystem::path& file : files) {
        const std::string name = file.stem().string();
        for (const Mutant& mutant : mutants(readAll(file))) {
            const std::string& text = mutant.text;
            ++total;
            const std::vector<LayoutDiagnostic> problems = checkLayout(text, "mutant.toml");
            for (const LayoutDiagnostic& d : problems) {
                const std::string line = d.text();
                EXPECT_EQ(line.find('\n'), std::string::npos) << line;
                EXPECT_TRUE(std::regex_search(line, place)) << line;
                ASSERT_TRUE(printableOnOneLine(line)) << line;
            }
            if (!problems.empty()) continue;
            ++accepted;
            const Layout layout = parseLayout(text, "mutant.toml");
            for (bool native : {false, true}) {
                const GBufferWiring w = generateWiring(layout, WiringOptions{native});
                const std::string key = withoutCommentText(w.glsl) + "\n#" + std::to_string(mutant.hostileString);
                if (!seenGlsl.insert(key).second) continue;
                ++compiled;
                compiles("gbuffer_pass.frag.glsl", w, text);
                compiles("decode_pass.comp.glsl", w, text);
            }
            // Exports: every accepted mutant is exported (text checks); each distinct code is
            // compiled once (hostile text lives only in comments, which the check below the loop
            // and LayoutExport.LayoutTextIsEscapedAndNamesArePrefixed hold to that), at most 2
            // distinct ones per layout and language (glslang takes 0.1-0.2 s per export: all
            // distinct ones took this test past 230 s).
            for (ExportLanguage lang : {ExportLanguage::Glsl, ExportLanguage::Hlsl}) {
                const std::string e = exportText(layout, lang);
                for (const std::string& l : splitLines(e))
                    if (l.rfind("//", 0) != 0 && l.find("//") == std::string::npos)
                        ASSERT_TRUE(printableOnOneLine(l)) << l;
                const std::string key = withoutCommentText(e);
                if (seenExports.count(key) || perLayout[name + (lang == ExportLanguage::Hlsl ? "h" : "g")] >= 2) continue;
                seenExports.insert(key);
                ++perLayout[name + (lang == ExportLanguage::Hlsl ? "h" : "g")];
                ++exported;
                exportCompiles(layout, lang, e, text);
            }
        }
    }
    // The mutants must exercise both sides: many refused, some accepted (e.g. hostile titles).
    EXPECT_GT(total, 1000u);
    EXPECT_GT(accepted, 50u);
    EXPECT_LT(accepted, total);
    EXPECT_GT(exported, 80u);
    std::printf("layout mutants: %zu generated, %zu accepted by check, %zu distinct wirings compiled, %zu distinct "
                "exports (HLSL and GLSL) compiled\n", total, accepted, compiled, exported);
}

TEST(LayoutMutants, NonFiniteAndOutOfRangeNumbersAreRefusedWithPlace) {
    const std::string thin = readAll(std::filesystem::path(GBL_SOURCE_LAYOUT_DIR) / "crysis3-thin.toml");
    const std::string constant = "at = \"a\", value = 0.0";
    const size_t at = thin.find(constant);
    ASSERT_NE(at, std::string::npos) << "crysis3-thin.toml changed: pick another constant";
    int line = 1;
    for (size_t i = 0; i < at; ++i) line += thin[i] == '\n';
    const size_t column = at - thin.rfind('\n', at) + constant.size() - 3;  // 1-based column of the number
    for (const char* bad : {"nan", "inf", "-inf", "1e39", "-1e39", "+nan"}) {
        std::string text = thin;
        text.replace(at, constant.size(), std::string("at = \"a\", value = ") + bad);
        const auto problems = checkLayout(text, "crysis3-thin.toml");
        ASSERT_FALSE(problems.empty()) << bad;
        const std::string message = problems.front().text();
        EXPECT_EQ(message.rfind("crysis3-thin.toml:" + std::to_string(line) + ":" + std::to_string(column) + ": ", 0), 0u)
            << message;
        EXPECT_TRUE(message.find("finite") != std::string::npos || message.find("out of range") != std::string::npos)
            << message;
    }
}

TEST(LayoutMutants, NamesWithNewlinesAreRefusedAndEscapedInMessages) {
    const std::string ue4 = readAll(std::filesystem::path(GBL_SOURCE_LAYOUT_DIR) / "ue4.toml");
    std::string text = ue4;
    const size_t at = text.find("name = \"", text.find("[[target]]"));
    ASSERT_NE(at, std::string::npos);
    text.insert(at + 8, "x\\n#error injected");
    const auto problems = checkLayout(text, "ue4.toml");
    ASSERT_FALSE(problems.empty());
    const std::string line = problems.front().text();
    EXPECT_NE(line.find("'x\\n#error injected"), std::string::npos) << line;  // escaped, not raw
    EXPECT_EQ(line.find('\n'), std::string::npos) << line;
}

TEST(LayoutMutants, GeneratedGlslKeepsLayoutTextInComments) {
    Layout l = loadLayoutFile(std::filesystem::path(GBL_SOURCE_LAYOUT_DIR) / "ue4.toml");
    l.title = "t\\\n#error title";  // a Layout not built by the parser: codegen must still be safe
    l.targets[0].name = "x\n#error injected\\";
    const GBufferWiring w = generateWiring(l);
    EXPECT_EQ(w.glsl.find("\n#error title"), std::string::npos) << w.glsl;
    EXPECT_EQ(w.glsl.find("\n#error injected"), std::string::npos) << w.glsl;
    EXPECT_EQ(w.glsl.find('\\'), std::string::npos) << w.glsl;
    compiles("gbuffer_pass.frag.glsl", w, "(hand-built layout)");
    for (ExportLanguage lang : {ExportLanguage::Glsl, ExportLanguage::Hlsl}) {
        const std::string e = exportText(l, lang);
        EXPECT_EQ(e.find("\n#error"), std::string::npos) << e;
        EXPECT_EQ(e.find('\\'), std::string::npos) << e;
        exportCompiles(l, lang, e, "(hand-built layout)");
    }
}
