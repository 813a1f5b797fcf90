#pragma once
// The registry of encodings a layout file may name (lowercase snake_case, e.g. "normal_octahedral").
// One entry per encoding primitive pair in shaders/encodings.glsl and src/encoding/encodings.h.
//
// Kinds say what an encoding consumes:
//   Normal: a unit vec3, encoded as a whole (codeCount codes of `bits` bits, plus extraBits).
//   Color:  an RGB vec3 in [0,1]^3, encoded as a whole (e.g. YCbCr: 3 codes; luma: 1 code).
//   Scalar: one float, applied to each component of an attribute independently (1 code each).
#include <string>
#include <string_view>
#include <vector>

namespace gbl {

enum class AttributeKind { Normal, Color, Scalar };

struct EncodingInfo {
    std::string name;         // layout-language name, lowercase snake_case
    AttributeKind kind;
    int codeCount;            // integer codes produced per encoded value (per component for Scalar)
    int defaultBits;          // bits per code when a layout gives none
    int minBits;              // valid range of bits per code (minBits == maxBits: fixed)
    int maxBits;
    int extraBits;            // fixed bits beyond codeCount*bits (normal_xy_zsign: the z sign bit)
    bool needsNeighbours;     // decodes from an image + pixel (chroma checkerboard), not one word
    std::string inputRange;   // what the encoder expects, e.g. "[0,1]", "unit vector"
    std::string description;
    std::string source;       // paper / talk / spec it follows
    // Another attribute of the same pixel the encoding reads (layout-language name, "" for none):
    // emissive_albedo_ratio stores emissive relative to base_color's luminance and decodes it from
    // the decoded base_color, so the layout must store base_color in a field before it;
    // anisotropy_angle_hdrp stores the tangent's angle in the frame of the normal.
    std::string reads = {};
    bool dithered = false;    // the encoder adds noise that is a function of the pixel coordinate
    // Another attribute the encoding also stores (layout-language name, "" for none): the encoder
    // reads its unquantised value, the decoder sets it, and the layout counts it as stored by this
    // field. float11_11_10_hdrp_ao_tag stores occlusion in HDRP's AO tag where emissive is 0;
    // anisotropy_angle_hdrp the signed anisotropy (anisotropy_strength) with the angle.
    // An encoding may both read one attribute and carry another.
    std::string carries = {};
};

// All encodings, in a stable order (scalars, colours, normals).
const std::vector<EncodingInfo>& listEncodings();

// nullptr when unknown.
const EncodingInfo* findEncoding(std::string_view name);

// "unorm, snorm, float16, ..." for error messages ("unknown encoding 'x' (known: ...)").
std::string knownEncodingNames();

// Total stored bits for one encoded value with `bits` per code: codeCount * bits + extraBits.
int encodingTotalBits(const EncodingInfo& info, int bits);

// True when bits lies in [minBits, maxBits].
bool encodingBitsValid(const EncodingInfo& info, int bits);

// "normal" / "color" / "scalar".
const char* attributeKindName(AttributeKind kind);

}  // namespace gbl
