#include "error.h"

#include <algorithm>
#include <cstdint>

namespace gbl {

std::string formatPlace(const std::string& file, int line, int column) {
    std::string place = file;
    if (line > 0) {
        place += ":" + std::to_string(line);
        if (column > 0) place += ":" + std::to_string(column);
    }
    return place;
}

void throwUserError(const std::string& message) { throw UserError(message); }

namespace {

void appendByteEscape(std::string& out, unsigned char c) {
    static const char* hex = "0123456789abcdef";
    out += "\\x";
    out += hex[c >> 4];
    out += hex[c & 15];
}

// The length of the well-formed UTF-8 sequence at text[i] (2 to 4) and its code point, or 0.
size_t utf8Sequence(std::string_view text, size_t i, uint32_t& cp) {
    const auto b = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char c = b(i);
    size_t n = 0;
    if (c >= 0xC2 && c <= 0xDF) n = 2, cp = c & 0x1Fu;
    else if (c >= 0xE0 && c <= 0xEF) n = 3, cp = c & 0x0Fu;
    else if (c >= 0xF0 && c <= 0xF4) n = 4, cp = c & 0x07u;
    else return 0;
    if (i + n > text.size()) return 0;
    for (size_t k = 1; k < n; ++k) {
        if ((b(i + k) & 0xC0) != 0x80) return 0;
        cp = (cp << 6) | (b(i + k) & 0x3Fu);
    }
    const uint32_t least[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < least[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;  // overlong, surrogate
    return n;
}

// Code points printed escaped although well formed: they break the line or hide text.
bool hidesOrBreaks(uint32_t cp) {
    return (cp >= 0x80 && cp <= 0x9F) || cp == 0xAD || (cp >= 0x200B && cp <= 0x200F) ||
           (cp >= 0x2028 && cp <= 0x202E) || (cp >= 0x2060 && cp <= 0x206F) || cp == 0xFEFF;
}

std::string escape(std::string_view text, bool keepUtf8) {
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        switch (c) {
            case '\n': out += "\\n"; ++i; continue;
            case '\r': out += "\\r"; ++i; continue;
            case '\t': out += "\\t"; ++i; continue;
            case '\\': out += "\\\\"; ++i; continue;
            case '\'': out += "\\'"; ++i; continue;
            default: break;
        }
        if (c >= 0x20 && c < 0x7f) {
            out += char(c);
            ++i;
            continue;
        }
        uint32_t cp = 0;
        const size_t n = keepUtf8 && c >= 0x80 ? utf8Sequence(text, i, cp) : 0;
        if (n > 0 && !hidesOrBreaks(cp)) {
            out.append(text.substr(i, n));
        } else {
            for (size_t k = 0; k < std::max<size_t>(n, 1); ++k)
                appendByteEscape(out, static_cast<unsigned char>(text[i + k]));
        }
        i += std::max<size_t>(n, 1);
    }
    return out;
}

}  // namespace

std::string escapeText(std::string_view text) { return escape(text, true); }

std::string quoteName(std::string_view text) { return "'" + escapeText(text) + "'"; }

std::string escapeBytes(std::string_view text) { return escape(text, false); }

std::string quoteBytes(std::string_view text) { return "'" + escapeBytes(text) + "'"; }

std::string jsonParseErrorMessage(const std::string& file, std::string_view text, size_t byte, const std::string& what) {
    int line = 1, column = 1;
    for (size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    std::string reason = what;
    const size_t at = reason.find("parse error");
    if (const size_t colon = reason.find(": ", at == std::string::npos ? 0 : at); colon != std::string::npos)
        reason = reason.substr(colon + 2);
    return formatPlace(escapeText(file), line, column) + ": not valid JSON: " + escapeText(reason);
}

}  // namespace gbl
