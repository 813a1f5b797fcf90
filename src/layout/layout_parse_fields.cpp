// A target's fields: attribute, encoding (+ transform / interleave), the places of its codes, bits
// and constant values. Part of the layout parser (layout_parser_detail.h).
#include <algorithm>
#include <cmath>

#include "encoding_registry.h"
#include "layout_parser_detail.h"

namespace gbl::layout_parser {

namespace {

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
    {"unorm", "cry_gloss_power", nullptr, "cry_gloss_power"},
    {"ycbcr", "sqrt", nullptr, "ycbcr_sqrt"},
    {"ycbcr", nullptr, "checkerboard", "ycbcr_checkerboard"},
    {"ycocg", nullptr, "checkerboard", "ycocg_checkerboard"},
};
constexpr const char* kTransforms[] = {"gloss", "cry_smoothness", "cry_gloss_power", "sqrt"};
constexpr const char* kInterleaves[] = {"checkerboard"};

// transform / interleave: the registry encoding that `e` with them spells, or `e` itself when
// neither is given; a bad spelling is reported and marks the field incomplete.
std::string resolveVariant(Parser& p, const toml::table& t, const std::string& e, const std::string& what,
                           Field& field) {
    std::string resolved = e;
    const toml::node* trNode = t.get("transform");
    const toml::node* ilNode = t.get("interleave");
    std::optional<std::string> transform, interleave;
    if (trNode) {
        transform = p.getString(t, "transform", false, field.place, what);
        if (transform && std::find_if(std::begin(kTransforms), std::end(kTransforms),
                                      [&](const char* k) { return *transform == k; }) == std::end(kTransforms)) {
            p.error(placeOf(*trNode),
                    "unknown transform " + squote(*transform) + " (known: gloss, cry_smoothness, cry_gloss_power, sqrt)");
            field.incomplete = true;
        }
    }
    if (ilNode) {
        interleave = p.getString(t, "interleave", false, field.place, what);
        if (interleave && std::find_if(std::begin(kInterleaves), std::end(kInterleaves),
                                       [&](const char* k) { return *interleave == k; }) == std::end(kInterleaves)) {
            p.error(placeOf(*ilNode), "unknown interleave " + squote(*interleave) + " (known: checkerboard)");
            field.incomplete = true;
        }
    }
    if (!field.incomplete && (transform || interleave) && !findEncoding(e)) {
        p.error(field.encodingPlace, "unknown encoding " + squote(e) + " (known: " + knownEncodingNames() + ", id)");
        field.incomplete = true;
    }
    if (!field.incomplete && (transform || interleave)) {
        const Variant* match = nullptr;
        for (const Variant& v : kVariants) {
            const bool sameTransform = transform ? (v.transform && *transform == v.transform) : !v.transform;
            const bool sameInterleave = interleave ? (v.interleave && *interleave == v.interleave) : !v.interleave;
            if (e == v.base && sameTransform && sameInterleave) match = &v;
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
            p.error(placeOf(trNode ? *trNode : *ilNode),
                    "encoding " + squote(e) + " has no such variant (available: " + list + ")");
            field.incomplete = true;
        }
    }
    return resolved;
}

// encoding (+ transform / interleave). False when the field cannot be read on (a stencil field of
// a non-integer attribute).
bool readEncoding(Parser& p, const toml::table& t, const AttributeInfo& attr, const std::string& what, bool stencil,
                  Field& field) {
    const toml::node* encNode = t.get("encoding");
    field.encodingPlace = encNode ? placeOf(*encNode) : field.place;
    if (attr.type == ValueType::Integer) {
        field.encoding = kIdEncoding;
        if (encNode) {
            auto e = p.getString(t, "encoding", false, field.place, what);
            if (e && *e != kIdEncoding) {
                p.error(field.encodingPlace, squote(attr.name) +
                                                 " is an integer id: its encoding is 'id' "
                                                 "(the declared value is the code), not " +
                                                 squote(*e));
                field.incomplete = true;
            }
        }
    } else if (stencil) {
        p.error(placeOf(*t.get("attribute")),
                "the stencil holds integer extras only; " + squote(attr.name) + " is not one");
        return false;
    } else if (auto e = p.getString(t, "encoding", true, field.place, what)) {
        const std::string resolved = resolveVariant(p, t, *e, what, field);
        if (resolved == kIdEncoding) {
            p.error(field.encodingPlace, "encoding 'id' holds integer extras only; " + squote(attr.name) +
                                             " needs one of: " + knownEncodingNames());
            field.incomplete = true;
        } else if (!field.incomplete && !findEncoding(resolved)) {
            p.error(field.encodingPlace, "unknown encoding " + squote(*e) + " (known: " + knownEncodingNames() + ", id)");
            field.incomplete = true;
        }
        field.encoding = resolved;
    } else {
        field.incomplete = true;
    }
    return true;
}

// dither_per_frame: whether the engine's dither takes the frame index (a dithered encoding only)
void readDitherPerFrame(Parser& p, const toml::table& t, Field& field) {
    const toml::node* d = t.get("dither_per_frame");
    if (!d) return;
    const EncodingInfo* enc = findEncoding(field.encoding);
    if (!d->is_boolean()) {
        p.error(placeOf(*d), "'dither_per_frame' must be true or false, not " + std::string(typeName(*d)));
        field.incomplete = true;
    } else if (enc && !enc->dithered) {
        p.error(placeOf(*d), "'dither_per_frame' is for a dithered encoding (normal_octahedral_dithered); " +
                                 squote(field.encoding) + " has no dither: remove the key");
        field.incomplete = true;
    } else {
        field.ditherPerFrame = d->as_boolean()->get();
        field.ditherDeclared = true;
    }
}

// bits: an optional cross-check of the widths given by 'at'
void checkBits(Parser& p, const toml::table& t, const std::string& what, Field& field) {
    const toml::node* b = t.get("bits");
    if (!b) return;
    std::vector<int> declared;
    if (const toml::array* a = b->as_array()) {
        for (const toml::node& e : *a)
            if (auto v = p.getInteger(e, "'bits'")) declared.push_back(static_cast<int>(*v));
    } else if (auto v = p.getInteger(*b, "'bits'")) {
        declared.push_back(static_cast<int>(*v));
    }
    if (field.incomplete || declared.empty()) return;
    const bool perCode = b->is_array();
    if (perCode && declared.size() != field.codes.size()) {
        p.error(placeOf(*b), what + ": 'bits' lists " + std::to_string(declared.size()) +
                                 " widths but 'at' places " + std::to_string(field.codes.size()) + " codes");
        field.incomplete = true;
        return;
    }
    // A single number is the encoding's bits per code: it applies to every code except a
    // fixed-width extra one (normal_xy_zsign's sign bit).
    const EncodingInfo* enc = findEncoding(field.encoding);
    const size_t checked =
        (!perCode && enc && enc->extraBits > 0 && field.codes.size() > 1) ? field.codes.size() - 1 : field.codes.size();
    for (size_t i = 0; i < checked; ++i) {
        const int want = perCode ? declared[i] : declared[0];
        if (field.codes[i].bits() != want) {
            p.error(field.codes[i].place, what + ": 'bits' says " + std::to_string(want) + " but " +
                                              squote(field.codes[i].text) + " holds " +
                                              std::to_string(field.codes[i].bits()) + " bits");
            field.incomplete = true;
        }
    }
}

// value: extras only
void readValue(Parser& p, const toml::table& t, const AttributeInfo& attr, const std::string& what, Field& field) {
    const toml::node* v = t.get("value");
    if (!v) {
        if (attr.cls == AttributeClass::Extra) {
            p.error(field.place,
                    what + " needs a 'value': extras hold a constant the layout declares (" + attr.meaning + ")");
            field.incomplete = true;
        }
        return;
    }
    if (attr.cls != AttributeClass::Extra) {
        p.error(placeOf(*v), "'value' is for extra attributes; " + squote(attr.name) + " comes from the surface");
        field.incomplete = true;
        return;
    }
    auto values = p.getNumbers(*v, what + ": 'value'");
    if (!values) {
        field.incomplete = true;
        return;
    }
    if (values->size() == 1 && attr.components > 1) values->assign(attr.components, values->front());
    if (static_cast<int>(values->size()) != attr.components) {
        p.error(placeOf(*v), what + ": 'value' has " + std::to_string(values->size()) + " components, " +
                                 squote(attr.name) + " has " + std::to_string(attr.components));
        field.incomplete = true;
    }
    for (double x : *values) {
        if (attr.type == ValueType::Integer && (x != std::floor(x) || x < 0)) {
            p.error(placeOf(*v), what + ": 'value' must be a non-negative integer (an id)");
            field.incomplete = true;
            break;
        }
        if (attr.type == ValueType::Float && attr.domain == ValueDomain::Unit && (x < 0 || x > 1)) {
            p.error(placeOf(*v), what + ": 'value' " + std::to_string(x) + " is outside [0,1]");
            field.incomplete = true;
            break;
        }
    }
    field.value = *values;
}

// model (a conditional field) and models (the selector): layouts/README.md, "Shading models".
void readModels(Parser& p, const toml::table& t, const AttributeInfo& attr, const std::string& what, bool stencil,
                Field& field) {
    const toml::node* model = t.get("model");
    const toml::node* models = t.get("models");
    const bool selector = attr.id == Attribute::ShadingModel;
    if (selector && stencil) {
        p.error(field.place, "the shading-model selector lives in a colour target, not in the stencil: the lighting "
                             "pass reads it with the fields it selects");
        field.incomplete = true;
        return;
    }
    if (model && selector) {
        p.error(placeOf(*model), "the selector itself is not conditional: remove 'model' (its 'models' names the "
                                 "models and their ids)");
        field.incomplete = true;
    }
    if (models && !selector) {
        p.error(placeOf(*models), "'models' belongs to the selector (attribute = \"shading_model\"); a field held "
                                  "under some models says model = \"clear_coat\" or model = [...]");
        field.incomplete = true;
    }
    if (selector) {
        if (!models) {
            p.error(field.place, what + " has no 'models': name the models and their ids, e.g. models = { default "
                                        "= 1, clear_coat = 4, cloth = 8 } (known models: " +
                                        knownShadingModelNames() + ")");
            field.incomplete = true;
            return;
        }
        field.selectorPlace = placeOf(*models);
        const toml::table* table = models->as_table();
        if (!table) {
            p.error(placeOf(*models), "'models' must be a table of model = id, not " + std::string(typeName(*models)));
            field.incomplete = true;
            return;
        }
        for (auto&& [key, node] : *table) {
            const ShadingModelInfo* info = findShadingModel(key.str());
            if (!info) {
                p.error(placeOf(key.source()), "unknown shading model " + squote(key.str()) +
                                                   " (known: " + knownShadingModelNames() + ")");
                field.incomplete = true;
                continue;
            }
            auto id = p.getInteger(node, "the id of model " + squote(key.str()));
            if (!id) {
                field.incomplete = true;
                continue;
            }
            if (*id < 0 || *id > 0xffffffffLL) {
                p.error(placeOf(node), "the id of model " + squote(key.str()) + " must be a non-negative integer, not " +
                                           std::to_string(*id));
                field.incomplete = true;
                continue;
            }
            field.selector.push_back({info->id, uint32_t(*id), placeOf(node)});
        }
        // toml++ iterates a table by key; the model table is kept in file order.
        std::stable_sort(field.selector.begin(), field.selector.end(), [](const Field::ModelId& a, const Field::ModelId& b) {
            return a.place.line != b.place.line ? a.place.line < b.place.line : a.place.column < b.place.column;
        });
        return;
    }
    if (!model) return;
    field.modelPlace = placeOf(*model);
    if (stencil) {
        p.error(placeOf(*model), "a stencil field is written per draw, not per pixel: it cannot be conditional on "
                                 "the shading model; remove 'model'");
        field.incomplete = true;
        return;
    }
    auto add = [&](const toml::node& n) {
        if (!n.is_string()) {
            p.error(placeOf(n), "a model in 'model' must be a string (" + knownShadingModelNames() + "), not " +
                                    std::string(typeName(n)));
            field.incomplete = true;
            return;
        }
        const std::string& name = n.as_string()->get();
        const ShadingModelInfo* info = findShadingModel(name);
        if (!info) {
            p.error(placeOf(n), "unknown shading model " + squote(name) + " (known: " + knownShadingModelNames() + ")");
            field.incomplete = true;
            return;
        }
        field.models |= 1u << unsigned(info->id);
    };
    if (const toml::array* a = model->as_array()) {
        if (a->empty()) {
            p.error(placeOf(*model), what + ": 'model' is empty: name the models the field holds its attribute under");
            field.incomplete = true;
        }
        for (const toml::node& n : *a) add(n);
    } else {
        add(*model);
    }
}

}  // namespace

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
        checkKeys(*t, {"attribute", "encoding", "at", "bits", "value", "model", "models", "from", "status", "differs"},
                  "a stencil field");
    else
        checkKeys(*t, {"attribute", "encoding", "transform", "interleave", "at", "bits", "value", "dither_per_frame",
                       "model", "models", "from", "status", "differs"},
                  "a field");
    readProvenance(*t, field.provenance, field.place);

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
    if (!readEncoding(*this, *t, *attr, what, stencil, field)) return std::nullopt;
    readDitherPerFrame(*this, *t, field);
    parsePlaces(*t, channels, formatName, what, field);
    checkBits(*this, *t, what, field);
    readValue(*this, *t, *attr, what, field);
    readModels(*this, *t, *attr, what, stencil, field);
    return field;
}

// at: where each code goes, one place or an array of them.
void Parser::parsePlaces(const toml::table& t, const std::vector<Channel>& channels, const std::string& formatName,
                         const std::string& what, Field& field) {
    const toml::node* at = t.get("at");
    if (!at) {
        error(field.place, what + " has no 'at': say where each code goes, e.g. at = [\"r\", \"g\", \"b[7]\"]");
        field.incomplete = true;
        return;
    }
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

}  // namespace gbl::layout_parser
