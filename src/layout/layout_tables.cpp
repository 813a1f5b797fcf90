// Tables of the layout language: attributes, render-target and depth formats, and their lookups.
#include "layout.h"

#include <algorithm>
#include <cassert>
#include <charconv>

#include "encoding_registry.h"

namespace gbl {

namespace {

using AC = AttributeClass;
using VT = ValueType;
using VD = ValueDomain;

const std::vector<AttributeInfo>& attributeTable() {
    static const std::vector<AttributeInfo> table = {
        {Attribute::Normal, "normal", 3, AC::Shading, VT::Float, VD::Signed, "world-space unit normal"},
        {Attribute::BaseColor, "base_color", 3, AC::Shading, VT::Float, VD::Unit,
         "linear base colour (metallic workflow)"},
        {Attribute::Metallic, "metallic", 1, AC::Shading, VT::Float, VD::Unit, "metalness"},
        {Attribute::Roughness, "roughness", 1, AC::Shading, VT::Float, VD::Unit,
         "perceptual roughness; GGX alpha = roughness^2"},
        {Attribute::Specular, "specular", 1, AC::Shading, VT::Float, VD::Unit,
         "UE4 scalar specular; dielectric F0 = 0.08 * specular (0.5 -> 0.04)"},
        {Attribute::SpecularColor, "specular_color", 3, AC::Shading, VT::Float, VD::Unit,
         "F0, reflectance at normal incidence, linear"},
        {Attribute::DiffuseColor, "diffuse_color", 3, AC::Shading, VT::Float, VD::Unit,
         "Lambert albedo = base_color * (1 - metallic), linear"},
        {Attribute::Occlusion, "occlusion", 1, AC::Shading, VT::Float, VD::Unit, "ambient occlusion"},
        {Attribute::Emissive, "emissive", 3, AC::Shading, VT::Float, VD::NonNegative,
         "emitted radiance, linear, may exceed 1"},
        {Attribute::Coat, "coat", 1, AC::Shading, VT::Float, VD::Unit,
         "clear-coat amount (KHR_materials_clearcoat clearcoat); 0 = no coat, what a layout without it decodes"},
        {Attribute::CoatRoughness, "coat_roughness", 1, AC::Shading, VT::Float, VD::Unit,
         "clear-coat perceptual roughness (clearcoatRoughness); GGX alpha = coat_roughness^2"},
        {Attribute::CoatNormal, "coat_normal", 3, AC::Shading, VT::Float, VD::Signed,
         "the clear coat's unit normal, in the normal's [space] (0 = the base normal)"},
        {Attribute::SheenColor, "sheen_color", 3, AC::Shading, VT::Float, VD::Unit,
         "sheen colour, linear (KHR_materials_sheen sheenColor); black = no sheen"},
        {Attribute::SheenRoughness, "sheen_roughness", 1, AC::Shading, VT::Float, VD::Unit,
         "sheen perceptual roughness (sheenRoughness); Charlie alpha = sheen_roughness^2"},
        {Attribute::AnisotropyStrength, "anisotropy_strength", 1, AC::Shading, VT::Float, VD::Unit,
         "anisotropy strength (KHR_materials_anisotropy); 0 = isotropic"},
        {Attribute::AnisotropyDirection, "anisotropy_direction", 3, AC::Shading, VT::Float, VD::Signed,
         "unit tangent the highlights stretch along (anisotropyRotation applied), in the normal's [space], "
         "orthogonal to the normal (0 = none)"},
        {Attribute::Position, "position", 3, AC::Geometry, VT::Float, VD::Any,
         "view-space position; a layout that does not store it reconstructs it from depth"},
        {Attribute::Depth, "depth", 1, AC::Geometry, VT::Float, VD::Unit,
         "window-space depth (gl_FragCoord.z, the layout's own Z convention); the lighting rebuilds position "
         "from it instead of from the depth attachment (Bevy on WebGL2)"},
        {Attribute::Translucency, "translucency", 1, AC::Extra, VT::Float, VD::Unit,
         "translucency (transmission) luminance of thin surfaces (Crysis 3 RT0.a, Ryse RT0.a)"},
        {Attribute::SssProfile, "sss_profile", 1, AC::Extra, VT::Integer, VD::Id,
         "subsurface-scattering profile index (Ryse RT1.a)"},
        {Attribute::ShadingModelId, "shading_model_id", 1, AC::Extra, VT::Integer, VD::Id,
         "shading model id (UE4 GBufferB.a bits 0..3; SHADINGMODELID_DEFAULT_LIT = 1)"},
        {Attribute::SelectiveOutputMask, "selective_output_mask", 1, AC::Extra, VT::Integer, VD::Id,
         "UE4 GBufferB.a bits 4..7: flags that skip precomputed shadow / velocity per pixel"},
        {Attribute::PerObject, "per_object", 1, AC::Extra, VT::Float, VD::Unit,
         "UE4 GBufferA.a: PerObjectGBufferData (2 bits of per-object flags)"},
        {Attribute::AmbientId, "ambient_id", 1, AC::Extra, VT::Integer, VD::Id,
         "ambient-volume (probe) id the pixel belongs to (Crysis 3 stencil)"},
        {Attribute::Decals, "decals", 1, AC::Extra, VT::Integer, VD::Id,
         "decal mask: which deferred decals affect the pixel (Crysis 3 stencil)"},
        {Attribute::Indoor, "indoor", 1, AC::Extra, VT::Integer, VD::Id,
         "tags indoor surfaces, read back by later passes (Crysis 2 stencil)"},
        {Attribute::PerProject, "per_project", 1, AC::Extra, VT::Float, VD::Unit,
         "reserved for each game built on the engine (Crysis 3 RT1.a)"},
        {Attribute::CustomData, "custom_data", 4, AC::Extra, VT::Float, VD::Unit,
         "shading-model data: subsurface colour, clear coat, ... (UE4 GBufferD)"},
        {Attribute::PrecomputedShadow, "precomputed_shadow", 4, AC::Extra, VT::Float, VD::Unit,
         "precomputed (static-light) shadow factors, 1 = unshadowed (UE4 GBufferE)"},
        {Attribute::MaterialFeature, "material_feature", 1, AC::Extra, VT::Integer, VD::Id,
         "material classification id for tiled lighting (HDRP-style)"},
        {Attribute::CoatMask, "coat_mask", 1, AC::Extra, VT::Float, VD::Unit, "clear-coat mask (HDRP)"},
        {Attribute::Flags, "flags", 1, AC::Extra, VT::Integer, VD::Id, "per-pixel mesh / material flags (Bevy)"},
        {Attribute::Velocity, "velocity", 2, AC::Extra, VT::Float, VD::Unit,
         "screen-space motion as the engine encodes it; a static camera and scene give the engine's zero code "
         "(UE5 velocity target, Killzone 2 RT2.rg)"},
        {Attribute::Tangent, "tangent", 3, AC::Extra, VT::Float, VD::Unit,
         "world tangent as t * 0.5 + 0.5 (UE5 GBufferF.rgb); the scene has no tangents, so a constant"},
        {Attribute::Anisotropy, "anisotropy", 1, AC::Extra, VT::Float, VD::Unit,
         "anisotropy as a * 0.5 + 0.5 (UE5 GBufferF.a; 0.5 = isotropic)"},
        {Attribute::PassId, "pass_id", 1, AC::Extra, VT::Integer, VD::Id,
         "deferred lighting pass id (Bevy's R8Uint target; 1 = the default PBR lighting pass)"},
        {Attribute::SunOcclusion, "sun_occlusion", 1, AC::Extra, VT::Float, VD::Unit,
         "baked sun occlusion, 1 = unoccluded (Killzone 2 RT3.a)"},
        {Attribute::ShadingModelFloat, "shading_model_float", 1, AC::Extra, VT::Float, VD::Unit,
         "UE GBufferB.a in a float target: (ShadingModelID | SelectiveOutputMask) / 255 (r.GBufferFormat=5)"},
        {Attribute::LightIntensity, "light_intensity", 1, AC::Extra, VT::Float, VD::Unit,
         "intensity channel of a light accumulation target (Killzone 2 RT0.a)"},
        {Attribute::PrecomputedIrradiance, "precomputed_irradiance", 1, AC::Extra, VT::Float, VD::Unit,
         "UE GBufferC.a with static lighting allowed: log2(baked irradiance * AO + 2^-8) / 16 + 0.5 plus a dither "
         "below half a code; 0 where nothing is baked, and lighting then reads AO = 1"},
        {Attribute::Opacity, "opacity", 1, AC::Extra, VT::Float, VD::Unit,
         "opacity or decal mask (UE4 Elemental demo 2012, GBufferC.a)"},
        {Attribute::SubsurfaceColor, "subsurface_color", 3, AC::Extra, VT::Float, VD::Unit,
         "subsurface colour (UE4 Elemental demo 2012, GBufferD.gba)"},
        {Attribute::IsLightmap, "is_lightmap", 1, AC::Extra, VT::Integer, VD::Id,
         "1 when the object is lightmapped (HDRP with probe volumes, GBuffer0.a bit 7)"},
        {Attribute::SpecularOcclusion, "specular_occlusion", 1, AC::Extra, VT::Float, VD::Unit,
         "specular occlusion (HDRP GBuffer0.a: 1 for a Lit material without a mask map); kept, not shaded"},
        {Attribute::ShadingModel, "shading_model", 1, AC::Selector, VT::Integer, VD::Id,
         "the shading-model selector: the id of the model the pixel's other bits hold (UE's shading model id, "
         "HDRP's material feature id); its field names the models and their ids"},
    };
    return table;
}

Channel ch(const char* name, int bits, int offset, ChannelType type) { return {name, bits, offset, type}; }

std::string uintFormatForBits(int bits) {
    switch (bits) {
        case 8:
            return "R8_UINT";
        case 16:
            return "R16_UINT";
        case 32:
            return "R32_UINT";
        case 64:
            return "R32G32_UINT";
        case 128:
            return "R32G32B32A32_UINT";
    }
    assert(false && "no UINT format of this size");
    return "";
}

// Channels named in `order` (bit order), each `bits` wide, all of `type`.
TargetFormatInfo uniform(const char* name, const char* order, int bits, ChannelType type) {
    TargetFormatInfo f;
    f.name = name;
    int offset = 0;
    for (const char* c = order; *c; ++c) {
        f.channels.push_back({std::string(1, *c), bits, offset, type});
        offset += bits;
    }
    f.bits = offset;
    f.uintFormat = uintFormatForBits(f.bits);
    return f;
}

TargetFormatInfo custom(const char* name, std::vector<Channel> channels) {
    TargetFormatInfo f;
    f.name = name;
    f.channels = std::move(channels);
    for (const Channel& c : f.channels) f.bits = std::max(f.bits, c.offset + c.bits);
    f.uintFormat = uintFormatForBits(f.bits);
    return f;
}

// sRGB formats: colour channels use the sRGB transfer function, alpha is linear UNORM.
TargetFormatInfo srgb(const char* name, const char* order) {
    TargetFormatInfo f = uniform(name, order, 8, ChannelType::Srgb);
    for (Channel& c : f.channels)
        if (c.name == "a") c.type = ChannelType::Unorm;
    return f;
}

const std::vector<TargetFormatInfo>& targetFormatTable() {
    using T = ChannelType;
    static const std::vector<TargetFormatInfo> table = {
        uniform("R8_UNORM", "r", 8, T::Unorm),
        uniform("R8G8_UNORM", "rg", 8, T::Unorm),
        uniform("R8G8B8A8_UNORM", "rgba", 8, T::Unorm),
        srgb("R8G8B8A8_SRGB", "rgba"),
        // SNORM channels hold bit fields like UNORM ones (the snorm encoding writes two's complement codes).
        uniform("R8G8B8A8_SNORM", "rgba", 8, T::Unorm),
        uniform("B8G8R8A8_UNORM", "bgra", 8, T::Unorm),
        srgb("B8G8R8A8_SRGB", "bgra"),
        uniform("A8B8G8R8_UNORM_PACK32", "rgba", 8, T::Unorm),
        srgb("A8B8G8R8_SRGB_PACK32", "rgba"),
        uniform("R8_UINT", "r", 8, T::Uint),
        uniform("R8G8_UINT", "rg", 8, T::Uint),
        uniform("R8G8B8A8_UINT", "rgba", 8, T::Uint),
        custom("A2B10G10R10_UNORM_PACK32", {ch("r", 10, 0, T::Unorm), ch("g", 10, 10, T::Unorm),
                                            ch("b", 10, 20, T::Unorm), ch("a", 2, 30, T::Unorm)}),
        custom("A2R10G10B10_UNORM_PACK32", {ch("b", 10, 0, T::Unorm), ch("g", 10, 10, T::Unorm),
                                            ch("r", 10, 20, T::Unorm), ch("a", 2, 30, T::Unorm)}),
        custom("A2B10G10R10_UINT_PACK32",
               {ch("r", 10, 0, T::Uint), ch("g", 10, 10, T::Uint), ch("b", 10, 20, T::Uint), ch("a", 2, 30, T::Uint)}),
        custom("B10G11R11_UFLOAT_PACK32",
               {ch("r", 11, 0, T::Ufloat), ch("g", 11, 11, T::Ufloat), ch("b", 10, 22, T::Ufloat)}),
        uniform("R16_UNORM", "r", 16, T::Unorm),
        uniform("R16G16_UNORM", "rg", 16, T::Unorm),
        uniform("R16G16B16A16_UNORM", "rgba", 16, T::Unorm),
        uniform("R16_SFLOAT", "r", 16, T::Sfloat),
        uniform("R16G16_SFLOAT", "rg", 16, T::Sfloat),
        uniform("R16G16B16A16_SFLOAT", "rgba", 16, T::Sfloat),
        uniform("R16_UINT", "r", 16, T::Uint),
        uniform("R16G16_UINT", "rg", 16, T::Uint),
        uniform("R16G16B16A16_UINT", "rgba", 16, T::Uint),
        uniform("R32_SFLOAT", "r", 32, T::Sfloat),
        uniform("R32G32_SFLOAT", "rg", 32, T::Sfloat),
        uniform("R32G32B32A32_SFLOAT", "rgba", 32, T::Sfloat),
        uniform("R32_UINT", "r", 32, T::Uint),
        uniform("R32G32_UINT", "rg", 32, T::Uint),
        uniform("R32G32B32A32_UINT", "rgba", 32, T::Uint),
    };
    return table;
}

const std::vector<DepthFormatInfo>& depthFormatTable() {
    static const std::vector<DepthFormatInfo> table = {
        {"D16_UNORM", 16, 0, false, 2},         {"X8_D24_UNORM_PACK32", 24, 0, false, 4},
        {"D24_UNORM_S8_UINT", 24, 8, false, 4}, {"D32_SFLOAT", 32, 0, true, 4},
        {"D32_SFLOAT_S8_UINT", 32, 8, true, 5},
    };
    return table;
}

template <class Table>
std::string joinNames(const Table& table) {
    std::string s;
    for (const auto& e : table) {
        if (!s.empty()) s += ", ";
        s += e.name;
    }
    return s;
}

}  // namespace

// ---- attributes -------------------------------------------------------------------------------

const std::vector<AttributeInfo>& listAttributes() { return attributeTable(); }

const AttributeInfo& attributeInfo(Attribute a) {
    const auto& t = attributeTable();
    assert(static_cast<size_t>(a) < t.size() && t[static_cast<size_t>(a)].id == a);
    return t[static_cast<size_t>(a)];
}

const char* attributeName(Attribute a) { return attributeInfo(a).name; }

const AttributeInfo* findAttribute(std::string_view name) {
    for (const AttributeInfo& a : attributeTable())
        if (name == a.name) return &a;
    return nullptr;
}

std::string knownAttributeNames() { return joinNames(attributeTable()); }

bool isShadingAttribute(Attribute a) { return attributeInfo(a).cls == AttributeClass::Shading; }

bool isLayerAttribute(Attribute a) { return a >= Attribute::Coat && a <= Attribute::AnisotropyDirection; }

int attributeLayerBit(Attribute a) {
    switch (a) {
        case Attribute::Coat:
        case Attribute::CoatRoughness:
        case Attribute::CoatNormal: return 1;
        case Attribute::SheenColor:
        case Attribute::SheenRoughness: return 2;
        case Attribute::AnisotropyStrength:
        case Attribute::AnisotropyDirection: return 4;
        default: return 0;
    }
}

bool isDirectionAttribute(Attribute a) {
    return a == Attribute::Normal || a == Attribute::CoatNormal || a == Attribute::AnisotropyDirection;
}

// ---- formats ----------------------------------------------------------------------------------

const std::vector<TargetFormatInfo>& listTargetFormats() { return targetFormatTable(); }

const TargetFormatInfo* findTargetFormat(std::string_view name) {
    for (const TargetFormatInfo& f : targetFormatTable())
        if (f.name == name) return &f;
    return nullptr;
}

std::string knownTargetFormatNames() { return joinNames(targetFormatTable()); }

const std::vector<DepthFormatInfo>& listDepthFormats() { return depthFormatTable(); }

const DepthFormatInfo* findDepthFormat(std::string_view name) {
    for (const DepthFormatInfo& f : depthFormatTable())
        if (f.name == name) return &f;
    return nullptr;
}

std::string knownDepthFormatNames() { return joinNames(depthFormatTable()); }

}  // namespace gbl
