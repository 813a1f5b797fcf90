#pragma once
// The layout-language tests' small valid layout and their helpers: edit one line, find the place
// of a marker, and expect one diagnostic at that place with given words.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <vector>

#include "error.h"
#include "layout.h"
#include "layout_text.h"

namespace gbl::layout_test {

using namespace gbl;

inline const char* kFile = "fake/test.toml";

// A valid layout exercising bit fields: xy + z sign, 7-bit gloss, a 3:3:2 colour in one byte.
const std::string kValid =
    test::LayoutText("test", "A test layout", R"({ game = "none", talk = "unit test", year = 2024 })")
        .depth("format = \"D24_UNORM_S8_UINT\"\nstencil = [ { attribute = \"ambient_id\", at = \"s[0:3]\", value = 2 } ]\n")
        .target("rt0", "R8G8B8A8_UNORM",
                {R"(attribute = "normal", encoding = "normal_xy_zsign", at = ["r", "g", "b[7]"])",
                 R"(attribute = "roughness", encoding = "gloss", at = "b[0:6]")",
                 R"(attribute = "base_color", encoding = "unorm", at = ["a[0:2]", "a[3:5]", "a[6:7]"])"})
        .fallbackOrder({"specular_color", "diffuse_color", "metallic", "specular", "occlusion", "emissive"})
        .space("normal = \"world\"\nup = \"z\"\n")
        .clear("base_color = 0.0");

// `text` with the first `from` replaced by `to` (which must exist).
inline std::string edit(const std::string& text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the text";
    if (at == std::string::npos) return text;
    return text.substr(0, at) + to + text.substr(at + from.size());
}

// "file:line:col" of the first occurrence of `marker` in `text` (1-based).
inline std::string placeOf(const std::string& text, const std::string& marker, size_t occurrence = 0) {
    size_t at = text.find(marker);
    for (size_t i = 0; i < occurrence && at != std::string::npos; ++i) at = text.find(marker, at + 1);
    EXPECT_NE(at, std::string::npos) << "test bug: marker '" << marker << "' not in the text";
    int line = 1, col = 1;
    for (size_t i = 0; i < at && i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++line;
            col = 1;
        } else {
            ++col;
        }
    }
    return std::string(kFile) + ":" + std::to_string(line) + ":" + std::to_string(col);
}

inline std::string joined(const std::vector<LayoutDiagnostic>& diags) {
    std::string s;
    for (const auto& d : diags) s += d.text() + "\n";
    return s;
}

// Asserts a diagnostic exists that starts with `place + ": "` and contains every word.
inline void expectError(const std::string& text, const std::string& place, std::initializer_list<std::string> words) {
    const auto diags = checkLayout(text, kFile);
    ASSERT_FALSE(diags.empty()) << "no error for:\n" << text;
    for (const auto& d : diags) {
        const std::string t = d.text();
        if (t.rfind(place + ": ", 0) != 0) continue;
        bool all = true;
        for (const std::string& w : words) all = all && t.find(w) != std::string::npos;
        if (all) return;
    }
    std::string want;
    for (const std::string& w : words) want += " [" + w + "]";
    ADD_FAILURE() << "expected an error at " << place << " with" << want << "; got:\n" << joined(diags);
}

// Exactly one diagnostic (no cascade).
inline void expectOnlyError(const std::string& text, const std::string& place, std::initializer_list<std::string> words) {
    const auto diags = checkLayout(text, kFile);
    EXPECT_EQ(diags.size(), 1u) << joined(diags);
    expectError(text, place, words);
}


}  // namespace gbl::layout_test
