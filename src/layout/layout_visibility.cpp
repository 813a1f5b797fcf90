// The visibility buffer in the layout language (layouts/README.md, "Visibility buffer"): reading
// [ids] and the rules of pipeline = "visibility-buffer". Such a layout stores no attribute: its
// geometry pass writes triangle and draw ids (and depth), and the lighting pass rebuilds the
// Surface from the triangle (Burns & Hunt, "The Visibility Buffer: A Cache-Friendly Approach to
// Deferred Shading", JCGT 2(2), 2013).
#include "layout_parser_detail.h"

namespace gbl {

namespace layout_parser {

// [ids]: format = "R32_UINT" | "R32G32_UINT", triangle_bits, draw_bits (1..32 each),
// alpha_mask_bit = true | false, and Nanite's and Bevy's meshlet keys draw_offset,
// cluster_triangles, depth_word. Whether they fit is validation's (validateVisibilityLayout).
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
    checkKeys(*t,
              {"format", "triangle_bits", "draw_bits", "alpha_mask_bit", "draw_offset", "cluster_triangles",
               "depth_word", "from", "status", "differs"},
              "[ids]");
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
    // Optional integers; whether they fit the widths above is validation's. Read as 64-bit, so a
    // value past 32 bits is an error here, never a silent wrap.
    auto readOptional = [&](const char* key, FilePlace& place) -> std::optional<int64_t> {
        const toml::node* k = t->get(key);
        if (!k) return std::nullopt;
        place = placeOf(*k);
        return getInteger(*k, std::string("'") + key + "'");
    };
    if (auto v = readOptional("draw_offset", ids.drawOffsetPlace)) {
        if (*v < 0 || *v > 0xFFFFFFFFll)
            error(ids.drawOffsetPlace, "'draw_offset' " + std::to_string(*v) +
                                           " must be 0 to 4294967295 (UE's Nanite stores visible cluster + 1: 1)");
        else
            ids.drawOffset = uint32_t(*v);
    }
    if (auto v = readOptional("cluster_triangles", ids.clusterTrianglesPlace)) {
        if (*v < 1 || *v > 0xFFFFFFFFll)
            error(ids.clusterTrianglesPlace, "'cluster_triangles' " + std::to_string(*v) +
                                                 " must be 1 or more (Nanite's and Bevy's clusters: 128)");
        else
            ids.clusterTriangles = uint32_t(*v);
    }
    if (auto v = readOptional("depth_word", ids.depthWordPlace)) {
        if (*v != 1)
            error(ids.depthWordPlace, "'depth_word' " + std::to_string(*v) +
                                          " must be 1: the depth's float bits go in word 1, the high half of the "
                                          "64-bit value, so that a 64-bit max orders by depth first (the ids take "
                                          "word 0)");
        else
            ids.depthWord = 1;
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
    const int room = ids.depthWord >= 0 ? 32 : ids.bits;  // a depth word leaves the ids word 0
    if (ids.depthWord >= 0 && ids.bits != 64) {
        error(ids.depthWordPlace, "'depth_word' needs a second word: set format = \"R32G32_UINT\" (Nanite's "
                                  "R64_UINT / R32G32_UINT fallback, Bevy's R64Uint), not " + ids.format);
    } else if (need > room) {
        error(ids.formatPlace, "ids need " + std::to_string(need) + " bits (" + std::to_string(ids.triangleBits) +
                                   " triangle + " + std::to_string(ids.drawBits) + " draw" +
                                   (ids.alphaMaskBit ? " + 1 alpha-mask flag" : "") + ") but " + ids.format +
                                   (ids.depthWord >= 0 ? " with depth in word 1 leaves word 0, " : " holds ") +
                                   std::to_string(room) + " (" + std::to_string(need - room) + " over)");
    }
    const uint64_t fieldValues = 1ull << ids.drawBits;  // values the draw field holds
    if (ids.drawOffset > 0 && ids.drawOffset >= fieldValues)
        error(ids.drawOffsetPlace, "'draw_offset' " + std::to_string(ids.drawOffset) + " leaves no id: " +
                                       std::to_string(ids.drawBits) + "-bit draw fields hold 0 to " +
                                       std::to_string(fieldValues - 1) + "; use an offset below " +
                                       std::to_string(fieldValues) + " (Nanite's: 1) or more draw_bits");
    const uint64_t triangleValues = 1ull << ids.triangleBits;
    if (ids.clusterTriangles > triangleValues)
        error(ids.clusterTrianglesPlace, "'cluster_triangles' " + std::to_string(ids.clusterTriangles) +
                                             " is more than " + std::to_string(ids.triangleBits) +
                                             "-bit triangle ids hold (" + std::to_string(triangleValues) +
                                             "): use at most " + std::to_string(triangleValues) +
                                             " or more triangle_bits");
    if (ids.depthWord >= 0) {
        // The word holds the depth's float32 bits, resolved by a 64-bit atomic max: the largest
        // value wins, which is the nearest surface only when near is 1 (reversed Z). Cleared to
        // 0, which is then the far plane.
        if (!layout.depth.format.empty() && layout.depth.format != "D32_SFLOAT")  // empty: unknown, reported
            error(layout.depth.formatPlace, "with 'depth_word' the depth is the float32 in word 1 of the ids: set "
                                            "format = \"D32_SFLOAT\", not '" + layout.depth.format + "'");
        if (!layout.depth.reversedZ)
            error(layout.depth.reversedZPlace.line > 0 ? layout.depth.reversedZPlace : layout.depth.place, "with 'depth_word' the ids are resolved by a 64-bit max, which keeps the "
                                      "nearest surface only with reversed Z (near = 1, far = 0): set reversed_z = "
                                      "true (Nanite and Bevy use reversed Z)");
    }
}

}  // namespace gbl
