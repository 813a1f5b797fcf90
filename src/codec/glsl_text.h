#pragma once
// How the code generators (wiring_codegen.cpp, light_buffer_wiring.cpp) write values and layout
// text into GLSL.
#include <cstdio>
#include <string>

namespace gbl {

// A float literal GLSL reads back to the same 32-bit float: v rounded to float, 9 significant
// digits, with a ".0" when printf gives an integer.
inline std::string glslFloatLiteral(double v) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(static_cast<float>(v)));
    std::string s = buf;
    if (s.find_first_of(".en") == std::string::npos) s += ".0";
    return s;
}

// Layout text (title, target names) only ever appears in GLSL comments, and only as this: printable
// ASCII without backslashes or double quotes (a trailing backslash would continue the comment onto
// the next line; a quote would unbalance the #error line). The parser already refuses control
// characters; this holds for a Layout built any other way too.
inline std::string glslCommentText(const std::string& text) {
    std::string out = text;
    for (char& c : out)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f || c == '\\' || c == '"')
            c = '?';
    return out;
}

}  // namespace gbl
