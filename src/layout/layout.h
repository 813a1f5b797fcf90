#pragma once
// The data model of a G-buffer layout, as read from a layouts/*.toml file (layouts/README.md is
// the language reference). A layout is data: which attributes of the Surface it stores, through
// which encoding (src/encoding/encoding_registry.h), in which bits of which channel of which render target;
// the depth(-stencil) format and what its stencil bits hold; a declared fallback for every
// shading attribute it does not store; for deferred lighting, the light buffers.
//
// Bits: a target's pixel is a little-endian bit string; channel c occupies bits
// [offset, offset + bits) of it (R8G8B8A8: r = 0..7, g = 8..15, ...; A2B10G10R10_PACK32:
// r = 0..9, ..., a = 30..31). A code is placed in one or more bit ranges of channels, its low bits
// in the first range. Every placement is integer-only: shifts and masks, no float conversion.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "error.h"

namespace gbl {

// ---------------------------------------------------------------------------------------------
// Attributes: the names a layout file uses. The shading ones are the members of Surface
// (shaders/surface.glsl); "extras" carry no shading meaning in gbufferlab but take bits, exactly
// as in the engine the layout comes from, and hold a constant the layout declares.

enum class Attribute : uint8_t {
    // shading (Surface members)
    Normal,         // vec3, world space, unit
    BaseColor,      // vec3, linear [0,1]
    Metallic,       // [0,1]
    Roughness,      // perceptual [0,1]; GGX alpha = roughness^2
    Specular,       // UE4 scalar [0,1]; dielectric F0 = 0.08 * specular
    SpecularColor,  // vec3 F0, linear [0,1]
    DiffuseColor,   // vec3 Lambert albedo = base_color * (1 - metallic)
    Occlusion,      // [0,1], ambient occlusion
    Emissive,       // vec3 linear radiance >= 0
    // shading, the material layers of glTF's PBR extensions: optional, a layout that does not store
    // one decodes it as "no layer" (0), the layer dropped as an engine without it drops it
    Coat,                 // KHR_materials_clearcoat clearcoat, [0,1]
    CoatRoughness,        // clearcoatRoughness, perceptual [0,1]
    CoatNormal,           // vec3 unit, the coat's normal (0 = the base normal)
    SheenColor,           // vec3 KHR_materials_sheen sheenColor, linear [0,1]
    SheenRoughness,       // sheenRoughness, perceptual [0,1]
    AnisotropyStrength,   // KHR_materials_anisotropy strength, [0,1]
    AnisotropyDirection,  // vec3 unit tangent the highlight stretches along (0 = none)
    // geometry
    Position,  // vec3 view-space position; when not stored, reconstructed from depth
    Depth,     // window-space depth (gl_FragCoord.z) the lighting reads instead of the depth attachment
    // extras
    Translucency,
    SssProfile,
    ShadingModelId,
    SelectiveOutputMask,
    PerObject,
    AmbientId,
    Decals,
    Indoor,
    PerProject,
    CustomData,
    PrecomputedShadow,
    MaterialFeature,
    CoatMask,
    Flags,
    Velocity,
    Tangent,
    Anisotropy,
    PassId,
    SunOcclusion,
    ShadingModelFloat,
    LightIntensity,
    PrecomputedIrradiance,
    Opacity,
    SubsurfaceColor,
    IsLightmap,
    SpecularOcclusion,
    // the shading-model selector (layouts/README.md, "Shading models"): an id per pixel, the model
    // the encoder picked from the Surface's layers; it says which conditional fields hold the pixel
    ShadingModel,
};

// Selector: the shading-model selector's class, neither a shading value nor a declared constant.
enum class AttributeClass : uint8_t { Shading, Geometry, Extra, Selector };
enum class ValueType : uint8_t { Float, Integer };
// What values an attribute's components take (used to reject encodings that cannot hold them).
enum class ValueDomain : uint8_t { Unit, Signed, NonNegative, Any, Id };

struct AttributeInfo {
    Attribute id;
    const char* name;  // layout-language name, snake_case
    int components;
    AttributeClass cls;
    ValueType type;
    ValueDomain domain;
    const char* meaning;  // one line: what it is and where it comes from
};

const std::vector<AttributeInfo>& listAttributes();
const AttributeInfo& attributeInfo(Attribute a);
const char* attributeName(Attribute a);
const AttributeInfo* findAttribute(std::string_view name);  // nullptr when unknown
std::string knownAttributeNames();                          // "normal, base_color, ..."
bool isShadingAttribute(Attribute a);
// The layers' attributes (Coat .. AnisotropyDirection): shading attributes a layout need not store
// nor give a fallback; unstored, they decode as 0 ("no layer").
bool isLayerAttribute(Attribute a);
// The material layer a layer attribute belongs to, as scene.h's kLayer* and brdf_layers.glsl's
// GBL_LAYER_* bits: 1 clear coat (coat, coat_roughness, coat_normal), 2 sheen, 4 anisotropy; 0 for
// every other attribute.
int attributeLayerBit(Attribute a);
// Unit vectors stored like the normal, in the layout's [space]: normal, coat_normal,
// anisotropy_direction (normal encodings take them).
bool isDirectionAttribute(Attribute a);

// ---------------------------------------------------------------------------------------------
// Shading models (layouts/README.md, "Shading models: the selector"; src/layout/shading_models.cpp
// is the one statement of the encoder's rule, which the generated GLSL and the CPU codec both take).
// A layout's selector field stores, per pixel, the id of one of these models; a conditional field
// (Field::models) holds its attribute only on pixels of the models it names.

enum class ShadingModel : uint8_t { Default, ClearCoat, Cloth, Anisotropic };
inline constexpr int kShadingModels = 4;
// The selector's widest place: ids 0..31, so a set of ids is one 32-bit mask (UE's id takes 4 bits,
// HDRP's feature id 3).
inline constexpr int kMaxSelectorBits = 5;

struct ShadingModelInfo {
    ShadingModel id;
    const char* name;  // layout-language name: "default", "clear_coat", "cloth", "anisotropic"
    // The layer whose presence picks the model: some component of this Surface attribute > 0.
    // Default has none (Attribute::Normal, unused).
    Attribute test;
    const char* meaning;
};
// In the encoder's order of preference: clear_coat, cloth, anisotropic, then default.
const std::vector<ShadingModelInfo>& listShadingModels();
const ShadingModelInfo& shadingModelInfo(ShadingModel m);
const ShadingModelInfo* findShadingModel(std::string_view name);  // nullptr when unknown
std::string knownShadingModelNames();  // "default, clear_coat, cloth, anisotropic"
// "clear_coat", "clear_coat, cloth" for a mask of models (bit m = ShadingModel m).
std::string shadingModelNames(uint32_t models);

// ---------------------------------------------------------------------------------------------
// Formats

// How the real (native) format interprets a channel. The default render path writes UINT targets
// of the same size and ignores this; the native-formats mode and validation use it.
enum class ChannelType : uint8_t { Unorm, Srgb, Sfloat, Ufloat, Uint };

struct Channel {
    std::string name;  // "r", "g", "b", "a"; "s" for stencil
    int bits = 0;
    int offset = 0;  // first bit of the channel in the pixel's bit string
    ChannelType type = ChannelType::Unorm;
};

struct TargetFormatInfo {
    std::string name;               // Vulkan name without VK_FORMAT_, e.g. "A2B10G10R10_UNORM_PACK32"
    std::vector<Channel> channels;  // in bit order
    int bits = 0;                   // bits per pixel
    std::string uintFormat;         // what the bit-exact path renders: R8_UINT, R16_UINT, R32_UINT,
                                    // R32G32_UINT or R32G32B32A32_UINT, by pixel size
};

const std::vector<TargetFormatInfo>& listTargetFormats();
const TargetFormatInfo* findTargetFormat(std::string_view name);
std::string knownTargetFormatNames();

struct DepthFormatInfo {
    std::string name;  // "D24_UNORM_S8_UINT", ...
    int depthBits = 0;
    int stencilBits = 0;
    bool floatDepth = false;
    int bytes = 0;  // nominal bytes per pixel: depth + stencil (D32_SFLOAT_S8_UINT = 5; many GPUs
                    // store its stencil in a separate 1-byte plane, some pad to 8)
};

const std::vector<DepthFormatInfo>& listDepthFormats();
const DepthFormatInfo* findDepthFormat(std::string_view name);
std::string knownDepthFormatNames();

// ---------------------------------------------------------------------------------------------
// The layout

struct FilePlace {
    int line = 0;  // 1-based; 0 = unknown
    int column = 0;
};

// ---------------------------------------------------------------------------------------------
// Provenance (layouts/README.md, "Provenance"): where each entry of a layout comes from. A file
// names its citations once, in a top-level [sources] table (a repository path at a pinned commit,
// or a talk, paper or article), and every entry (depth, each target, field, fallback, clear value,
// [space], [ids], light buffer, [material_pass]) says `from = "key:line"` and `status`. A layout
// that declares [sources] (every file in layouts/) must give it on every entry; a user's own
// layout without [sources] need not cite anything.

enum class ProvenanceStatus : uint8_t {
    None,      // not given
    Verified,  // "verified": read in the engine's source code, at a pinned commit
    Talk,      // "talk": stated by a talk, paper or article (slides, pages), not code
    Lineage,   // "lineage": read in the code of a later version of the same engine, not the one
               // the layout describes (CryENGINE V's source for the CryENGINE 3 talks' rows)
    Assumed,   // "assumed": neither states it; the layout assumes it (say why in a comment)
    Own,       // "own": gbufferlab's own choice; the entry claims no engine (synthetic layouts)
};
const char* provenanceStatusName(ProvenanceStatus s);  // "verified", ..., "" for None

enum class CitationKind : uint8_t {
    Code,  // a file of a repository at a commit: locators are line numbers or a symbol
    Talk,  // a talk, paper or article: locators are slides (or pages, `unit = "page"`)
};

// One entry of [sources].
struct Citation {
    std::string key;  // the name entries cite it by
    CitationKind kind = CitationKind::Code;
    std::string repo, commit, path;  // code: "owner/name", 7..40 hex digits, a path in the repository
    std::string title, authors, venue, url;  // talk
    bool pages = false;  // talk: locators count pages (unit = "page"), not slides
    int slide = 0, page = 0;  // talk: the one slide or page it cites (0: none; the locator says)
    std::string version;  // optional: what the commit is, e.g. "UE 5.3.2" or "HDRP 13.0.0"
    std::string in;       // code: the citation whose repository and commit this file is read at
    FilePlace place, inPlace;
    bool incomplete = false;  // a parse error was reported for it: entries citing it are not checked
                              // against it again (never in a Layout that parseLayout returns)
    std::string text() const;  // one line: "Mephisto1024/Toon_Engine@1a10ef19 Engine/.../GBufferInfo.cpp (UE 5.3.2)"
};

// One citation in an entry's `from`: the key and what of it ("705", "686-705", "EncodeGBuffer").
struct CitationRef {
    std::string key;
    std::string locator;  // "" when the entry cites the whole source
    FilePlace place;      // of the key, inside the `from` string
};

struct Provenance {
    ProvenanceStatus status = ProvenanceStatus::None;
    std::string from;                // as written: "gbi:427; sgu:1833"
    std::vector<CitationRef> refs;   // from, parsed
    std::string differs;             // a known difference between the engine and this entry ("" none)
    FilePlace place;                 // the entry (a missing provenance is reported here)
    FilePlace statusPlace, fromPlace;
    bool given() const { return status != ProvenanceStatus::None; }
};

// One contiguous run of bits inside one channel: bits [first, first + count) of channel `channel`.
struct BitRange {
    int channel = 0;  // index into Target::channels (or the stencil channel, index 0)
    int first = 0;
    int count = 0;
};

// Where one code goes: one or more bit ranges, the code's lowest bits in pieces[0].
struct CodePlace {
    std::vector<BitRange> pieces;
    std::string text;  // as written, e.g. "b[0:6]" or "r + b[0:3]"
    FilePlace place;
    int bits() const;
};

// The name "id" is the layout-level encoding of integer extras: the declared integer is the code.
inline constexpr const char* kIdEncoding = "id";

struct Field {
    Attribute attribute = Attribute::Normal;
    std::string encoding;          // a registry name (after resolving transform/interleave) or "id"
    std::vector<CodePlace> codes;  // in the encoding's code order (see codeLabel)
    std::vector<double> value;     // extras: the declared constant, one per component
    FilePlace place;               // the field's table
    FilePlace encodingPlace;       // the "encoding" value (or the field when implicit)
    FilePlace atPlace;             // the "at" value
    Provenance provenance;
    // A dithered encoding (EncodingInfo::dithered): whether the dither takes the frame index, as
    // the engine's does or not (`dither_per_frame`; default false: a pattern fixed in screen space).
    // compare --temporal N then gives frame k's index to the encoder.
    bool ditherPerFrame = false;
    bool ditherDeclared = false;   // the key was given
    bool incomplete = false;       // a parse error was reported for it: validation skips it
                                   // (never set in a Layout that parseLayout returns)
    // A conditional field (`model = ...`): bit m set for each ShadingModel m it holds its attribute
    // under; 0: an unconditional field, written and read on every pixel.
    uint32_t models = 0;
    FilePlace modelPlace;  // the "model" value
    // The selector (attribute shading_model): its `models` table, model -> id, in file order.
    struct ModelId {
        ShadingModel model = ShadingModel::Default;
        uint32_t id = 0;
        FilePlace place;
    };
    std::vector<ModelId> selector;
    FilePlace selectorPlace;  // the "models" value
    bool conditional() const { return models != 0; }

