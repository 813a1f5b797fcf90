// Reads a layout file (TOML, via toml++) into the Layout data model. This file checks structure:
// keys, types and names (attributes, encodings, formats, channels, fallback keywords); the
// semantic checks (bits, code counts, overlaps, coverage) are in layout_validate.cpp. Every problem
// becomes a LayoutDiagnostic with the file, line and column of the offending key or value.
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "encoding_registry.h"
#include "error.h"
#include "file_io.h"
#include "layout.h"

namespace gbl {

namespace {

FilePlace placeOf(const toml::source_region& r) {
    if (r.begin.line == 0) return {1, 1};
    return {static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
}
FilePlace placeOf(const toml::node& n) { return placeOf(n.source()); }

const char* typeName(const toml::node& n) {
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
std::string squote(std::string_view s) { return quoteName(s); }

// Titles and target / light-buffer names are shown on one line (layouts list, reports); a control
// character in one would break that line. (They never reach GLSL unescaped either: see
// wiring_codegen.cpp's commentText.)
bool isOneLine(std::string_view s) {
    return std::none_of(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}

// ---- transforms and interleaving: spellings of registry encodings ------------------------------
// The registry names one primitive per variant ("gloss", "ycbcr_sqrt", "ycbcr_checkerboard"); a
// layout may also write the base encoding plus `transform` / `interleave`, which resolve here.
struct Variant {
    const char* base;
    const char* transform;   // nullptr: none
    const char* interleave;  // nullptr: none
    const char* encoding;    // the registry name it resolves to
};
constexpr Variant kVariants[] = {
    {"unorm", "gloss", nullptr, "gloss"},
    {"unorm", "cry_smoothness", nullptr, "smoothness_cry"},
    {"ycbcr", "sqrt", nullptr, "ycbcr_sqrt"},
    {"ycbcr", nullptr, "checkerboard", "ycbcr_checkerboard"},
    {"ycocg", nullptr, "checkerboard", "ycocg_checkerboard"},
};
constexpr const char* kTransforms[] = {"gloss", "cry_smoothness", "sqrt"};
constexpr const char* kInterleaves[] = {"checkerboard"};

struct FallbackKeyword {
    const char* name;
    FallbackKind kind;
};
constexpr FallbackKeyword kFallbackKeywords[] = {
    {"from_metallic", FallbackKind::FromMetallic},
    {"ue4", FallbackKind::Ue4},
    {"from_base_color", FallbackKind::FromBaseColor},
    {"from_diffuse_specular", FallbackKind::FromDiffuseSpecular},
    {"from_specular_color", FallbackKind::FromSpecularColor},
    {"material_pass", FallbackKind::MaterialPass},
    {"forward", FallbackKind::Forward},
};

// Which derived fallbacks each shading attribute accepts (all accept a constant except normal and
// roughness, which every layout must store).
std::vector<FallbackKind> allowedFallbacks(Attribute a) {
    using F = FallbackKind;
    switch (a) {
        case Attribute::SpecularColor:
            return {F::FromMetallic, F::Ue4, F::MaterialPass};
        case Attribute::DiffuseColor:
            return {F::FromBaseColor, F::MaterialPass};
        case Attribute::BaseColor:
            return {F::FromDiffuseSpecular, F::MaterialPass};
        case Attribute::Metallic:
            return {F::FromSpecularColor, F::MaterialPass};
        case Attribute::Specular:
            return {F::MaterialPass};
        case Attribute::Occlusion:
            return {F::MaterialPass};
        case Attribute::Emissive:
            return {F::Forward, F::MaterialPass};
        default:
            return {};
    }
}

// Values are ids (at most 32 bits) or floats; 2^32 bounds both comfortably below float's 3.4e38.
constexpr double kMaxLayoutNumber = 4294967296.0;

std::string formatNumber(double x) {
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
    void parseFallbacks(const toml::table& root, Layout& layout);
    void parseLightBuffers(const toml::table& root, Layout& layout);

    std::string file_;
    std::vector<LayoutDiagnostic>& out_;
};

Layout Parser::parse(std::string_view text) {
    Layout layout;
    layout.sourceFile = file_;
    toml::table root;
    try {
        root = toml::parse(text, file_);
    } catch (const toml::parse_error& e) {
        error(placeOf(e.source()), "TOML syntax error: " + escapeText(e.description()));
        return layout;
    }
    const FilePlace top{1, 1};
    checkKeys(root, {"name", "title", "source", "pipeline", "depth", "target", "fallback", "light_buffer"},
              "the layout");

    if (auto name = getString(root, "name", true, top, "the layout")) {
        const bool ok = !name->empty() && std::all_of(name->begin(), name->end(), [](char c) {
            return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
        });
        if (!ok)
            error(placeOf(*root.get("name")),
                  "layout name " + squote(*name) + " must be lowercase letters, digits, '-' or '_'");
        layout.name = *name;
        layout.namePlace = placeOf(*root.get("name"));
    }
    if (auto title = getString(root, "title", true, top, "the layout")) layout.title = *title;
    parseSource(root, layout);

    if (auto pipeline = getString(root, "pipeline", true, top, "the layout")) {
        if (*pipeline == "deferred-shading")
            layout.pipeline = Pipeline::DeferredShading;
        else if (*pipeline == "deferred-lighting")
            layout.pipeline = Pipeline::DeferredLighting;
        else
            error(placeOf(*root.get("pipeline")),
                  "unknown pipeline " + squote(*pipeline) + " (known: deferred-shading, deferred-lighting)");
    }

    parseDepth(root, layout);

    if (const toml::node* targets = root.get("target")) {
        if (const toml::array* a = targets->as_array()) {
            for (const toml::node& t : *a) parseTarget(t, layout);
            if (a->empty()) error(placeOf(*targets), "'target' is empty: a layout needs at least one render target");
        } else {
            error(placeOf(*targets),
                  "'target' must be an array of tables ([[target]]), not " + std::string(typeName(*targets)));
        }
    } else {
        error(top, "the layout has no render target: add a [[target]] table");
    }

    parseFallbacks(root, layout);
    parseLightBuffers(root, layout);
    return layout;
}

void Parser::parseSource(const toml::table& root, Layout& layout) {
    const toml::node* n = root.get("source");
    if (!n) {
        error({1, 1},
              "the layout has no 'source': cite the game, talk or code and the year "
              "(source = { game = \"...\", talk = \"...\", year = 2013 })");
        return;
    }
    const toml::table* t = n->as_table();
    if (!t) {
        error(placeOf(*n),
              "'source' must be a table (game, engine, talk, code, year), not " + std::string(typeName(*n)));
        return;
    }
    const FilePlace at = placeOf(*n);
    checkKeys(*t, {"game", "engine", "talk", "code", "year"}, "source");
    Source& s = layout.source;
    s.game = getString(*t, "game", false, at, "source").value_or("");
    s.engine = getString(*t, "engine", false, at, "source").value_or("");
    s.talk = getString(*t, "talk", false, at, "source").value_or("");
    s.code = getString(*t, "code", false, at, "source").value_or("");
    if (const toml::node* y = t->get("year")) {
        if (auto year = getInteger(*y, "'year'")) {
            if (*year < 1970 || *year > 2100)
                error(placeOf(*y), "'year' " + std::to_string(*year) + " is not a plausible year");
            else
                s.year = static_cast<int>(*year);
        }
    } else {
        error(at, "source has no 'year'");
    }
    if (s.talk.empty() && s.code.empty())
        error(at, "source names neither a 'talk' (talk, paper or article) nor 'code' (a source file)");
    if (s.game.empty() && s.engine.empty()) error(at, "source names neither a 'game' nor an 'engine'");
}

void Parser::parseDepth(const toml::table& root, Layout& layout) {
    const toml::node* n = root.get("depth");
    if (!n) {
        error({1, 1}, "the layout has no [depth] table (format = one of " + knownDepthFormatNames() + ")");
        return;
    }
    const toml::table* t = n->as_table();
    if (!t) {
        error(placeOf(*n), "'depth' must be a table, not " + std::string(typeName(*n)));
        return;
    }
    Depth& d = layout.depth;
    d.place = placeOf(*n);
    checkKeys(*t, {"format", "reversed_z", "stencil"}, "[depth]");
    if (auto format = getString(*t, "format", true, d.place, "[depth]")) {
        d.formatPlace = placeOf(*t->get("format"));
        if (const DepthFormatInfo* info = findDepthFormat(*format)) {
            d.format = info->name;
            d.depthBits = info->depthBits;
            d.stencilBits = info->stencilBits;
            d.floatDepth = info->floatDepth;
            d.bytes = info->bytes;
        } else {
            error(d.formatPlace,
                  "unknown depth format " + squote(*format) + " (known: " + knownDepthFormatNames() + ")");
        }
    }
    if (const toml::node* r = t->get("reversed_z")) {
        if (r->is_boolean())
            d.reversedZ = r->as_boolean()->get();
        else
            error(placeOf(*r), "'reversed_z' must be true or false, not " + std::string(typeName(*r)));
    }
    if (const toml::node* s = t->get("stencil")) {
        const toml::array* a = s->as_array();
        if (!a) {
            error(placeOf(*s),
                  "'stencil' must be an array of tables ([[depth.stencil]]), not " + std::string(typeName(*s)));
            return;
        }
        if (!d.format.empty() && d.stencilBits == 0) {
            error(placeOf(*s), "depth format " + d.format +
                                   " has no stencil bits; use D24_UNORM_S8_UINT or "
                                   "D32_SFLOAT_S8_UINT to declare stencil fields");
            return;
        }
        const std::vector<Channel> channels = {{"s", d.stencilBits > 0 ? d.stencilBits : 8, 0, ChannelType::Uint}};
        for (const toml::node& f : *a)
            if (auto field = parseField(f, channels, "stencil", true)) d.stencil.push_back(std::move(*field));
    }
}

void Parser::parseTarget(const toml::node& node, Layout& layout) {
    const toml::table* t = node.as_table();
    if (!t) {
        error(placeOf(node), "each [[target]] must be a table, not " + std::string(typeName(node)));
        return;
    }
    Target target;
    target.place = placeOf(node);
    checkKeys(*t, {"name", "format", "field"}, "[[target]]");
    target.name = getString(*t, "name", true, target.place, "[[target]]").value_or("");
    const std::string where = target.name.empty() ? "[[target]]" : "target " + squote(target.name);
    if (auto format = getString(*t, "format", true, target.place, where)) {
        target.formatPlace = placeOf(*t->get("format"));
        if (const TargetFormatInfo* info = findTargetFormat(*format)) {
            target.format = info->name;
            target.channels = info->channels;
        } else {
            error(target.formatPlace,
                  "unknown format " + squote(*format) + " (known: " + knownTargetFormatNames() + ")");
        }
    }
    if (const toml::node* fields = t->get("field")) {
        if (const toml::array* a = fields->as_array()) {
            for (const toml::node& f : *a)
                if (auto field = parseField(f, target.channels, target.format, false))
                    target.fields.push_back(std::move(*field));
        } else {
            error(placeOf(*fields), "'field' must be an array of tables, not " + std::string(typeName(*fields)));
        }
    } else {
        error(target.place, where + " has no fields: add [[target.field]] tables or field = [ {...}, ... ]");
    }
    layout.targets.push_back(std::move(target));
}

// Reads one field: attribute, encoding (+ transform / interleave), at, bits, value.
std::optional<Field> Parser::parseField(const toml::node& node, const std::vector<Channel>& channels,
                                        const std::string& formatName, bool stencil) {
    const toml::table* t = node.as_table();
    if (!t) {
        error(placeOf(node), "each field must be a table ({ attribute = ..., encoding = ..., at = [...] }), not " +
                                 std::string(typeName(node)));
        return std::nullopt;
    }
    Field field;
    field.place = placeOf(node);
    if (stencil)
        checkKeys(*t, {"attribute", "encoding", "at", "bits", "value"}, "a stencil field");
    else
        checkKeys(*t, {"attribute", "encoding", "transform", "interleave", "at", "bits", "value"}, "a field");

    auto attrName = getString(*t, "attribute", true, field.place, "the field");
    if (!attrName) return std::nullopt;
    const AttributeInfo* attr = findAttribute(*attrName);
    if (!attr) {
        error(placeOf(*t->get("attribute")),
              "unknown attribute " + squote(*attrName) + " (known: " + knownAttributeNames() + ")");
        return std::nullopt;
    }
    field.attribute = attr->id;
    const std::string what = "field " + squote(attr->name);

    // encoding
    const toml::node* encNode = t->get("encoding");
    field.encodingPlace = encNode ? placeOf(*encNode) : field.place;
    if (attr->type == ValueType::Integer) {
        field.encoding = kIdEncoding;
        if (encNode) {
            auto e = getString(*t, "encoding", false, field.place, what);
            if (e && *e != kIdEncoding) {
                error(field.encodingPlace, squote(attr->name) +
                                               " is an integer id: its encoding is 'id' "
                                               "(the declared value is the code), not " +
                                               squote(*e));
                field.incomplete = true;
            }
        }
    } else if (stencil) {
        error(placeOf(*t->get("attribute")),
              "the stencil holds integer extras only; " + squote(attr->name) + " is not one");
        return std::nullopt;
    } else if (auto e = getString(*t, "encoding", true, field.place, what)) {
        std::string resolved = *e;
        const toml::node* trNode = t->get("transform");
        const toml::node* ilNode = t->get("interleave");
        std::optional<std::string> transform, interleave;
        if (trNode) {
            transform = getString(*t, "transform", false, field.place, what);
            if (transform && std::find_if(std::begin(kTransforms), std::end(kTransforms),
                                          [&](const char* k) { return *transform == k; }) == std::end(kTransforms)) {
                error(placeOf(*trNode),
                      "unknown transform " + squote(*transform) + " (known: gloss, cry_smoothness, sqrt)");
                field.incomplete = true;
            }
        }
        if (ilNode) {
            interleave = getString(*t, "interleave", false, field.place, what);
            if (interleave && std::find_if(std::begin(kInterleaves), std::end(kInterleaves),
                                           [&](const char* k) { return *interleave == k; }) == std::end(kInterleaves)) {
                error(placeOf(*ilNode), "unknown interleave " + squote(*interleave) + " (known: checkerboard)");
                field.incomplete = true;
            }
        }
        if (!field.incomplete && (transform || interleave) && !findEncoding(*e)) {
            error(field.encodingPlace, "unknown encoding " + squote(*e) + " (known: " + knownEncodingNames() + ", id)");
            field.incomplete = true;
        }
        if (!field.incomplete && (transform || interleave)) {
            const Variant* match = nullptr;
            for (const Variant& v : kVariants) {
                const bool sameTransform = transform ? (v.transform && *transform == v.transform) : !v.transform;
                const bool sameInterleave = interleave ? (v.interleave && *interleave == v.interleave) : !v.interleave;
                if (*e == v.base && sameTransform && sameInterleave) match = &v;
            }
            if (match) {
                resolved = match->encoding;
            } else {
                std::string list;
                for (const Variant& v : kVariants) {
                    list += list.empty() ? "" : ", ";
                    list += std::string(v.base) + (v.transform ? " + transform " + std::string(v.transform) : "") +
                            (v.interleave ? " + interleave " + std::string(v.interleave) : "");
                }
                error(placeOf(trNode ? *trNode : *ilNode),
                      "encoding " + squote(*e) + " has no such variant (available: " + list + ")");
                field.incomplete = true;
            }
        }
        if (resolved == kIdEncoding) {
            error(field.encodingPlace, "encoding 'id' holds integer extras only; " + squote(attr->name) +
                                           " needs one of: " + knownEncodingNames());
            field.incomplete = true;
        } else if (!field.incomplete && !findEncoding(resolved)) {
            error(field.encodingPlace, "unknown encoding " + squote(*e) + " (known: " + knownEncodingNames() + ", id)");
            field.incomplete = true;
        }
        field.encoding = resolved;
    } else {
        field.incomplete = true;
    }

    // at
    if (const toml::node* at = t->get("at")) {
        field.atPlace = placeOf(*at);
        if (channels.empty()) {
            field.incomplete = true;  // unknown format, reported already
        } else if (const toml::array* a = at->as_array()) {
            if (a->empty()) {
                error(placeOf(*at), what + ": 'at' is empty");
                field.incomplete = true;
            }
            for (const toml::node& p : *a) {
                CodePlace code;
                if (parsePlace(p, channels, formatName, code))
                    field.codes.push_back(std::move(code));
                else
                    field.incomplete = true;
            }
        } else {
            CodePlace code;
            if (parsePlace(*at, channels, formatName, code))
                field.codes.push_back(std::move(code));
            else
                field.incomplete = true;
        }
    } else {
        error(field.place, what + " has no 'at': say where each code goes, e.g. at = [\"r\", \"g\", \"b[7]\"]");
        field.incomplete = true;
    }

    // bits: an optional cross-check of the widths given by 'at'
    if (const toml::node* b = t->get("bits")) {
        std::vector<int> declared;
        if (const toml::array* a = b->as_array()) {
            for (const toml::node& e : *a)
                if (auto v = getInteger(e, "'bits'")) declared.push_back(static_cast<int>(*v));
        } else if (auto v = getInteger(*b, "'bits'")) {
            declared.push_back(static_cast<int>(*v));
        }
        if (!field.incomplete && !declared.empty()) {
            const bool perCode = b->is_array();
            if (perCode && declared.size() != field.codes.size()) {
                error(placeOf(*b), what + ": 'bits' lists " + std::to_string(declared.size()) +
                                       " widths but 'at' places " + std::to_string(field.codes.size()) + " codes");
                field.incomplete = true;
            } else {
                // A single number is the encoding's bits per code: it applies to every code except a
                // fixed-width extra one (normal_xy_zsign's sign bit).
                const EncodingInfo* enc = findEncoding(field.encoding);
                const size_t checked = (!perCode && enc && enc->extraBits > 0 && field.codes.size() > 1)
                                           ? field.codes.size() - 1
                                           : field.codes.size();
                for (size_t i = 0; i < checked; ++i) {
                    const int want = perCode ? declared[i] : declared[0];
                    if (field.codes[i].bits() != want) {
                        error(field.codes[i].place, what + ": 'bits' says " + std::to_string(want) + " but " +
                                                        squote(field.codes[i].text) + " holds " +
                                                        std::to_string(field.codes[i].bits()) + " bits");
                        field.incomplete = true;
                    }
                }
            }
        }
    }

    // value: extras only
    if (const toml::node* v = t->get("value")) {
        if (attr->cls != AttributeClass::Extra) {
            error(placeOf(*v), "'value' is for extra attributes; " + squote(attr->name) + " comes from the surface");
            field.incomplete = true;
        } else if (auto values = getNumbers(*v, what + ": 'value'")) {
            if (values->size() == 1 && attr->components > 1) values->assign(attr->components, values->front());
            if (static_cast<int>(values->size()) != attr->components) {
                error(placeOf(*v), what + ": 'value' has " + std::to_string(values->size()) + " components, " +
                                       squote(attr->name) + " has " + std::to_string(attr->components));
                field.incomplete = true;
            }
            for (double x : *values) {
                if (attr->type == ValueType::Integer && (x != std::floor(x) || x < 0)) {
                    error(placeOf(*v), what + ": 'value' must be a non-negative integer (an id)");
                    field.incomplete = true;
                    break;
                }
                if (attr->type == ValueType::Float && attr->domain == ValueDomain::Unit && (x < 0 || x > 1)) {
                    error(placeOf(*v), what + ": 'value' " + std::to_string(x) + " is outside [0,1]");
                    field.incomplete = true;
                    break;
                }
            }
            field.value = *values;
        } else {
            field.incomplete = true;
        }
    } else if (attr->cls == AttributeClass::Extra) {
        error(field.place,
              what + " needs a 'value': extras hold a constant the layout declares (" + attr->meaning + ")");
        field.incomplete = true;
    }
    return field;
}

// One code's place (grammar in parseCodePlace, layout.cpp).
bool Parser::parsePlace(const toml::node& node, const std::vector<Channel>& channels, const std::string& formatName,
                        CodePlace& out) {
    out.place = placeOf(node);
    if (!node.is_string()) {
        error(out.place, "a place in 'at' must be a string like \"r\", \"b[7]\" or \"a[0:3]\", not " +
                             std::string(typeName(node)));
        return false;
    }
    const std::string problem = parseCodePlace(node.as_string()->get(), channels, formatName, out);
    if (problem.empty()) return true;
    error(out.place, problem);
    return false;
}

void Parser::parseFallbacks(const toml::table& root, Layout& layout) {
    const toml::node* n = root.get("fallback");
    layout.fallbackPlace = {1, 1};
    if (!n) return;
    layout.fallbackPlace = placeOf(*n);
    const toml::table* t = n->as_table();
    if (!t) {
        error(placeOf(*n), "'fallback' must be a table ([fallback]), not " + std::string(typeName(*n)));
        return;
    }
    for (auto&& [key, value] : *t) {
        const FilePlace keyPlace = placeOf(key.source());
        const AttributeInfo* attr = findAttribute(key.str());
        if (!attr) {
            error(keyPlace,
                  "unknown attribute " + squote(key.str()) + " in [fallback] (known: " + knownAttributeNames() + ")");
            continue;
        }
        if (attr->cls != AttributeClass::Shading) {
            error(keyPlace, squote(attr->name) + " takes no fallback: " +
                                (attr->cls == AttributeClass::Extra ? "extras are stored with a declared value"
                                                                    : "unstored, position comes from depth"));
            continue;
        }
        if (attr->id == Attribute::Normal || attr->id == Attribute::Roughness) {
            error(keyPlace, squote(attr->name) + " cannot fall back: every layout must store normal and roughness");
            continue;
        }
        Fallback fb;
        fb.attribute = attr->id;
        fb.place = placeOf(value);
        const std::vector<FallbackKind> allowed = allowedFallbacks(attr->id);
        auto allowedList = [&] {
            std::string list;
            for (FallbackKind k : allowed) list += std::string(list.empty() ? "" : ", ") + fallbackKindName(k);
            return list + (list.empty() ? "" : ", or ") + "a constant";
        };
        // A bad entry is still recorded (incomplete), so that the attribute does not also read as
        // "no fallback declared".
        fb.incomplete = true;
        if (value.is_string()) {
            const std::string word = value.as_string()->get();
            auto kw = std::find_if(std::begin(kFallbackKeywords), std::end(kFallbackKeywords),
                                   [&](const FallbackKeyword& k) { return word == k.name; });
            if (kw == std::end(kFallbackKeywords) ||
                std::find(allowed.begin(), allowed.end(), kw->kind) == allowed.end()) {
                error(fb.place, "unknown fallback " + squote(word) + " for " + squote(attr->name) +
                                    " (allowed: " + allowedList() + ")");
            } else {
                fb.kind = kw->kind;
                fb.incomplete = false;
            }
        } else if (auto values = getNumbers(value, "fallback for " + squote(attr->name))) {
            if (values->size() == 1 && attr->components > 1) values->assign(attr->components, values->front());
            bool ok = true;
            if (static_cast<int>(values->size()) != attr->components) {
                error(fb.place, "fallback for " + squote(attr->name) + " has " + std::to_string(values->size()) +
                                    " components, " + squote(attr->name) + " has " + std::to_string(attr->components));
                ok = false;
            }
            for (double x : *values) {
                const bool inRange = attr->domain == ValueDomain::NonNegative ? x >= 0 : (x >= 0 && x <= 1);
                if (ok && !inRange) {
                    error(fb.place, "fallback for " + squote(attr->name) + ": " + std::to_string(x) + " is outside " +
                                        (attr->domain == ValueDomain::NonNegative ? "[0, inf)" : "[0,1]"));
                    ok = false;
                }
            }
            fb.kind = FallbackKind::Constant;
            fb.value = *values;
            fb.incomplete = !ok;
        }
        layout.fallbacks.push_back(std::move(fb));
    }
    // file order (toml++ iterates keys alphabetically)
    std::stable_sort(layout.fallbacks.begin(), layout.fallbacks.end(), [](const Fallback& a, const Fallback& b) {
        return a.place.line != b.place.line ? a.place.line < b.place.line : a.place.column < b.place.column;
    });
}

void Parser::parseLightBuffers(const toml::table& root, Layout& layout) {
    const toml::node* n = root.get("light_buffer");
    if (!n) return;
    const toml::array* a = n->as_array();
    if (!a) {
        error(placeOf(*n),
              "'light_buffer' must be an array of tables ([[light_buffer]]), not " + std::string(typeName(*n)));
        return;
    }
    for (const toml::node& node : *a) {
        const toml::table* t = node.as_table();
        if (!t) {
            error(placeOf(node), "each [[light_buffer]] must be a table");
            continue;
        }
        LightBuffer lb;
        lb.place = placeOf(node);
        checkKeys(*t, {"name", "format", "holds"}, "[[light_buffer]]");
        lb.name = getString(*t, "name", true, lb.place, "[[light_buffer]]").value_or("");
        const TargetFormatInfo* info = nullptr;
        if (auto format = getString(*t, "format", true, lb.place, "[[light_buffer]]")) {
            info = findTargetFormat(*format);
            if (!info)
                error(placeOf(*t->get("format")),
                      "unknown format " + squote(*format) + " (known: " + knownTargetFormatNames() + ")");
            else {
                lb.format = info->name;
                lb.bytes = info->bits / 8;
            }
        }
        const toml::node* holds = t->get("holds");
        if (!holds) {
            error(lb.place, "[[light_buffer]] has no 'holds' (diffuse_rgb, specular_rgb, specular_luminance)");
        } else {
            std::vector<const toml::node*> items;
            if (const toml::array* ha = holds->as_array())
                for (const toml::node& h : *ha) items.push_back(&h);
            else
                items.push_back(holds);
            int channelsNeeded = 0;
            for (const toml::node* h : items) {
                const std::string word = h->is_string() ? h->as_string()->get() : "";
                if (word == "diffuse_rgb") {
                    lb.holds.push_back(LightQuantity::DiffuseRgb);
                    channelsNeeded += 3;
                } else if (word == "specular_rgb") {
                    lb.holds.push_back(LightQuantity::SpecularRgb);
                    channelsNeeded += 3;
                } else if (word == "specular_luminance") {
                    lb.holds.push_back(LightQuantity::SpecularLuminance);
                    channelsNeeded += 1;
                } else {
                    error(placeOf(*h), "unknown light quantity " + squote(word) +
                                           " (known: diffuse_rgb, specular_rgb, specular_luminance)");
                }
            }
            if (info && channelsNeeded > static_cast<int>(info->channels.size()))
                error(placeOf(*holds), "light buffer " + squote(lb.name) + " holds " + std::to_string(channelsNeeded) +
                                           " channels but " + info->name + " has " +
                                           std::to_string(info->channels.size()));
        }
        layout.lightBuffers.push_back(std::move(lb));
    }
}

bool placeLess(const LayoutDiagnostic& a, const LayoutDiagnostic& b) {
    if (a.place.line != b.place.line) return a.place.line < b.place.line;
    return a.place.column < b.place.column;
}

// Parses, then validates unless the TOML itself is broken; with `path`, also requires the layout's
// name to equal the file's stem (`layouts show NAME` finds NAME.toml). Diagnostics in file order.
Layout readAndCheck(std::string_view text, const std::string& fileName, const std::filesystem::path* path,
                    std::vector<LayoutDiagnostic>& out) {
    Layout layout = parseLayoutUnchecked(text, fileName, out);
    const bool syntaxError = !out.empty() && out.front().message.rfind("TOML syntax error", 0) == 0;
    if (!syntaxError) {
        validateLayout(layout, out);
        const std::string stem = path ? path->stem().string() : "";
        if (path && !layout.name.empty() && layout.name != stem)
            out.push_back({fileName, layout.namePlace,
                           "layout name " + squote(layout.name) + " differs from the file name " + squote(stem) +
                               ": rename one so that `layouts show " + stem + "` finds it"});
    }
    std::stable_sort(out.begin(), out.end(), placeLess);
    return layout;
}

}  // namespace

Layout parseLayoutUnchecked(std::string_view text, const std::string& fileName, std::vector<LayoutDiagnostic>& out) {
    Parser parser(fileName, out);
    return parser.parse(text);
}

std::vector<LayoutDiagnostic> checkLayout(std::string_view text, const std::string& fileName) {
    std::vector<LayoutDiagnostic> out;
    readAndCheck(text, fileName, nullptr, out);
    return out;
}

Layout parseLayout(std::string_view text, const std::string& fileName) {
    std::vector<LayoutDiagnostic> out;
    Layout layout = readAndCheck(text, fileName, nullptr, out);
    if (!out.empty()) throw LayoutError(std::move(out));
    return layout;
}

std::vector<LayoutDiagnostic> checkLayoutFile(const std::filesystem::path& path) {
    std::string text;
    try {
        text = readTextFile(path);
    } catch (const UserError& e) {
        std::string message = e.what();  // "path: why"; the diagnostic adds the path itself
        const std::string prefix = escapeText(path.string()) + ": ";
        if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
        return {{path.string(), {}, message}};
    }
    std::vector<LayoutDiagnostic> out;
    readAndCheck(text, path.string(), &path, out);
    return out;
}

Layout loadLayoutFile(const std::filesystem::path& path) {
    const std::string text = readTextFile(path);
    std::vector<LayoutDiagnostic> out;
    Layout layout = readAndCheck(text, path.string(), &path, out);
    if (!out.empty()) throw LayoutError(std::move(out));
    return layout;
}

}  // namespace gbl
