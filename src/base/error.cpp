#include "error.h"

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

std::string escapeText(std::string_view text) {
    static const char* hex = "0123456789abcdef";
    std::string out;
    out.reserve(text.size());
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        switch (c) {
            case '\n': out += "\\n"; continue;
            case '\r': out += "\\r"; continue;
            case '\t': out += "\\t"; continue;
            case '\\': out += "\\\\"; continue;
            case '\'': out += "\\'"; continue;
            default: break;
        }
        if (c < 0x20 || c >= 0x7f) {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        } else {
            out += ch;
        }
    }
    return out;
}

std::string quoteName(std::string_view text) { return "'" + escapeText(text) + "'"; }

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