    // Bits of the encoding's main codes (the primitive's `bits` parameter). For per-component
    // (scalar) encodings each component may differ: bitsOfCode(i).
    int bitsOfCode(size_t i) const { return codes[i].bits(); }
    int totalBits() const;
};

struct Target {
    std::string name;
    std::string format;
    std::vector<Channel> channels;
    std::vector<Field> fields;
    FilePlace place;
    FilePlace formatPlace;
    int bits() const;
    Provenance provenance;
    int bytes() const { return bits() / 8; }
    int usedBits() const;
};

struct Depth {
    std::string format;
    int depthBits = 0;
    int stencilBits = 0;
    bool floatDepth = false;
    int bytes = 0;
    bool reversedZ = false;
    std::vector<Field> stencil;  // integer extras placed in channel "s"
    Provenance provenance;
    FilePlace place;
    FilePlace formatPlace;
    FilePlace reversedZPlace;  // line 0 where reversed_z is not given
};

enum class Pipeline : uint8_t { DeferredShading, DeferredLighting, VisibilityBuffer };
const char* pipelineName(Pipeline p);  // "deferred-shading" / "deferred-lighting" / "visibility-buffer"

// A visibility buffer's id target ([ids], pipeline = "visibility-buffer"; Burns & Hunt, JCGT 2013):
// the geometry pass stores, per pixel, which triangle of which draw is visible, and the lighting
// pass rebuilds the Surface from the triangle (shaders/visibility_resolve.glsl). The ids fill one
// little-endian bit string: the triangle id from bit 0, the draw id above it, and, with
// alphaMaskBit, the top bit flags an alpha-tested draw (The Forge's packVisBufData: 23-bit
// triangle, 8-bit draw, bit 31 for alpha-tested geometry, in R32_UINT).
struct VisibilityIds {
    bool declared = false;
    std::string format;         // "R32_UINT" or "R32G32_UINT"
    int bits = 0;               // 32 or 64
    int triangleBits = 0;       // 1..32
    int drawBits = 0;           // 1..32
    bool alphaMaskBit = false;  // the top bit (bits - 1)
    // Nanite's and Bevy's meshlet visibility buffers (layouts/README.md, "Visibility buffer"):
    // drawOffset is added to the draw field (UE stores visible cluster + 1, so 0 = no geometry);
    // clusterTriangles > 0 makes the draw field a cluster's index: every draw is split into
    // clusters of that many triangles (cluster c of a draw holds its triangles [c n, c n + n)),
    // and the triangle field is the triangle within its cluster; depthWord 1 puts the float bits
    // of the window depth in word 1 (the 64-bit value's high half: what a 64-bit atomic max
    // orders first), and the resolve reads depth from there. -1: no depth word.
    uint32_t drawOffset = 0;
    uint32_t clusterTriangles = 0;
    int depthWord = -1;
    FilePlace place, formatPlace, triangleBitsPlace, drawBitsPlace, drawOffsetPlace, clusterTrianglesPlace,
        depthWordPlace;
    Provenance provenance;
    int bytes() const { return bits / 8; }
};

// How an attribute the layout does not store is obtained. Formulas in layouts/README.md.
enum class FallbackKind : uint8_t {
    Constant,             // value
    FromMetallic,         // specular_color = mix(vec3(0.04), base_color, metallic)
    Ue4,                  // specular_color = mix(vec3(0.08 * specular), base_color, metallic)
    FromBaseColor,        // diffuse_color = base_color * (1 - metallic)
    FromDiffuseSpecular,  // base_color = diffuse_color + metallic * specular_color
    FromSpecularColor,    // metallic = clamp((max3(specular_color) - 0.04) / 0.96, 0, 1)
    FromRoughness,        // sheen_roughness = roughness (UE's cloth lobe takes the base roughness)
    MaterialPass,         // deferred lighting: read by the second geometry (material) pass
    Forward,              // emissive: added to the lighting output by the geometry pass, unstored
};
const char* fallbackKindName(FallbackKind k);  // the keyword, "constant" for Constant

struct Fallback {
    Attribute attribute = Attribute::Normal;
    FallbackKind kind = FallbackKind::Constant;
    std::vector<double> value;  // Constant: one per component
    FilePlace place;
    Provenance provenance;
    bool incomplete = false;  // a parse error was reported for it (never in a returned Layout)
};

// What a pixel without geometry holds: one declared value per stored attribute ([clear]). The
// renderer clears each target with the words the layout's own encoders make of these values.
struct ClearValue {
    Attribute attribute = Attribute::Normal;
    std::vector<double> value;  // one per component
    FilePlace place;
    Provenance provenance;
};

enum class LightQuantity : uint8_t { DiffuseRgb, SpecularRgb, SpecularLuminance };
const char* lightQuantityName(LightQuantity q);

// How a light buffer's channels are quantised (layouts/README.md, "[[light_buffer]]"; the GLSL is
// shaders/light_buffer_encodings.glsl, the CPU mirror src/encoding/light_buffer_encodings.h).
enum class LightBufferEncoding : uint8_t {
    Float16,      // "float16": RGBA16F, IEEE binary16 per channel (PC)
    Float111110,  // "float11_11_10": R11G11B10F, unsigned 5e6 / 5e6 / 5e5 floats, no alpha
    Float7e3,     // "float7e3": the Xbox 360's A2B10G10R10F (7e3: 3-bit exponent, 7-bit mantissa) + 2-bit alpha
    Rgbk,         // "rgbk": the PS3's RGBK (RGBM) in RGBA8: rgb * k * range / 255^2, k in alpha
};
const char* lightBufferEncodingName(LightBufferEncoding e);
// Light quantities a buffer in this encoding can hold: channels it has (7e3's 2-bit alpha and
// RGBK's multiplier hold none).
int lightBufferEncodingChannels(LightBufferEncoding e);

struct LightBuffer {
    std::string name;
    std::string format;
    std::vector<LightQuantity> holds;  // assigned to the format's channels in order (rgb = 3, luminance = 1)
    LightBufferEncoding encoding = LightBufferEncoding::Float16;
    double range = 0.0;  // rgbk: the largest value a channel holds (the multiplier's range); else 0
    FilePlace place;
    FilePlace encodingPlace;
    int bytes = 0;
    Provenance provenance;
};

// Deferred lighting's material pass: how the light buffers are combined with the material.
enum class MaterialFresnel : uint8_t {
    None,       // "none": specular light * specular colour (F0)
    SchlickNv,  // "schlick_nv": specular light * Schlick(F0, n.v), the only angle the material pass has
};

struct MaterialPassOptions {
    MaterialFresnel fresnel = MaterialFresnel::None;
    FilePlace place;
    Provenance provenance;
    bool declared = false;
};

// The space a layout stores normals (and position) in ([space], layouts/README.md). gbufferlab's
// world is Y-up; CryEngine and UE4 are Z-up, so their world-space normals have the ground's normal
// along +Z. The G-buffer pass transforms into the declared space before encoding and the lighting
// and decode passes transform back (shaders/normal_space.glsl, mirrored by
// src/codec/normal_space.h); the generated wiring itself is space-agnostic.
enum class StoredSpace : uint8_t {
    WorldYUp,  // "world", up = "y": gbufferlab's own world, no transform
    WorldZUp,  // "world", up = "z": the fixed right-handed axis swap (x, y, z) -> (x, -z, y)
    View,      // "view": the camera's view matrix (right-handed, looking down -Z)
};
const char* storedSpaceName(StoredSpace s);  // "world (Y-up)", "world (Z-up)", "view"

struct SpaceDecl {
    bool declared = false;          // the layout has a [space] table
    bool normalDeclared = false;    // ... with `normal`
    bool positionDeclared = false;  // ... with `position`
    StoredSpace normal = StoredSpace::WorldYUp;
    StoredSpace position = StoredSpace::View;
    FilePlace place;          // the [space] table (1:1 when absent)
    FilePlace positionPlace;  // its `position` key
    Provenance provenance;
};

struct Source {
    std::string game;
    std::string engine;
    std::string talk;  // talk / paper / article, with authors and venue
    std::string code;  // source file the layout is read from (e.g. DeferredShadingCommon.ush)
    std::string family;  // what the atlas groups by (e.g. "Unreal Engine"); empty: engine, else game
    int year = 0;
    std::string text() const;  // one line for `layouts show`
};

struct Layout {
    std::string name;
    std::string title;
    Source source;
    Pipeline pipeline = Pipeline::DeferredShading;
    Depth depth;
    std::vector<Target> targets;
    std::vector<Fallback> fallbacks;
    std::vector<LightBuffer> lightBuffers;
    MaterialPassOptions materialPass;  // [material_pass] (deferred lighting)
    SpaceDecl space;                   // [space]: where normals (and position) are stored
    VisibilityIds ids;                 // [ids] (visibility buffer only)
    std::string sourceFile;  // the file it was read from (or the name given to parseLayout)
    FilePlace namePlace;
    FilePlace fallbackPlace;  // the [fallback] table (1:1 when absent)
    std::vector<ClearValue> clears;  // [clear], in file order
    bool clearDeclared = false;      // the layout has a [clear] table
    FilePlace clearPlace;            // the [clear] table (1:1 when absent)
    std::vector<Citation> citations;  // [sources], in file order
    bool sourcesDeclared = false;     // the layout has a [sources] table: provenance on every entry
    FilePlace sourcesPlace;

