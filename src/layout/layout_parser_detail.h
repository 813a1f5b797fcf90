#pragma once
// The layout parser's own parts, shared by the files that read one section each of a layout file:
// layout_parser.cpp (document, source, depth, targets, and the public functions of layout.h),
// layout_parse_fields.cpp (a target's fields and code places) and layout_parse_fallbacks.cpp
// (fallbacks and light buffers). Not part of the layout library's interface.
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "error.h"
#include "layout.h"

namespace gbl::layout_parser {

inline FilePlace placeOf(const toml::source_region& r) {
    if (r.begin.line == 0) return {1, 1};
    return {static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
}
inline FilePlace placeOf(const toml::node& n) { return placeOf(n.source()); }

inline const char* typeName(const toml::node& n) {
    switch (n.type()) {
        case toml::node_type::table:
            return "a table";
        case toml::node_type::array:
            return "an array";
        case toml::node_type::string:
            return "a string";
        case toml::node_type::integer:
            return "an integer";
        case toml::node_type::floating_point:
            return "a number";
        case toml::node_type::boolean:
            return "a boolean";
        default:
            return "a date/time";
    }
}

// Names come from the file: quoted escaped, so a message stays one line of plain text.
inline std::string squote(std::string_view s) { return quoteName(s); }

// Titles and target / light-buffer names are shown on one line (layouts list, reports); a control
// character in one would break that line. (They never reach GLSL unescaped either: see
// wiring_codegen.cpp's commentText.)
inline bool isOneLine(std::string_view s) {
    return std::none_of(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}

// Values are ids (at most 32 bits) or floats; 2^32 bounds both comfortably below float's 3.4e38.
constexpr double kMaxLayoutNumber = 4294967296.0;

// The first place in `text` that would break a precondition toml++ 3.3.0 does not check ("[#",
// "l=[}": see layout_toml_guard.cpp), with a "TOML syntax error: ..." message; nullopt when
// toml::parse can be given the text.
std::optional<std::pair<FilePlace, std::string>> findTomlPlusPlusHazard(std::string_view text);

inline std::string formatNumber(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

class Parser {
public:
    Parser(std::string file, std::vector<LayoutDiagnostic>& out) : file_(std::move(file)), out_(out) {}

    void error(FilePlace place, std::string message) { out_.push_back({file_, place, std::move(message)}); }

    // Reports keys of `table` not in `known`.
    void checkKeys(const toml::table& table, std::initializer_list<const char*> known, const char* where) {
        for (auto&& [key, node] : table) {
            (void)node;
            bool ok = false;
            for (const char* k : known) ok = ok || key.str() == k;
            if (ok) continue;
            std::string list;
            for (const char* k : known) list += std::string(list.empty() ? "" : ", ") + k;
            error(placeOf(key.source()),
                  "unknown key " + squote(key.str()) + " in " + where + " (known: " + list + ")");
        }
    }

    // Value of `key` in `table` as a string; reports a missing key (when `required`) at `owner`.
    std::optional<std::string> getString(const toml::table& table, const char* key, bool required, FilePlace owner,
                                         const std::string& where) {
        const toml::node* n = table.get(key);
        if (!n) {
            if (required) error(owner, where + " has no '" + key + "'");
            return std::nullopt;
        }
        if (!n->is_string()) {
            error(placeOf(*n), "'" + std::string(key) + "' must be a string, not " + typeName(*n));
            return std::nullopt;
        }
        const std::string& text = n->as_string()->get();
        if (!isOneLine(text)) {
            error(placeOf(*n), "'" + std::string(key) + "' " + squote(text) +
                                   " holds a control character (newline, tab...): write it on one line");
            return std::nullopt;
        }
        return text;
    }

    std::optional<int64_t> getInteger(const toml::node& n, const std::string& what) {
        if (!n.is_integer()) {
            error(placeOf(n), what + " must be an integer, not " + typeName(n));
            return std::nullopt;
        }
        return n.as_integer()->get();
    }

    // Every number ends up as a 32-bit float (in GLSL and the CPU mirror): nan, inf and values
    // beyond float range would not survive that, so they are refused here, where the place is known.
    std::optional<double> getNumber(const toml::node& n, const std::string& what) {
        double x = 0;
        if (n.is_integer() || n.is_floating_point()) {
            x = n.is_integer() ? static_cast<double>(n.as_integer()->get()) : n.as_floating_point()->get();
            if (!std::isfinite(x)) {
                error(placeOf(n), what + " must be a finite number, not " + std::to_string(x));
                return std::nullopt;
            }
            if (std::fabs(x) > kMaxLayoutNumber) {
                error(placeOf(n), what + " " + formatNumber(x) + " is out of range (at most " +
                                      formatNumber(kMaxLayoutNumber) + " in magnitude)");
                return std::nullopt;
            }
            return x;
        }
        error(placeOf(n), what + " must be a number, not " + typeName(n));
        return std::nullopt;
    }

    // A number or an array of numbers.
    std::optional<std::vector<double>> getNumbers(const toml::node& n, const std::string& what) {
        std::vector<double> v;
        if (const toml::array* a = n.as_array()) {
            for (const toml::node& e : *a) {
                auto x = getNumber(e, what);
                if (!x) return std::nullopt;
                v.push_back(*x);
            }
            if (v.empty()) {
                error(placeOf(n), what + " is an empty array");
                return std::nullopt;
            }
            return v;
        }
        auto x = getNumber(n, what);
        if (!x) return std::nullopt;
        v.push_back(*x);
        return v;
    }

    Layout parse(std::string_view text);

private:
    void parseSource(const toml::table& root, Layout& layout);
    void parseDepth(const toml::table& root, Layout& layout);
    void parseTarget(const toml::node& node, Layout& layout);
    std::optional<Field> parseField(const toml::node& node, const std::vector<Channel>& channels,
                                    const std::string& formatName, bool stencil);
    bool parsePlace(const toml::node& node, const std::vector<Channel>& channels, const std::string& formatName,
                    CodePlace& out);
    // A field's 'at' (layout_parse_fields.cpp): its codes' places into field.codes.
    void parsePlaces(const toml::table& t, const std::vector<Channel>& channels, const std::string& formatName,
                     const std::string& what, Field& field);
    void parseFallbacks(const toml::table& root, Layout& layout);
    void parseLightBuffers(const toml::table& root, Layout& layout);
    void parseClear(const toml::table& root, Layout& layout);
    void parseMaterialPass(const toml::table& root, Layout& layout);
    void parseSpace(const toml::table& root, Layout& layout);
    void parseIds(const toml::table& root, Layout& layout);  // layout_visibility.cpp
    // layout_provenance.cpp: [sources], and the from / status / differs keys of one entry.
    void parseSources(const toml::table& root, Layout& layout);
    void readProvenance(const toml::table& table, Provenance& out, FilePlace entry);
    const toml::node* entryValue(const toml::node& node, Provenance& out, const std::string& what);

    std::string file_;
    std::vector<LayoutDiagnostic>& out_;
};

}  // namespace gbl::layout_parser
