// libFuzzer target: any bytes as a layout file. checkLayout must return diagnostics (never crash,
// hang or trip a sanitizer), and a layout it accepts must export (layouts export, HLSL and GLSL
// with the kernel) to text whose every byte is printable ASCII or a newline: layout text reaches
// the export only escaped (that the exports compile is tests/layout/layout_mutants_test.cpp's
// job: glslang is not in this build). Built and run by scripts/fuzz.sh (clang, -fsanitize=fuzzer).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>

#include "layout.h"
#include "layout_export.h"

namespace {

std::optional<std::string> shaderFile(const std::string& name) {
    static std::map<std::string, std::string> cache;
    if (auto it = cache.find(name); it != cache.end()) return it->second;
    std::ifstream in(std::string(GBL_SOURCE_SHADER_DIR) + "/" + name);
    if (!in) return std::nullopt;
    std::stringstream ss;
    ss << in.rdbuf();
    return cache[name] = ss.str();
}

// Both languages with the kernel; a byte that is not printable ASCII or a newline traps.
void exportBoth(const gbl::Layout& layout) {
    static const gbl::exporting::GlslLibrary library(shaderFile);
    for (gbl::ExportLanguage lang : {gbl::ExportLanguage::Glsl, gbl::ExportLanguage::Hlsl}) {
        gbl::ExportOptions options;
        options.language = lang;
        options.kernel = true;
        const std::string out = gbl::exportLayout(layout, options, library);
        for (const char c : out)
            if ((static_cast<unsigned char>(c) < 0x20 && c != '\n') || static_cast<unsigned char>(c) >= 0x7f)
                __builtin_trap();
    }
}

}  // namespace

// Every shipped layout is exported once before the first unit: the one-time costs (the shader
// library's files, the export's table trees: seconds under ASan) then fall on no unit, which
// libFuzzer would otherwise report as slow.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    for (const auto& entry : std::filesystem::directory_iterator(GBL_SOURCE_LAYOUT_DIR)) {
        if (entry.path().extension() != ".toml") continue;
        std::ifstream in(entry.path());
        std::stringstream ss;
        ss << in.rdbuf();
        const std::string text = ss.str();
        if (gbl::checkLayout(text, entry.path().string()).empty()) exportBoth(gbl::parseLayout(text, entry.path().string()));
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::vector<gbl::LayoutDiagnostic> problems = gbl::checkLayout(text, "fuzz.toml");
    for (const gbl::LayoutDiagnostic& d : problems) {
        const std::string line = d.text();
        for (const char c : line)
            if (c == '\n') __builtin_trap();  // every diagnostic is one line
    }
    if (!problems.empty()) return 0;
    exportBoth(gbl::parseLayout(text, "fuzz.toml"));
    return 0;
}