    const Field* findField(Attribute a) const;  // in targets or stencil; nullptr when not stored
    const Fallback* findFallback(Attribute a) const;
    const ClearValue* findClear(Attribute a) const;  // nullptr when [clear] does not list it
    const Citation* findCitation(std::string_view key) const;  // nullptr when [sources] has no such key
    bool stores(Attribute a) const { return findField(a) != nullptr; }
    // Stored by an unconditional field (or carried by one's encoding): on every pixel.
    bool storesAlways(Attribute a) const;
    // Stored by conditional fields only: on the pixels of some models (a fallback, or "no layer",
    // gives the others).
    bool storesConditionally(Attribute a) const { return stores(a) && !storesAlways(a); }
    // The selector field (attribute shading_model); nullptr when the layout has none.
    const Field* selector() const;
    // The ids (bit i = id i) the selector gives the models of the mask `models`.
    uint32_t selectorIds(uint32_t models) const;
    // The models (bit m = ShadingModel m) the selector names; 0 without a selector.
    uint32_t selectorModels() const;
    // The models under which `a` is stored by a conditional field (0 when none is).
    uint32_t conditionalModels(Attribute a) const;
};

// G-buffer bytes per pixel: all targets plus the depth-stencil attachment (a visibility buffer:
// its id target plus depth).
int bytesPerPixel(const Layout& layout);
// The depth attachment's nominal bytes per pixel: the [depth] format's, except where the depth
// lives in the ids' depth word (Nanite and Bevy's meshlet raster have no depth attachment): 0.
int depthAttachmentBytes(const Layout& layout);
// Light-buffer bytes per pixel (deferred lighting; 0 otherwise).
int lightBufferBytesPerPixel(const Layout& layout);

struct AttributeBits {
    Attribute attribute;
    int bits;
    uint32_t models = 0;  // the models it is stored under when only conditional fields store it (else 0)
};
// Bits each stored attribute takes (all its codes, stencil included), in attribute order; an
// attribute stored by several conditional fields (under different models) counts its widest.
std::vector<AttributeBits> bitsPerAttribute(const Layout& layout);

// Every entry of a layout that carries provenance, in file order of sections: depth and its
// stencil fields, each target then its fields, [ids], light buffers, [material_pass], fallbacks,
// clear values, [space]. `what` names it for messages and `layouts show` ("field 'normal' of
// target 'GBufferA'").
struct ProvenanceEntry {
    std::string what;
    const Provenance* provenance = nullptr;
};
std::vector<ProvenanceEntry> provenanceEntries(const Layout& layout);

// How much of a layout is verified: entries by status, and those with a known difference.
struct ProvenanceCounts {
    int entries = 0;
    int verified = 0, talk = 0, lineage = 0, assumed = 0, own = 0, missing = 0;
    int differs = 0;
    // "verified 14/18, talk 2, assumed 2" (zero counts left out; "differs 3" when any; "none"
    // when no entry has provenance)
    std::string text() const;
};
ProvenanceCounts provenanceCounts(const Layout& layout);

// A code's name within its field: "x", "y", "z_sign", "Y", "Cb", "r", ... ("code N" if unnamed).
std::string codeLabel(const Field& field, size_t code);
// Reads a place written in a layout file into `out`: "r", "b[7]", "a[0:3]", or pieces joined by
// '+' ("r + b[0:3]", the code's low bits first), against `channels` (of `formatName`, for messages).
// Returns "" or what is wrong. Ranges are not checked against channel widths here (validation
// reports overflow by how much).
std::string parseCodePlace(std::string_view text, const std::vector<Channel>& channels, const std::string& formatName,
                           CodePlace& out);
// "r[0:6]" for one range.
std::string bitRangeText(const std::vector<Channel>& channels, const BitRange& range);

// ---------------------------------------------------------------------------------------------
// Reading and checking

struct LayoutDiagnostic {
    std::string file;
    FilePlace place;
    std::string message;
    std::string text() const;  // "file:line:col: message"
};

// Thrown for any invalid layout file; what() is every diagnostic, one per line, in file order.
struct LayoutError : UserError {
    explicit LayoutError(std::vector<LayoutDiagnostic> diagnostics);
    std::vector<LayoutDiagnostic> diagnostics;
};

// Parses and fully validates a layout written in `text`; `fileName` is used in messages and as
// Layout::sourceFile. Throws LayoutError listing every problem found.
Layout parseLayout(std::string_view text, const std::string& fileName);

// Reads `path` and parses it; also requires the layout's `name` to equal the file's stem.
Layout loadLayoutFile(const std::filesystem::path& path);

// Same checks without throwing: every diagnostic (empty when the text is a valid layout).
std::vector<LayoutDiagnostic> checkLayout(std::string_view text, const std::string& fileName);
std::vector<LayoutDiagnostic> checkLayoutFile(const std::filesystem::path& path);

// Internal steps, exposed for tests: parsing appends structural problems to `out` and returns what
// could be read; validation appends semantic problems of a parsed layout.
Layout parseLayoutUnchecked(std::string_view text, const std::string& fileName, std::vector<LayoutDiagnostic>& out);
void validateLayout(const Layout& layout, std::vector<LayoutDiagnostic>& out);

}  // namespace gbl
