#include "search_constraints.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <sstream>
#include <utility>
#include <vector>

#include "error.h"
#include "layout.h"
#include "layout_packer.h"

namespace gbl::search {

namespace {

// Depth formats of the layout families in layouts/ (D16 is in none of the shipped ones).
const std::vector<std::string>& familyDepthFormats() {
    static const std::vector<std::string> v = {"D24_UNORM_S8_UINT", "D32_SFLOAT", "D32_SFLOAT_S8_UINT"};
    return v;
}

// The most bits the search's menus store each attribute in (search_space.cpp): a minimum above it
// would leave only fallbacks (or nothing) and is refused.
int searchMaxBits(const std::string& attribute) {
    if (attribute == "normal") return 16;
    if (attribute == "roughness" || attribute == "base_color" || attribute == "diffuse_color" ||
        attribute == "specular_color")
        return 12;
    if (attribute == "coat_normal") return 12;
    return 8;  // metallic, specular, occlusion, the other layers
}

// The first encoding from `index` on (wrapping) whose range reaches `minBits`; `index` itself if none.
int encodingReaching(const std::vector<EncodingChoice>& menu, int index, int minBits) {
    for (size_t k = 0; k < menu.size(); ++k) {
        const size_t i = (size_t(index) + k) % menu.size();
        if (menu[i].maxBits >= minBits) return int(i);
    }
    return index;
}

void raise(const std::vector<EncodingChoice>& menu, int& encoding, int& bits, int minBits) {
    if (minBits <= 0) return;
    encoding = encodingReaching(menu, encoding, minBits);
    const EncodingChoice& e = menu[size_t(encoding)];
    bits = std::clamp(std::max(bits, minBits), e.minBits, e.maxBits);
}

}  // namespace

std::vector<MinBits> EngineConstraints::defaultMinBits() {
    // search_constraints.h says why: the fewest bits a shipped layout stores each in; occlusion 4.
    // The layers (searched when the scenes carry them): the fewest bits an engine stores each in.
    // Bevy's clear coat byte: 4-bit strength, 4-bit roughness (bevyengine/bevy pull request 23359);
    // UE5's ClearCoat bottom normal and Cloth fuzz colour: bytes of CustomData (B8G8R8A8); HDRP's
    // anisotropy and tangent angle: 8 bits each in GBuffer2; the sheen roughness as the sheen colour.
    return {{"normal", 8},         {"roughness", 7},       {"base_color", 8},      {"diffuse_color", 8},
            {"specular_color", 8}, {"metallic", 8},        {"specular", 8},        {"occlusion", 4},
            {"coat", 4},           {"coat_roughness", 4},  {"coat_normal", 8},     {"sheen_color", 8},
            {"sheen_roughness", 8}, {"anisotropy_strength", 8}, {"anisotropy_direction", 8}};
}

const std::vector<std::string>& minBitsAttributes() {
    static const std::vector<std::string> v = {
        "normal",      "roughness",   "base_color",      "diffuse_color",       "specular_color",
        "metallic",    "specular",    "occlusion",       "coat",                "coat_roughness",
        "coat_normal", "sheen_color", "sheen_roughness", "anisotropy_strength", "anisotropy_direction"};
    return v;
}

void parseMinBits(const std::string& text, EngineConstraints& c) {
    std::string known;
    for (const std::string& a : minBitsAttributes()) known += (known.empty() ? "" : ", ") + a;
    if (text.empty())
        throwUserError("--min-bits: empty; give ATTRIBUTE=BITS[,...], e.g. --min-bits occlusion=4,roughness=6");
    std::istringstream in(text);
    std::string entry;
    std::vector<std::pair<std::string, std::string>> given;  // attribute, value: each at most once
    while (std::getline(in, entry, ',')) {
        const size_t eq = entry.find('=');
        if (entry.empty() || eq == std::string::npos)
            throwUserError("--min-bits " + quoteName(text) + ": entry " + quoteName(entry) +
                           " is not ATTRIBUTE=BITS (e.g. occlusion=4)");
        const std::string attribute = entry.substr(0, eq), value = entry.substr(eq + 1);
        if (std::find(minBitsAttributes().begin(), minBitsAttributes().end(), attribute) == minBitsAttributes().end())
            throwUserError("--min-bits " + quoteName(text) + ": unknown attribute " + quoteName(attribute) +
                           " (known: " + known + ")");
        for (const auto& [earlier, earlierValue] : given)
            if (earlier == attribute)
                throwUserError("--min-bits " + quoteName(text) + ": " + attribute + " is given twice (" +
                               escapeText(earlierValue) + " and " + escapeText(value) + "); give each attribute once");
        given.emplace_back(attribute, value);
        char* end = nullptr;
        errno = 0;
        // Digits only: strtol would also take " 8" and "+8".
        const bool digits = !value.empty() && value.size() <= 9 && value.find_first_not_of("0123456789") == std::string::npos;
        const long bits = digits ? std::strtol(value.c_str(), &end, 10) : -1;
        const int most = searchMaxBits(attribute);
        if (!digits || *end != '\0' || errno != 0 || bits < 0 || bits > most)
            throwUserError("--min-bits " + quoteName(text) + ": " + attribute + "=" + escapeText(value) +
                           ": bits must be a whole number from 0 (no minimum) to " + std::to_string(most) +
                           " (the most the search stores " + attribute + " in)");
        for (MinBits& m : c.minBits)
            if (m.attribute == attribute) m.bits = int(bits);
    }
    if (!text.empty() && text.back() == ',')
        throwUserError("--min-bits " + quoteName(text) + ": a trailing comma; give ATTRIBUTE=BITS[,...]");
}

int minBitsOf(const EngineConstraints& c, const std::string& attribute) {
    for (const MinBits& m : c.minBits)
        if (m.attribute == attribute) return m.bits;
    return 0;
}

bool depthAllowed(const std::string& format, const EngineConstraints& c) {
    if (c.searchDepth) return true;
    const auto& v = familyDepthFormats();
    return std::find(v.begin(), v.end(), format) != v.end();
}

void constrainGenome(Genome& g, const EngineConstraints& c) {
    raise(normalEncodings(), g.normalEncoding, g.normalBits, minBitsOf(c, "normal"));
    raise(roughnessEncodings(), g.roughnessEncoding, g.roughnessBits, minBitsOf(c, "roughness"));
    raise(colourEncodings(), g.colourEncoding, g.colourBits,
          minBitsOf(c, g.workflow == Workflow::Metallic ? "base_color" : "diffuse_color"));
    raise(colourEncodings(), g.specularColourEncoding, g.specularColourBits, minBitsOf(c, "specular_color"));
    if (g.metallicBits > 0) g.metallicBits = std::clamp(std::max(g.metallicBits, minBitsOf(c, "metallic")), 1, 8);
    g.specularBits = std::clamp(std::max(g.specularBits, minBitsOf(c, "specular")), 1, 8);
    if (g.occlusionBits > 0) g.occlusionBits = std::clamp(std::max(g.occlusionBits, minBitsOf(c, "occlusion")), 1, 8);
    // A layer stored at all holds its attributes' minimum bits (one width per layer: search_space.h).
    if (g.coatBits > 0)
        g.coatBits = std::clamp(std::max({g.coatBits, minBitsOf(c, "coat"), minBitsOf(c, "coat_roughness")}), 1, 8);
    if (g.coatNormalBits > 0) g.coatNormalBits = std::clamp(std::max(g.coatNormalBits, minBitsOf(c, "coat_normal")), 2, 12);
    if (g.sheenBits > 0)
        g.sheenBits = std::clamp(std::max({g.sheenBits, minBitsOf(c, "sheen_color"), minBitsOf(c, "sheen_roughness")}), 1, 8);
    if (g.anisotropyBits > 0)
        g.anisotropyBits = std::clamp(
            std::max({g.anisotropyBits, minBitsOf(c, "anisotropy_strength"), minBitsOf(c, "anisotropy_direction")}), 2, 8);
    const auto& depths = depthFormats();
    for (size_t k = 0; k < depths.size(); ++k) {
        const size_t i = (size_t(g.depthFormat) + k) % depths.size();
        if (depthAllowed(depths[i].format, c)) {
            g.depthFormat = int(i);
            break;
        }
    }
}

std::vector<std::string> constraintViolations(const Layout& layout, const EngineConstraints& c) {
    std::vector<std::string> out;
    if (!depthAllowed(layout.depth.format, c))
        out.push_back("depth " + layout.depth.format +
                      " is not a layout family's format (D24_UNORM_S8_UINT, D32_SFLOAT, D32_SFLOAT_S8_UINT)");
    for (const MinBits& m : c.minBits) {
        if (m.bits <= 0) continue;
        const AttributeInfo* info = findAttribute(m.attribute);
        if (!info) continue;
        const Field* f = layout.findField(info->id);
        if (!f) continue;  // a fallback: allowed
        int widest = 0;
        for (size_t i = 0; i < f->codes.size(); ++i) widest = std::max(widest, f->bitsOfCode(i));
        if (widest < m.bits)
            out.push_back(m.attribute + " stored in " + std::to_string(widest) + " bits, under the minimum of " +
                          std::to_string(m.bits));
    }
    if (layout.depth.stencilBits > 0) {
        int used = 0;
        for (const Field& f : layout.depth.stencil) used += f.totalBits();
        if (layout.depth.stencilBits - used < c.freeStencilBits)
            out.push_back(std::to_string(layout.depth.stencilBits - used) + " stencil bits free, under the " +
                          std::to_string(c.freeStencilBits) + " engines keep");
    }
    return out;
}

std::vector<std::string> describeConstraints(const EngineConstraints& c) {
    std::vector<std::string> lines;
    if (c.searchDepth)
        lines.push_back("depth: any format (--search-depth; D16 included). The depth buffer also serves shadows, "
                        "SSAO, SSR, fog and decals, which gbufferlab does not model.");
    else
        lines.push_back("depth: a layout family's format (D24_UNORM_S8_UINT or D32_SFLOAT), not D16: the depth "
                        "buffer also serves shadows, SSAO, SSR, fog and decals, which gbufferlab does not model, so "
                        "a saving there is invisible to the metrics (--search-depth lifts this).");
    std::string bits;
    for (const MinBits& m : c.minBits)
        if (m.bits > 0) bits += (bits.empty() ? "" : ", ") + m.attribute + " " + std::to_string(m.bits);
    lines.push_back("minimum bits per stored attribute (its widest code; a fallback instead stays allowed): " +
                    (bits.empty() ? std::string("none") : bits) +
                    ". Defaults: the fewest bits a shipped layout stores each in, occlusion 4, the layers the fewest an engine "
                    "stores them in (--min-bits overrides).");
    lines.push_back("stencil: at least " + std::to_string(c.freeStencilBits) +
                    " bits stay free when the depth format has stencil (engines keep run-time flags there).");
    return lines;
}

std::string constraintsKey(const EngineConstraints& c) {
    std::string bits;
    for (const MinBits& m : c.minBits) bits += (bits.empty() ? "" : ",") + m.attribute + ":" + std::to_string(m.bits);
    return std::string("depth=") + (c.searchDepth ? "any" : "family") + " min-bits=" + bits +
           " free-stencil=" + std::to_string(c.freeStencilBits);
}

int smallestPackedBytes(const EngineConstraints& c) {
    return smallestPackedBytes([&](Genome& g) { constrainGenome(g, c); });
}

}  // namespace gbl::search
