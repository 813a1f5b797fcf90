// A guard in front of toml::parse for two bugs of toml++ 3.3.0 (the Debian 12 package), both
// found by scripts/fuzz.sh within seconds. toml++ states preconditions with TOML_ASSERT_ASSUME:
// an assert() in a build with assertions, and with NDEBUG a hint to the optimiser (TOML_ASSUME is
// __builtin_assume on clang and MSVC), so breaking one is an abort or undefined behaviour.
//   1. A table header whose first character after '[' (or "[[") and spaces cannot start a key:
//      "[#", "[&", "[[[1]]]", '[' at the end of a line. parse_table_header() calls parse_key()
//      without checking, which assumes is_bare_key_character(*cp) || is_string_delimiter(*cp).
//      (Upstream issue marzer/tomlplusplus#294, fixed upstream by pull request #301.)
//   2. In an array, '}' or a Unicode line break (U+0085, U+2028, U+2029) where a value may start:
//      "l=[}". parse_array() handles spaces, line breaks, comments, ',' and ']', then calls
//      parse_value(), which assumes !is_value_terminator(*cp).
//   3. Any of U+00A1..U+0499 ('é', Greek, Cyrillic) outside a string or comment, or right after a
//      line-ending backslash in a multi-line string: is_non_ascii_horizontal_whitespace() reaches
//      TOML_UNREACHABLE for them (UBSan: "execution reached an unreachable program point").
// Debian's libtomlplusplus.so is built by g++ with NDEBUG, where TOML_ASSUME is a no-op, so the
// Release build happens to reach toml++'s own error branches; nothing guarantees that.
//
// findTomlPlusPlusHazard scans the text the way toml++'s root loop walks it (statements, strings,
// comments, brackets) and finds the first such place, so the parser reports it with its place and
// never hands such a text to toml++. Where the text is broken in some other way before it,
// toml++ stops there first, so the scan stops too and lets toml++ report it.
#include "layout_parser_detail.h"

namespace gbl::layout_parser {

namespace {

bool isBareKeyChar(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
}
bool isSpace(char c) { return c == ' ' || c == '\t'; }

class Scanner {
public:
    explicit Scanner(std::string_view text) : text_(text) {
        if (text_.substr(0, 3) == "\xEF\xBB\xBF") bom_ = pos_ = 3;  // toml++ skips a UTF-8 BOM
    }

    std::optional<std::pair<FilePlace, std::string>> run() {
        while (true) {
            while (pos_ < text_.size() && isSpace(text_[pos_])) ++pos_;
            if (pos_ >= text_.size()) return std::nullopt;
            const char c = text_[pos_];
            if (c == '\n') {
                ++pos_;
            } else if (c == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n') {
                pos_ += 2;
            } else if (c == '#') {
                skipComment();
            } else if (c == '[') {
                if (auto bad = checkHeader()) return bad;
                if (!skipStatement()) return found_;
            } else if (isBareKeyChar(c) || c == '"' || c == '\'') {
                if (!skipStatement()) return found_;
            } else if (static_cast<unsigned char>(c) >= 0x80) {
                refuse(pos_, nonAsciiOutsideStrings(pos_));
                return found_;
            } else {
                return std::nullopt;  // toml++ refuses this statement itself, before any later header
            }
        }
    }

private:
    // At a '[' that starts a statement: what toml++'s parse_table_header does before parse_key().
    std::optional<std::pair<FilePlace, std::string>> checkHeader() {
        size_t p = pos_ + 1;
        const size_t afterBracket = p;
        while (p < text_.size() && isSpace(text_[p])) ++p;
        if (p >= text_.size()) return std::nullopt;          // toml++: unexpected end of file
        if (text_[p] == '[') {
            if (p != afterBracket) return std::nullopt;      // toml++: "[ [" is refused
            ++p;
            while (p < text_.size() && isSpace(text_[p])) ++p;
            if (p >= text_.size()) return std::nullopt;
        }
        const char c = text_[p];
        if (c == ']' || isBareKeyChar(c) || c == '"' || c == '\'') return std::nullopt;
        std::string saw;
        if (c == '\n' || c == '\r') {
            saw = "the end of the line";
        } else {
            size_t end = p + 1;  // the whole UTF-8 sequence, escaped by quoteBytes
            while (end < text_.size() && (static_cast<unsigned char>(text_[end]) & 0xC0) == 0x80 && end - p < 4) ++end;
            saw = quoteBytes(text_.substr(p, end - p));
        }
        return std::make_pair(placeAt(p), "TOML syntax error: a table header must start with a key (a bare name or a "
                                          "quoted string) after '[', saw " +
                                              saw);
    }

