#pragma once
// The constraints engines live under, which the search's metrics cannot see; on by default
// (search --search-depth and --min-bits loosen them). Each is named in every found layout's
// header comment and in the search report.
//
//  * Depth keeps a family format: D24_UNORM_S8_UINT or D32_SFLOAT (D32_SFLOAT_S8_UINT counts too,
//    for published layouts). The depth buffer serves passes gbufferlab does not model (shadow
//    receivers, SSAO, SSR, fog, decals, particles' soft intersection), so a saving there is
//    invisible to the objective: D16 was chosen by a FLIP-only search on a scene with buildings
//    100-400 m away. --search-depth lets the search choose D16 too.
//  * Per-attribute minimum bits: each stored attribute's widest code holds at least N bits (the
//    attribute may still be left to a fallback: occlusion 1.0, metallic 0, ...). The defaults are
//    the fewest bits a shipped layout of layouts/ stores the attribute in (every shipped layout
//    stores colours, metallic and specular in 8 bits per channel; normals in 8 or more per code
//    (Crysis 3's best-fit and xy + z sign, URP's snorm); roughness in 7 or more (Crysis 3 and URP
//    gloss)), except occlusion: 4 bits, 16 levels of a term that only scales ambient light, where
//    a 1-bit occlusion passed a search on a scene without baked occlusion. The material layers
//    (searched when the scenes carry them): the fewest bits an engine stores each in (Bevy's 4-bit
//    coat and coat roughness, UE5's CustomData and HDRP's GBuffer2 bytes for the rest).
//  * Free stencil: when the depth format has stencil, at least 4 of its bits stay free. Engines
//    keep run-time flags there for passes gbufferlab does not model (layouts/ue4.toml: receive
//    decals, lighting channels; crysis3-thin.toml: the ambient-volume id and the decal mask;
//    hdrp-lit.toml: HDRP's run-time flags), not surface data.
#include <string>
#include <vector>

#include "search_space.h"

namespace gbl {
struct Layout;
}

namespace gbl::search {

struct MinBits {
    std::string attribute;  // layout attribute name: "normal", "roughness", ...
    int bits = 0;
};

struct EngineConstraints {
    bool searchDepth = false;          // --search-depth: any depth format (D16 included)
    std::vector<MinBits> minBits = defaultMinBits();
    int freeStencilBits = 4;
    static std::vector<MinBits> defaultMinBits();
};

// The attributes --min-bits accepts (those the search stores), in this order.
const std::vector<std::string>& minBitsAttributes();

// `text` as given to --min-bits ("occlusion=4,roughness=6"), applied over `c`'s values. A bad
// entry is a one-line UserError naming --min-bits, the entry and the fix.
void parseMinBits(const std::string& text, EngineConstraints& c);

int minBitsOf(const EngineConstraints& c, const std::string& attribute);  // 0 when unconstrained

// Whether the depth format may be used ("family" formats unless searchDepth).
bool depthAllowed(const std::string& format, const EngineConstraints& c);

// Brings a genome inside the constraints (bits up to the minimum, an encoding that cannot hold
// them replaced by the next that can, the depth format by a family one). Deterministic.
void constrainGenome(Genome& g, const EngineConstraints& c);

// What a layout breaks, one line each (empty: none): checked on the parsed layout itself, not the
// genome, so the test is independent of how the genome was made.
std::vector<std::string> constraintViolations(const Layout& layout, const EngineConstraints& c);

// One line per constraint, for the front files' header comment and the report ("depth: ...").
std::vector<std::string> describeConstraints(const EngineConstraints& c);

// For the journal's key: every constraint the result depends on, without spaces.
std::string constraintsKey(const EngineConstraints& c);

// The fewest bytes per pixel a genome inside the constraints packs into.
int smallestPackedBytes(const EngineConstraints& c);

}  // namespace gbl::search
