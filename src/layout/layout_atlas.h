#pragma once
// The atlas: one row per layout, the same facts whichever view prints it (`gbufferlab layouts
// list`, the report's atlas table in report.html and report.json): its family and engine, year,
// bytes per pixel, and every attribute's bits and encoding (or how it is derived when not
// stored). Rows are grouped by family (Source::family, else the engine, else the game), families
// in order of their earliest year.
//
// Bytes per pixel: a layout whose pipeline writes attributes into render targets counts them as
// "attributes"; any other pipeline kind (e.g. a visibility buffer, whose targets hold triangle and
// instance ids and whose attributes are fetched later) counts its bytes as "ids" and may have no
// attribute rows at all. Nothing here assumes a layout has attribute targets.
#include <string>
#include <vector>

#include "layout.h"

namespace gbl {

struct AtlasAttribute {
    std::string name;      // layout-language name ("normal", "base_color", "flags", ...)
    int bits = 0;          // stored bits (targets + stencil); 0 when not stored
    std::string encoding;  // stored: the encoding(s), "+"-joined; not stored: "derived: <keyword>",
                           // "constant", "forward" or "material pass"
};

struct AtlasEntry {
    std::string layout;  // name
    std::string family;  // what the atlas groups by
    std::string engine;  // "Unreal Engine 5", "Killzone 2 (Guerrilla (PS3))", ...
    std::string title;
    int year = 0;
    int bytesPerPixel = 0;           // G-buffer: targets + depth-stencil
    std::string bytesKind;           // "attributes" or "ids" (see above)
    int lightBufferBytesPerPixel = 0;  // deferred lighting's light buffers, separately
    std::vector<AtlasAttribute> attributes;  // stored ones first (layout order), then the derived shading ones
    // How much of the layout is verified in the engine's source, from a talk, assumed or
    // gbufferlab's own: its entries counted by provenance status (layout.h, provenanceCounts).
    // Entries 0: unknown (a report written before provenance existed).
    ProvenanceCounts provenance;
};

// The layout's family: Source::family, else Source::engine, else Source::game.
std::string atlasFamily(const Layout& layout);

AtlasEntry atlasEntryOf(const Layout& layout);

struct AtlasGroup {
    std::string family;
    std::vector<AtlasEntry> entries;  // by year, then name
};

// Groups by family; families in order of their earliest year, then name.
std::vector<AtlasGroup> groupAtlas(std::vector<AtlasEntry> entries);

// "normal 24 normal_octahedral_unity" style one-line summary of an entry's stored attributes.
std::string atlasAttributeSummary(const AtlasEntry& entry);

}  // namespace gbl
