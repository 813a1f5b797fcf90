// Reads a layout file (TOML, via toml++) into the Layout data model. The parser checks structure:
// keys, types and names (attributes, encodings, formats, channels, fallback keywords); the
// semantic checks (bits, code counts, overlaps, coverage) are in layout_validate.cpp. Every problem
// becomes a LayoutDiagnostic with the file, line and column of the offending key or value.
// This file reads the document, its source, depth and targets; fields are read in
// layout_parse_fields.cpp, fallbacks and light buffers in layout_parse_fallbacks.cpp.
#include <algorithm>
#include <cmath>

#include "file_io.h"
#include "layout_parser_detail.h"

namespace gbl {

namespace layout_parser {

Layout Parser::parse(std::string_view text) {
    Layout layout;
    layout.sourceFile = file_;
    toml::table root;
    if (auto unsafe = findTomlPlusPlusHazard(text)) {  // never handed to toml++: see layout_toml_guard.cpp
        error(unsafe->first, std::move(unsafe->second));
        return layout;
    }
    try {
        root = toml::parse(text, file_);
    } catch (const toml::parse_error& e) {
        error(placeOf(e.source()), "TOML syntax error: " + escapeText(e.description()));
        return layout;
    }
    const FilePlace top{1, 1};
    checkKeys(root, {"name", "title", "source", "pipeline", "depth", "target", "fallback", "clear", "light_buffer",
                     "material_pass", "space", "ids", "sources"},
              "the layout");
    parseSources(root, layout);

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
        else if (*pipeline == "visibility-buffer")
            layout.pipeline = Pipeline::VisibilityBuffer;
        else
            error(placeOf(*root.get("pipeline")), "unknown pipeline " + squote(*pipeline) +
                                                      " (known: deferred-shading, deferred-lighting, visibility-buffer)");
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
    } else if (layout.pipeline != Pipeline::VisibilityBuffer) {  // a visibility buffer has only [ids]
        error(top, "the layout has no render target: add a [[target]] table");
    }

    parseFallbacks(root, layout);
    parseClear(root, layout);
    parseLightBuffers(root, layout);
    parseMaterialPass(root, layout);
    parseSpace(root, layout);
    parseIds(root, layout);
    return layout;
}

// [space]: normal = "world" | "view"; up = "y" | "z" (world only); position = "world" | "view"
// (only where position is stored). Whether anything is missing is validation's (layout_validate.cpp).
void Parser::parseSpace(const toml::table& root, Layout& layout) {
    const toml::node* n = root.get("space");
    if (!n) return;
    const toml::table* t = n->as_table();
    SpaceDecl& sp = layout.space;
    if (!t) {
        error(placeOf(*n), "'space' must be a table ([space]), not " + std::string(typeName(*n)));
        sp.declared = sp.normalDeclared = sp.positionDeclared = true;  // reported: no second message
        return;
    }
    sp.declared = true;
    sp.place = placeOf(*n);
    checkKeys(*t, {"normal", "up", "position", "from", "status", "differs"}, "[space]");
    readProvenance(*t, sp.provenance, sp.place);
    bool zUp = false, upGiven = false;
    if (const toml::node* u = t->get("up")) {
        upGiven = true;
        if (auto up = getString(*t, "up", false, sp.place, "[space]")) {
            if (*up == "z")
                zUp = true;
            else if (*up != "y")
                error(placeOf(*u), "unknown up axis " + squote(*up) +
                                       " (known: y, gbufferlab's own; z, CryEngine's and UE4's)");
        }
    }
    auto readSpace = [&](const char* key, bool& declared, StoredSpace& out) {
        const toml::node* k = t->get(key);
        if (!k) return;
        declared = true;
        auto v = getString(*t, key, false, sp.place, "[space]");
        if (!v) return;
        if (*v == "view")
            out = StoredSpace::View;
        else if (*v == "world") {
            if (!upGiven)
                error(placeOf(*k), std::string("'") + key +
                                       "' is \"world\": declare the engine's up axis too (up = \"y\" or \"z\")");
            out = zUp ? StoredSpace::WorldZUp : StoredSpace::WorldYUp;
        } else
            error(placeOf(*k), "unknown " + std::string(key) + " space " + squote(*v) + " (known: world, view)");
    };
    readSpace("normal", sp.normalDeclared, sp.normal);
    readSpace("position", sp.positionDeclared, sp.position);
    if (const toml::node* p = t->get("position")) sp.positionPlace = placeOf(*p);
    if (upGiven && (!sp.normalDeclared || sp.normal == StoredSpace::View) &&
        (!sp.positionDeclared || sp.position == StoredSpace::View))
        error(placeOf(*t->get("up")), "'up' applies to world space only, and nothing here is stored in world space");
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
    checkKeys(*t, {"game", "engine", "family", "talk", "code", "year"}, "source");
    Source& s = layout.source;
    s.game = getString(*t, "game", false, at, "source").value_or("");
    s.engine = getString(*t, "engine", false, at, "source").value_or("");
    s.talk = getString(*t, "talk", false, at, "source").value_or("");
    s.family = getString(*t, "family", false, at, "source").value_or("");
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
    checkKeys(*t, {"format", "reversed_z", "stencil", "from", "status", "differs"}, "[depth]");
    readProvenance(*t, d.provenance, d.place);
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
        d.reversedZPlace = placeOf(*r);
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
    checkKeys(*t, {"name", "format", "field", "from", "status", "differs"}, "[[target]]");
    readProvenance(*t, target.provenance, target.place);
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

}  // namespace layout_parser

namespace {

using namespace layout_parser;

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
    registerInput(path);  // no output may replace it (file_io.h)
    std::vector<LayoutDiagnostic> out;
    Layout layout = readAndCheck(text, path.string(), &path, out);
    if (!out.empty()) throw LayoutError(std::move(out));
    return layout;
}

}  // namespace gbl
