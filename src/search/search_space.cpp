#include "search_space.h"

#include <algorithm>

namespace gbl::search {

// Bit ranges are the encodings' valid ranges (encoding_registry.cpp) narrowed to what can pay off
// in a G-buffer of at most a few tens of bytes: fewer than 6 bits per normal code or 3 per colour
// code only ever lose, more than 16 per code cannot fit next to anything else.
const std::vector<EncodingChoice>& normalEncodings() {
    static const std::vector<EncodingChoice> v = {
        {"normal_octahedral", 6, 16, 2, 0},          // Cigolle et al. 2014
        {"normal_octahedral_precise", 6, 16, 2, 0},  // the same, rounding the code that decodes best
        {"normal_xy_zsign", 6, 16, 2, 1},            // CryEngine 3 (Crysis 3)
        {"normal_spheremap", 6, 16, 2, 0},           // Lambert azimuthal (Mittring / Pranckevicius)
        {"normal_stereographic", 6, 16, 2, 0},
        {"normal_xyz", 6, 16, 3, 0},      // n * 0.5 + 0.5, the naive one
        {"normal_bestfit", 8, 8, 3, 0},   // CryEngine 3's best-fit normals (Kaplanyan 2010)
        {"snorm", 6, 16, 3, 0},           // per component
        {"float16", 16, 16, 3, 0},
    };
    return v;
}

const std::vector<EncodingChoice>& roughnessEncodings() {
    static const std::vector<EncodingChoice> v = {
        {"unorm", 3, 12, 1, 0},
        {"gloss", 3, 12, 1, 0},           // 1 - roughness
        {"smoothness_cry", 3, 12, 1, 0},  // 1 - sqrt(roughness): more codes where roughness is small
        {"cry_gloss_power", 8, 8, 1, 0},
    };
    return v;
}

const std::vector<EncodingChoice>& colourEncodings() {
    static const std::vector<EncodingChoice> v = {
        {"srgb8", 8, 8, 3, 0},
        {"unorm", 3, 12, 3, 0},
        {"ycbcr", 3, 12, 3, 0},
        {"ycbcr_sqrt", 3, 12, 3, 0},
        {"ycocg", 3, 12, 3, 0},
        {"ycbcr_checkerboard", 3, 12, 2, 0},  // Crysis 3; Mavridis & Papaioannou 2012
        {"ycocg_checkerboard", 3, 12, 2, 0},
        {"luma", 3, 12, 1, 0},  // reads back grey
    };
    return v;
}

const std::vector<DepthChoice>& depthFormats() {
    static const std::vector<DepthChoice> v = {
        {"D16_UNORM", 2, 16, false},
        {"D24_UNORM_S8_UINT", 4, 24, false},
        {"D32_SFLOAT", 4, 0, true},  // reversed: a unorm depth gains nothing from it, a float one 2^-23 relative
    };
    return v;
}

namespace {

int clampBits(int bits, const EncodingChoice& e) { return std::clamp(bits, e.minBits, e.maxBits); }

// Bits uniform over the menu's range: the search must see both ends of it.
int randomBits(SplitMix64& rng, const EncodingChoice& e) { return rng.range(e.minBits, e.maxBits); }

}  // namespace

void clampGenome(Genome& g) {
    g.normalEncoding = std::clamp(g.normalEncoding, 0, int(normalEncodings().size()) - 1);
    g.normalBits = clampBits(g.normalBits, normalEncodings()[size_t(g.normalEncoding)]);
    g.normalSpace = std::clamp(g.normalSpace, 0, 1);
    g.roughnessEncoding = std::clamp(g.roughnessEncoding, 0, int(roughnessEncodings().size()) - 1);
    g.roughnessBits = clampBits(g.roughnessBits, roughnessEncodings()[size_t(g.roughnessEncoding)]);
    g.colourEncoding = std::clamp(g.colourEncoding, 0, int(colourEncodings().size()) - 1);
    g.colourBits = clampBits(g.colourBits, colourEncodings()[size_t(g.colourEncoding)]);
    g.metallicBits = std::clamp(g.metallicBits, 0, 8);
    g.specularBits = std::clamp(g.specularBits, 1, 8);
    g.specularColourEncoding = std::clamp(g.specularColourEncoding, 0, int(colourEncodings().size()) - 1);
    g.specularColourBits = clampBits(g.specularColourBits, colourEncodings()[size_t(g.specularColourEncoding)]);
    g.occlusionBits = std::clamp(g.occlusionBits, 0, 8);
    g.depthFormat = std::clamp(g.depthFormat, 0, int(depthFormats().size()) - 1);
    // The layers' minimum bits: a unorm code of 1 bit, an octahedral direction of 2 per code
    // (layouts/README.md's ranges); at most 8 and 12.
    g.coatBits = std::clamp(g.coatBits, 0, 8);
    g.coatNormalBits = g.coatBits == 0 ? 0 : std::clamp(g.coatNormalBits, 0, 12);
    if (g.coatNormalBits == 1) g.coatNormalBits = 2;
    g.sheenBits = std::clamp(g.sheenBits, 0, 8);
    g.anisotropyBits = std::clamp(g.anisotropyBits, 0, 8);
    if (g.anisotropyBits == 1) g.anisotropyBits = 2;
    if (g.coatBits + g.sheenBits + g.anisotropyBits == 0) g.layerSelector = false;
}

Genome randomGenome(SplitMix64& rng, bool layers) {
    Genome g;
    g.normalEncoding = rng.below(int(normalEncodings().size()));
    g.normalBits = randomBits(rng, normalEncodings()[size_t(g.normalEncoding)]);
    g.normalSpace = rng.below(2);
    g.roughnessEncoding = rng.below(int(roughnessEncodings().size()));
    g.roughnessBits = randomBits(rng, roughnessEncodings()[size_t(g.roughnessEncoding)]);
    g.workflow = rng.chance(0.5) ? Workflow::Metallic : Workflow::DiffuseSpecular;
    g.colourEncoding = rng.below(int(colourEncodings().size()));
    g.colourBits = randomBits(rng, colourEncodings()[size_t(g.colourEncoding)]);
    g.metallicBits = rng.range(0, 8);
    g.specularMode = SpecularMode(rng.below(3));
    g.specularBits = rng.range(1, 8);
    g.specularColourEncoding = rng.below(int(colourEncodings().size()));
    g.specularColourBits = randomBits(rng, colourEncodings()[size_t(g.specularColourEncoding)]);
    g.occlusionBits = rng.chance(0.5) ? 0 : rng.range(1, 8);
    g.depthFormat = rng.below(int(depthFormats().size()));
    if (layers) {
        g.coatBits = rng.chance(0.3) ? 0 : rng.range(1, 8);
        g.coatNormalBits = rng.chance(0.5) ? 0 : rng.range(2, 12);
        g.sheenBits = rng.chance(0.3) ? 0 : rng.range(1, 8);
        g.anisotropyBits = rng.chance(0.3) ? 0 : rng.range(2, 8);
        g.layerSelector = rng.chance(0.5);
    }
    clampGenome(g);
    return g;
}

Genome mutateGenome(const Genome& parent, SplitMix64& rng, bool layers) {
    Genome g = parent;
    const int changes = 1 + rng.below(3);
    for (int c = 0; c < changes; ++c) {
        // Bits change by one or two more often than encodings: small steps along the front.
        const int step = rng.chance(0.5) ? 1 : 2;
        const int delta = rng.chance(0.5) ? step : -step;
        if (layers && rng.chance(0.25)) {
            switch (rng.below(5)) {
                case 0: g.coatBits = g.coatBits == 0 ? rng.range(1, 8) : (rng.chance(0.3) ? 0 : g.coatBits + delta); break;
                case 1: g.coatNormalBits = g.coatNormalBits == 0 ? rng.range(2, 12) : (rng.chance(0.3) ? 0 : g.coatNormalBits + delta); break;
                case 2: g.sheenBits = g.sheenBits == 0 ? rng.range(1, 8) : (rng.chance(0.3) ? 0 : g.sheenBits + delta); break;
                case 3: g.anisotropyBits = g.anisotropyBits == 0 ? rng.range(2, 8) : (rng.chance(0.3) ? 0 : g.anisotropyBits + delta); break;
                default: g.layerSelector = !g.layerSelector; break;
            }
            continue;
        }
        switch (rng.below(16)) {
            case 0: g.normalEncoding = rng.below(int(normalEncodings().size())); break;
            case 1:
            case 2: g.normalBits += delta; break;
            case 3: g.normalSpace ^= 1; break;
            case 4: g.roughnessEncoding = rng.below(int(roughnessEncodings().size())); break;
            case 5: g.roughnessBits += delta; break;
            case 6: g.workflow = g.workflow == Workflow::Metallic ? Workflow::DiffuseSpecular : Workflow::Metallic; break;
            case 7: g.colourEncoding = rng.below(int(colourEncodings().size())); break;
            case 8: g.colourBits += delta; break;
            case 9: g.metallicBits = g.metallicBits == 0 ? rng.range(1, 8) : (rng.chance(0.3) ? 0 : g.metallicBits + delta); break;
            case 10: g.specularMode = SpecularMode(rng.below(3)); break;
            case 11: g.specularBits += delta; break;
            case 12: g.specularColourEncoding = rng.below(int(colourEncodings().size())); break;
            case 13: g.specularColourBits += delta; break;
            case 14: g.occlusionBits = g.occlusionBits == 0 ? rng.range(1, 8) : (rng.chance(0.3) ? 0 : g.occlusionBits + delta); break;
            default: g.depthFormat = rng.below(int(depthFormats().size())); break;
        }
    }
    // An encoding change keeps the bits where they are valid, else moves them into the range.
    clampGenome(g);
    return g;
}

namespace {
std::string encodingText(const EncodingChoice& e, int bits) {
    return std::string(e.name) + (e.minBits == e.maxBits ? "" : " " + std::to_string(bits));
}
}  // namespace

std::string describeGenome(const Genome& g) {
    std::string s = "normal " + encodingText(normalEncodings()[size_t(g.normalEncoding)], g.normalBits) +
                    (g.normalSpace ? " (world z-up)" : " (world y-up)");
    s += ", roughness " + encodingText(roughnessEncodings()[size_t(g.roughnessEncoding)], g.roughnessBits);
    const std::string colour = encodingText(colourEncodings()[size_t(g.colourEncoding)], g.colourBits);
    const std::string specColour =
        encodingText(colourEncodings()[size_t(g.specularColourEncoding)], g.specularColourBits);
    if (g.workflow == Workflow::Metallic) {
        s += ", base_color " + colour;
        s += g.metallicBits ? ", metallic unorm " + std::to_string(g.metallicBits) : ", metallic 0 (fallback)";
        if (g.specularMode == SpecularMode::FromMetallic) s += ", specular_color from_metallic";
        if (g.specularMode == SpecularMode::Scalar) s += ", specular unorm " + std::to_string(g.specularBits);
        if (g.specularMode == SpecularMode::Colour) s += ", specular_color " + specColour;
    } else {
        s += ", diffuse_color " + colour + ", specular_color " + specColour;
    }
    s += g.occlusionBits ? ", occlusion unorm " + std::to_string(g.occlusionBits) : ", occlusion 1 (fallback)";
    s += std::string(", depth ") + depthFormats()[size_t(g.depthFormat)].format;
    if (g.coatBits)
        s += ", coat unorm " + std::to_string(g.coatBits) +
             (g.coatNormalBits ? " + coat_normal octahedral " + std::to_string(g.coatNormalBits) : "");
    if (g.sheenBits) s += ", sheen unorm " + std::to_string(g.sheenBits);
    if (g.anisotropyBits) s += ", anisotropy unorm + octahedral " + std::to_string(g.anisotropyBits);
    if (g.layerSelector) s += " (layers under a shading-model selector)";
    return s;
}

}  // namespace gbl::search
