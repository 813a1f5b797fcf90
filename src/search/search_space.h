#pragma once
// What the layout search chooses per attribute (a Genome): the encoding and its bits, or a
// fallback that derives or fixes the attribute instead of storing it. The menus follow the
// encodings of layouts/README.md; packing the chosen fields into render targets is
// layout_packer.h's job.
#include <cstdint>
#include <string>
#include <vector>

#include "search_rng.h"

namespace gbl::search {

// How the colours the lighting reads (diffuse and specular colour) are obtained.
enum class Workflow : uint8_t {
    Metallic,         // store base_color (+ metallic): diffuse = from_base_color; F0 per SpecularMode
    DiffuseSpecular,  // store diffuse_color and specular_color (CryEngine 3's thin G-buffer)
};

// Metallic workflow only: where F0 comes from.
enum class SpecularMode : uint8_t {
    FromMetallic,  // specular_color = from_metallic (dielectric F0 0.04)
    Scalar,        // store UE4's scalar specular; specular_color = ue4 (0.08 specular)
    Colour,        // store specular_color itself
};

struct Genome {
    // normal: an index into normalEncodings(), bits per code; the stored space (0 world Y-up,
    // 1 world Z-up: where the z-sign and hemisphere encodings lose most differs).
    int normalEncoding = 0;
    int normalBits = 10;
    int normalSpace = 0;
    // roughness: an index into roughnessEncodings().
    int roughnessEncoding = 0;
    int roughnessBits = 8;
    Workflow workflow = Workflow::Metallic;
    // The main colour (base_color, or diffuse_color): an index into colourEncodings().
    int colourEncoding = 0;
    int colourBits = 8;
    // metallic (metallic workflow): bits, 0 = not stored (constant 0: every surface a dielectric).
    int metallicBits = 8;
    SpecularMode specularMode = SpecularMode::FromMetallic;
    int specularBits = 8;  // the scalar, SpecularMode::Scalar
    // specular colour (SpecularMode::Colour or the diffuse/specular workflow).
    int specularColourEncoding = 0;
    int specularColourBits = 8;
    // occlusion: bits, 0 = not stored (constant 1).
    int occlusionBits = 0;
    // An index into depthFormats().
    int depthFormat = 1;
    // The material layers (SearchOptions::layers: only when the scenes carry them; 0 = not stored,
    // decoded "no layer"): coat and coat roughness unorm at coatBits, the coat normal octahedral at
    // coatNormalBits (0: the base normal, as Bevy's coat); sheen colour and roughness unorm at
    // sheenBits; anisotropy strength unorm and direction octahedral at anisotropyBits.
    int coatBits = 0;
    int coatNormalBits = 0;
    int sheenBits = 0;
    int anisotropyBits = 0;
    // The stored layers share one target under a shading-model selector (layouts/README.md,
    // "Shading models"), each pixel keeping its model's layer only, as UE's CustomData; false: each
    // layer in bits of its own.
    bool layerSelector = false;

    bool operator==(const Genome&) const = default;
};

struct EncodingChoice {
    const char* name;  // registry name
    int minBits, maxBits;
    int codes;      // codes per value (scalar encodings: per component, for a 3-component attribute 3)
    int extraBits;  // fixed bits beyond codes * bits (the z sign)
};

const std::vector<EncodingChoice>& normalEncodings();
const std::vector<EncodingChoice>& roughnessEncodings();
// For colours (the main one and the specular one): sRGB at 8 bits, unorm per channel, YCbCr /
// YCoCg full or with checkerboard chroma, luma only.
const std::vector<EncodingChoice>& colourEncodings();

struct DepthChoice {
    const char* format;
    int bytes;
    int depthBits;    // 0: 32-bit float
    bool reversedZ;   // float depth reversed, as engines use it (and the reference: layouts/reference.toml)
};
const std::vector<DepthChoice>& depthFormats();

// Brings every member into its menu's range (after a mutation).
void clampGenome(Genome& g);
// With `layers` (the scenes carry material layers), the layers' choices too; without, the same
// draws from `rng` as before they existed, and no layer stored.
Genome randomGenome(SplitMix64& rng, bool layers = false);
// Changes 1 to 3 choices (an encoding, bits up or down, a fallback instead of storing, ...).
Genome mutateGenome(const Genome& parent, SplitMix64& rng, bool layers = false);

// One line: "normal octahedral 12 (world z-up), roughness unorm 8, base_color srgb8, ...".
std::string describeGenome(const Genome& g);

}  // namespace gbl::search