    // From the start of a statement (a key = value pair or a table header) to the line break that
    // ends it, past strings, comments and the line breaks inside arrays and inline tables.
    // False where the scan stops: the text ends inside a string (toml++ reports that), or an array
    // holds what toml++ would hand to parse_value() unchecked (found_).
    bool skipStatement() {
        const bool header = text_[pos_] == '[';
        const size_t start = pos_;
        std::string open;    // the '[' and '{' not yet closed, innermost last
        bool inKey = true;   // reading a key (before '=', or after '{' or ',' in an inline table)
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            const bool inArray = !header && !open.empty() && open.back() == '[';
            // A quote starts a string only where a value or key can start: right after a bare
            // character ('0"...') toml++ scans it as part of the bare value instead.
            const char before = pos_ == start ? ' ' : text_[pos_ - 1];
            const bool canStart = before == ' ' || before == '\t' || before == '=' || before == '[' ||
                                  before == '{' || before == ',' || before == '\n' || before == '\r' ||
                                  (before == '.' && inKey) || pos_ == start;
            if ((c == '"' || c == '\'') && canStart) {
                if (!skipString()) return false;
                continue;
            }
            if (c == '=') inKey = false;
            if (c == '{' || (c == ',' && !open.empty() && open.back() == '{')) inKey = true;
            if (c == '[' && !header) inKey = false;
            if (c == '#') {
                skipComment();
                continue;
            }
            if (c == '\n' && open.empty()) return true;
            // parse_array() skips spaces, line breaks and comments and handles ',' and ']', then
            // calls parse_value(), which assumes (TOML_ASSERT_ASSUME) that no value terminator
            // follows: '}' ("l=[}") and the Unicode line breaks U+0085, U+2028, U+2029 do.
            if (inArray && c == '}') return refuse(pos_, "'}' in an array (expected a value, ',' or ']')");
            if (inArray && isUnicodeLineBreak(pos_))
                return refuse(pos_, quoteBytes(text_.substr(pos_, text_[pos_] == '\xC2' ? 2 : 3)) +
                                        " (a Unicode line break) in an array: TOML allows only spaces, tabs and "
                                        "\\n or \\r\\n between values");
            if (static_cast<unsigned char>(c) >= 0x80) return refuse(pos_, nonAsciiOutsideStrings(pos_));
            if (c == '[' || c == '{') {
                open += c;
            } else if ((c == ']' || c == '}') && !open.empty()) {
                open.pop_back();
            }
            ++pos_;
        }
        return true;
    }

    // Bug 3: toml++'s is_non_ascii_horizontal_whitespace() reaches TOML_UNREACHABLE (undefined
    // behaviour) for U+00A1 to U+0499 (Latin-1 letters such as 'é', Greek, Cyrillic). toml++ asks
    // it of every character outside strings and comments that it skips or ends a value at, and in
    // a multi-line basic string of the first character after a line-ending backslash. Outside
    // strings and comments TOML is ASCII anyway, so every non-ASCII character there is refused.
    std::string nonAsciiOutsideStrings(size_t at) const {
        return "non-ASCII character " + quoteBytes(codepointText(at)) +
               " outside a string or comment (TOML keys and non-string values are ASCII)";
    }
    std::string_view codepointText(size_t at) const {
        size_t end = at + 1;
        while (end < text_.size() && (static_cast<unsigned char>(text_[end]) & 0xC0) == 0x80 && end - at < 4) ++end;
        return text_.substr(at, end - at);
    }
    bool isInUnreachableRange(size_t at) const {  // U+00A1..U+0499: two UTF-8 bytes C2 A1 .. D2 99
        if (at + 1 >= text_.size()) return false;
        const auto b0 = static_cast<unsigned char>(text_[at]), b1 = static_cast<unsigned char>(text_[at + 1]);
        if (b0 < 0xC2 || b0 > 0xDF || (b1 & 0xC0) != 0x80) return false;
        const unsigned cp = ((b0 & 0x1Fu) << 6) | (b1 & 0x3Fu);
        return cp >= 0xA1 && cp <= 0x499;
    }

    bool isUnicodeLineBreak(size_t at) const {  // U+0085 (C2 85), U+2028 and U+2029 (E2 80 A8/A9)
        const std::string_view s = text_.substr(at, 3);
        return s.substr(0, 2) == "\xC2\x85" || s == "\xE2\x80\xA8" || s == "\xE2\x80\xA9";
    }

    bool refuse(size_t at, const std::string& what) {
        found_ = std::make_pair(placeAt(at), "TOML syntax error: " + what);
        return false;
    }

    void skipComment() {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    }

    // At a quote: past the string ("...", '...', """...""" or '''...'''). False if it does not
    // end, or a one-line string meets a line break (toml++ reports both).
    bool skipString() {
        const char q = text_[pos_];
        const bool basic = q == '"';
        const bool multi = text_.substr(pos_, 3) == std::string(3, q);
        pos_ += multi ? 3 : 1;
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (basic && c == '\\') {
                if (multi) {
                    size_t p = pos_ + 1;
                    while (p < text_.size() && (isSpace(text_[p]) || text_[p] == '\n' || text_[p] == '\r')) ++p;
                    if (p < text_.size() && isInUnreachableRange(p)) {
                        const std::string ch = quoteBytes(codepointText(p));
                        refuse(p, ch + " right after a line-ending backslash in a multi-line string: toml++ 3.3.0 "
                                       "cannot read it there; write it as a \\u escape");
                        return false;
                    }
                }
                pos_ += 2;
                continue;
            }
            if (c == q) {
                if (!multi) {
                    ++pos_;
                    return true;
                }
                if (text_.substr(pos_, 3) == std::string(3, q)) {
                    pos_ += 3;
                    for (int extra = 0; extra < 2 && pos_ < text_.size() && text_[pos_] == q; ++extra) ++pos_;
                    return true;
                }
            }
            if (c == '\n' && !multi) return false;
            ++pos_;
        }
        return false;
    }

    // Line and column as toml++ counts them: columns in code points, a BOM not counted.
    FilePlace placeAt(size_t at) const {
        int line = 1, column = 1;
        for (size_t i = bom_; i < at; ++i) {
            if (text_[i] == '\n') {
                ++line;
                column = 1;
            } else if ((static_cast<unsigned char>(text_[i]) & 0xC0) != 0x80) {
                ++column;
            }
        }
        return {line, column};
    }

    std::string_view text_;
    std::optional<std::pair<FilePlace, std::string>> found_;
    size_t pos_ = 0;
    size_t bom_ = 0;
};

}  // namespace

std::optional<std::pair<FilePlace, std::string>> findTomlPlusPlusHazard(std::string_view text) {
    return Scanner(text).run();
}

}  // namespace gbl::layout_parser
