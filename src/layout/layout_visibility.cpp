// The visibility buffer in the layout language (layouts/README.md, "Visibility buffer"): reading
// [ids] and the rules of pipeline = "visibility-buffer". Such a layout stores no attribute: its
// geometry pass writes triangle and draw ids (and depth), and the lighting pass rebuilds the
// Surface from the triangle (Burns & Hunt, "The Visibility Buffer: A Cache-Friendly Approach to
// Deferred Shading", JCGT 2(2), 2013).
#include "layout_parser_detail.h"

namespace gbl {

namespace layout_parser {

// [ids]: format = "R32_UINT" | "R32G32_UINT", triangle_bits, draw_bits (1..32 each),
// alpha_mask_bit = true | false. Whether they fit is validation's (validateVisibilityLayout).
void Parser::parseIds(const toml::table& root, Layout& layout) {
    const toml::node* n = root.get("ids");
    if (!n) return;
    VisibilityIds& ids = layout.ids;
    ids.declared = true;
    ids.place = placeOf(*n);
    const toml::table* t = n->as_table();
    if (!t) {
        error(ids.place, "'ids' must be a table ([ids]), not " + std::string(typeName(*n)));
        return;
    }
    checkKeys(*t, {"format", "triangle_bits", "draw_bits", "alpha_mask_bit", "from", "status", "differs"}, "[ids]");
    readProvenance(*t, ids.provenance, ids.place);
    if (auto format = getString(*t, "format", true, ids.place, "[ids]")) {
        ids.formatPlace = placeOf(*t->get("format"));
        if (*format == "R32_UINT" || *format == "R32G32_UINT") {
            ids.format = *format;
            ids.bits = *format == "R32_UINT" ? 32 : 64;
        } else {
            error(ids.formatPlace, "unknown id format " + squote(*format) +
                                       " (known: R32_UINT, The Forge's 32-bit ids; R32G32_UINT, 64-bit ids)");
        }
    }
    auto readBits = [&](const char* key, int& value, FilePlace& place) {
        const toml::node* k = t->get(key);
        if (!k) {
            error(ids.place, std::string("[ids] has no '") + key + "' (the id's width in bits, 1 to 32)");
            return;
        }
        place = placeOf(*k);
        auto v = getInteger(*k, std::string("'") + key + "'");
        if (!v) return;
        if (*v < 1 || *v > 32) {
            error(place, std::string("'") + key + "' " + std::to_string(*v) + " must be 1 to 32 bits");
            return;
        }
        value = int(*v);
    };
    readBits("triangle_bits", ids.triangleBits, ids.triangleBitsPlace);
    readBits("draw_bits", ids.drawBits, ids.drawBitsPlace);
    if (const toml::node* a = t->get("alpha_mask_bit")) {
        if (a->is_boolean())
            ids.alphaMaskBit = a->as_boolean()->get();
        else
            error(placeOf(*a), "'alpha_mask_bit' must be true or false, not " + std::string(typeName(*a)));
    }
}

}  // namespace layout_parser

void validateVisibilityLayout(const Layout& layout, std::vector<LayoutDiagnostic>& out) {
    auto error = [&](FilePlace place, std::string message) {
        out.push_back({layout.sourceFile, place, std::move(message)});
    };
    const VisibilityIds& ids = layout.ids;
    if (layout.pipeline != Pipeline::VisibilityBuffer) {
        if (ids.declared)
            error(ids.place, "[ids] belongs to pipeline = \"visibility-buffer\"; a G-buffer layout stores attributes "
                             "in [[target]] tables instead");
        return;
    }
    if (!ids.declared) {
        error({1, 1}, "a visibility-buffer layout declares its id target: add [ids] with format = \"R32_UINT\" "
                      "(triangle_bits = 23, draw_bits = 8, alpha_mask_bit = true: The Forge) or \"R32G32_UINT\"");
        return;
    }
    // The lighting pass rebuilds every attribute from the triangle: nothing else may be declared.
    const char* why = ": a visibility-buffer layout stores only ids and depth; its lighting pass rebuilds the Surface "
                      "from the triangle";
    if (!layout.targets.empty()) error(layout.targets.front().place, std::string("remove [[target]]") + why);
    if (!layout.fallbacks.empty() || layout.fallbackPlace.line > 1)
        error(layout.fallbackPlace, std::string("remove [fallback]") + why);
    if (layout.clearDeclared) error(layout.clearPlace, std::string("remove [clear]") + why);
    if (layout.space.declared) error(layout.space.place, std::string("remove [space]") + why);
    if (!layout.lightBuffers.empty()) error(layout.lightBuffers.front().place, std::string("remove [[light_buffer]]") + why);
    if (layout.materialPass.declared) error(layout.materialPass.place, std::string("remove [material_pass]") + why);
    if (!layout.depth.stencil.empty())
        error(layout.depth.stencil.front().place, std::string("remove the stencil fields") + why);
    if (ids.bits == 0 || ids.triangleBits == 0 || ids.drawBits == 0) return;  // reported while parsing
    const int need = ids.triangleBits + ids.drawBits + (ids.alphaMaskBit ? 1 : 0);
    if (need > ids.bits)
        error(ids.formatPlace, "ids need " + std::to_string(need) + " bits (" + std::to_string(ids.triangleBits) +
                                   " triangle + " + std::to_string(ids.drawBits) + " draw" +
                                   (ids.alphaMaskBit ? " + 1 alpha-mask flag" : "") + ") but " + ids.format +
                                   " holds " + std::to_string(ids.bits) + " (" + std::to_string(need - ids.bits) +
                                   " over)");
}

}  // namespace gbl
