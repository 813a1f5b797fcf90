#pragma once
// The CPU codec's compiled form of a Layout, built once per CpuCodec (cpu_codec_plan.cpp): each
// field's encoding resolved to an enum, each code's bit pieces as (word, shift, mask), Surface
// members as float offsets, and fields that do not depend on the pixel folded into per-target
// constant words. The loops in cpu_codec_encode.cpp / cpu_codec_decode.cpp read only this: no
// strings, look-ups or allocations per pixel.
#include <cstdint>
#include <type_traits>
#include <vector>

#include "layout.h"
#include "surface.h"

namespace gbl::codec {

// Surface as an array of floats: Surface members are addressed by their first float.
inline constexpr int kSurfaceFloats = int(sizeof(Surface) / sizeof(float));
static_assert(sizeof(Surface) == 36 * sizeof(float) && std::is_standard_layout_v<Surface>,
              "Surface is 36 packed floats (shaders/surface.glsl), read and written as a float array");

// Pixels per block: the loops run field by field over a block of one row (inputs, codes and the
// decoded Surfaces of a block stay in L1).
inline constexpr int kBlock = 128;

// One per encoding of the registry (src/encoding/encoding_registry.h), plus Id (the integer of an extra).
enum class Codec : uint8_t {
    Id,
    Unorm,
    Snorm,
    Float16,
    Float11,
    Float10,
    Float32,
    Depth24,
    Gloss,
    SmoothnessCry,
    Reflectance,
    ReflectanceBevyWebgl2,
    UnormRoundEven,
    CoatRoughnessBevy,
    UnormSigned,
    UnormSqrt,
    CryGlossPower,
    Kz2LogPower,  // the last scalar (isScalar)
    Srgb8,
    Luma,
    YCbCr,
    YCbCrSqrt,
    YCoCg,
    YCbCrCheckerboard,
    YCoCgCheckerboard,
    NormalXyz,
    NormalBestFit,
    NormalXyZSign,
    NormalSpheremap,
    NormalStereographic,
    NormalOctahedral,
    NormalOctahedralPrecise,
    Gamma22,
    Rgb9e5,
    Float111110,
    NormalOctahedralBevy,
    NormalOctahedralUnity,
    NormalXyFloat16,
    EmissiveAlbedoRatio,       // reads base colour (FieldPlan::reads)
    NormalOctahedralDithered,  // reads the pixel coordinate (gradient noise)
    NormalOctahedralHdrp,
    Srgb8FastHdrp,
    Float111110HdrpAoTag,      // also stores occlusion (FieldPlan::carried: read by encode, set by decode)
    AnisotropyTangentAngleHdrp,  // reads the normal (FieldPlan::reads), stores anisotropy_strength (carried)
    NormalOctahedralDeltaUe,     // reads the coat normal (FieldPlan::reads): UE's bottom normal
};

// Per component of the attribute (one code each) or the whole vec3 (Color and Normal kinds).
bool isScalar(Codec c);
bool isCheckerboard(Codec c);

// A run of a code's bits: word |= ((code >> codeShift) & mask) << shift.
struct Piece {
    int word = 0;
    int shift = 0;
    int codeShift = 0;
    uint32_t mask = 0;
};

struct CodePlan {
    uint32_t bits = 0;  // the primitive's `bits` for this code (Field::bitsOfCode)
    std::vector<Piece> pieces;
};

struct FieldPlan {
    Codec codec = Codec::Unorm;
    int source = -1;      // first float of the attribute in Surface; -1: an extra (no Surface member)
    int components = 0;   // the attribute's Surface components (what decode writes); 0 for extras
    int inputs = 0;       // floats read per pixel: one per code for scalars, 3 for vec3 encodings
    int reads = -1;       // first float of the other attribute the encoding reads (base colour), -1: none
    int carried = -1;     // first float of the attribute the encoding also stores (HDRP's AO tag:
                          // occlusion), read by encode, set by decode; -1: none
    float constant[4] = {0.0f, 0.0f, 0.0f, 0.0f};  // the inputs of an extra (its declared value)
    std::vector<CodePlan> codes;
    // A dither that moves with time (Field::ditherPerFrame) and the frame it encodes
    // (CpuCodecOptions::frameIndex), as the GPU's gblFrameIndex().
    bool ditherPerFrame = false;
    uint32_t frameIndex = 0;
    // A conditional field (Field::models; layouts/README.md, "Shading models"): encoded on pixels
    // whose model m has bit m of `models` (its codes elsewhere 0), decoded where the stored id i has
    // bit i of `ids` (elsewhere the attribute keeps what the fields before, or 0, gave it).
    // 0: every pixel.
    uint32_t models = 0;
    uint32_t ids = 0;
    // The selector: its code is modelIds[the pixel's model].
    bool selector = false;
    uint32_t modelIds[4] = {0, 0, 0, 0};
    uint32_t idValue[4] = {0, 0, 0, 0};  // a conditional integer extra's codes (its declared value)
};

struct TargetPlan {
    int words = 1;                        // 32-bit words per pixel
    uint32_t constantWords[4] = {0, 0, 0, 0};  // folded fields (constant extras), OR-ed into every pixel
    std::vector<FieldPlan> encodeFields;  // fields whose codes depend on the pixel, in layout order
    std::vector<FieldPlan> decodeFields;  // fields of Surface members, in layout order
};

struct FallbackPlan {
    FallbackKind kind = FallbackKind::Constant;
    // An attribute stored under some models only: the fallback applies where the stored id i has
    // no bit i here (0: every pixel, the attribute is not stored at all).
    uint32_t storedIds = 0;
    int dest = 0;        // first float of the attribute in Surface
    int components = 0;
    float value[3] = {0.0f, 0.0f, 0.0f};  // Constant
};

// Deferred lighting: an attribute carried at full precision in the material words.
struct MaterialSlotPlan {
    int dest = 0;            // first float of the attribute in Surface
    int components = 0;      // the attribute's components
    int slotComponents = 0;  // floats it has in the material words
    int firstFloat = 0;      // float index over all material targets (target = /4, channel = %4)
};

// One test of the encoder's rule for the pixel's model (src/layout/shading_models.cpp): the pixel
// is of `model` when some of the `components` Surface floats from `first` is > 0.
struct ModelTest {
    uint32_t model = 0;
    int first = 0;
    int components = 0;
};

struct CodecPlan {
    // The shading-model selector (none: selectorTarget < 0): the named models' tests in the rule's
    // order of preference, and where the selector's code lies (decode reads it before the fields).
    int selectorTarget = -1;
    int selectorWords = 1;
    CodePlan selectorCode;
    std::vector<ModelTest> modelTests;
    std::vector<TargetPlan> targets;
    int materialTargets = 0;
    std::vector<int> materialSource;  // per material float (4 per target): Surface float, or -1 (0)
    std::vector<MaterialSlotPlan> materialSlots;
    std::vector<FallbackPlan> fallbacks;  // in dependency order (orderedFallbacks)
    std::vector<int> unwritten;           // Surface floats no field, slot or fallback sets: decode zeroes them
    // Surface floats encode reads (fields' inputs, material words), by group of 4 floats (bit k:
    // floats 4k .. 4k + 3): encode transposes only these groups of each block.
    uint32_t encodeGroups = 0;
    const char* decodeError = nullptr;    // set when a stored Surface member has no decoder (id)
};

// Throws std::logic_error for what validation rules out (unknown encoding, a code count that does
// not match the encoding, bits beyond the target's words).
CodecPlan compilePlan(const Layout& layout);

// Surface float index of a Surface member (attributeInfo components from there); -1 for extras.
int surfaceOffset(Attribute a);

}  // namespace gbl::codec
