#include "layout_atlas.h"

#include <algorithm>
#include <map>

#include "encoding_registry.h"

namespace gbl {

namespace {

// Encodings of every field storing `a`, "+"-joined in layout order, each once.
std::string encodingsOf(const Layout& layout, Attribute a) {
    std::vector<std::string> seen;
    auto visit = [&](const std::vector<Field>& fields) {
        for (const Field& f : fields)
            if (f.attribute == a && std::find(seen.begin(), seen.end(), f.encoding) == seen.end())
                seen.push_back(f.encoding);
    };
    for (const Target& t : layout.targets) visit(t.fields);
    visit(layout.depth.stencil);
    std::string s;
    for (const std::string& e : seen) s += (s.empty() ? "" : "+") + e;
    return s;
}

std::string derivedText(const Fallback& f) {
    switch (f.kind) {
        case FallbackKind::Constant: return "constant";
        case FallbackKind::Forward: return "forward";
        case FallbackKind::MaterialPass: return "material pass";
        default: return std::string("derived: ") + fallbackKindName(f.kind);
    }
}

}  // namespace

std::string atlasFamily(const Layout& layout) {
    const Source& s = layout.source;
    if (!s.family.empty()) return s.family;
    return s.engine.empty() ? s.game : s.engine;
}

AtlasEntry atlasEntryOf(const Layout& layout) {
    AtlasEntry e;
    e.layout = layout.name;
    e.family = atlasFamily(layout);
    const Source& s = layout.source;
    e.engine = s.game.empty() ? s.engine : s.engine.empty() ? s.game : s.game + " (" + s.engine + ")";
    e.title = layout.title;
    e.year = s.year;
    e.bytesPerPixel = bytesPerPixel(layout);
    const bool attributeTargets =
        layout.pipeline == Pipeline::DeferredShading || layout.pipeline == Pipeline::DeferredLighting;
    e.bytesKind = attributeTargets ? "attributes" : "ids";
    e.lightBufferBytesPerPixel = lightBufferBytesPerPixel(layout);
    e.provenance = provenanceCounts(layout);
    for (const AttributeBits& ab : bitsPerAttribute(layout))
        e.attributes.push_back({attributeName(ab.attribute), ab.bits, encodingsOf(layout, ab.attribute)});
    // What an encoding stores besides its attribute (HDRP's AO tag: occlusion, in the tag's g code).
    for (const Target& t : layout.targets)
        for (const Field& f : t.fields) {
            const EncodingInfo* enc = findEncoding(f.encoding);
            if (!enc || enc->carries.empty() || f.codes.size() < 2) continue;
            e.attributes.push_back({enc->carries, f.codes[1].bits(), f.encoding + " (in " + attributeName(f.attribute) + ")"});
        }
    for (const AttributeInfo& info : listAttributes()) {
        if (info.cls != AttributeClass::Shading || layout.stores(info.id)) continue;
        if (const Fallback* f = layout.findFallback(info.id)) e.attributes.push_back({info.name, 0, derivedText(*f)});
    }
    return e;
}

std::vector<AtlasGroup> groupAtlas(std::vector<AtlasEntry> entries) {
    std::map<std::string, AtlasGroup> byFamily;
    for (AtlasEntry& e : entries) {
        AtlasGroup& g = byFamily[e.family];
        g.family = e.family;
        g.entries.push_back(std::move(e));
    }
    std::vector<AtlasGroup> groups;
    for (auto& [family, g] : byFamily) {
        std::sort(g.entries.begin(), g.entries.end(), [](const AtlasEntry& a, const AtlasEntry& b) {
            return a.year != b.year ? a.year < b.year : a.layout < b.layout;
        });
        groups.push_back(std::move(g));
    }
    std::sort(groups.begin(), groups.end(), [](const AtlasGroup& a, const AtlasGroup& b) {
        const int ya = a.entries.front().year, yb = b.entries.front().year;
        return ya != yb ? ya < yb : a.family < b.family;
    });
    return groups;
}

std::string atlasAttributeSummary(const AtlasEntry& entry) {
    std::string s;
    for (const AtlasAttribute& a : entry.attributes) {
        if (a.bits == 0) continue;
        s += (s.empty() ? "" : ", ") + a.name + " " + std::to_string(a.bits) + " " + a.encoding;
    }
    return s.empty() ? "-" : s;
}

}  // namespace gbl
