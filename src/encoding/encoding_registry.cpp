#include "encoding_registry.h"

namespace gbl {

namespace {

using K = AttributeKind;

// Each entry: name, kind, codes, default bits, min bits, max bits, extra bits, neighbours, input,
// description, source. The registry's order is listEncodings()'s.

// The general encodings: fixed point, small floats, sRGB, normals, colour transforms, depth and
// the packings of the engines before the material layers.
void addGeneralEncodings(std::vector<EncodingInfo>& v) {
    v.push_back({"unorm", K::Scalar, 1, 8, 1, 24, 0, false, "[0,1]",
                 "unsigned normalised integer: floor(x*(2^b-1)+0.5)",
                 "Vulkan spec, 'Fixed-Point Data Conversions'"});
    v.push_back({"snorm", K::Scalar, 1, 8, 2, 24, 0, false, "[-1,1]",
                 "signed normalised integer, two's complement, symmetric: -1 -> -(2^(b-1)-1)",
                 "Vulkan spec, 'Fixed-Point Data Conversions'"});
    v.push_back({"float16", K::Scalar, 1, 16, 16, 16, 0, false, "finite float",
                 "IEEE 754 binary16, round to nearest even, overflow clamps to max finite (65504)",
                 "IEEE 754-2008"});
    v.push_back({"float11", K::Scalar, 1, 11, 11, 11, 0, false, "[0, 65024]",
                 "unsigned float, 5-bit exponent, 6-bit mantissa, negative -> 0, round to nearest even",
                 "Vulkan spec, 'Unsigned 11-Bit Floating-Point Numbers' (B10G11R11_UFLOAT)"});
    v.push_back({"float10", K::Scalar, 1, 10, 10, 10, 0, false, "[0, 64512]",
                 "unsigned float, 5-bit exponent, 5-bit mantissa, negative -> 0, round to nearest even",
                 "Vulkan spec, 'Unsigned 10-Bit Floating-Point Numbers' (B10G11R11_UFLOAT)"});
    v.push_back({"float32", K::Scalar, 1, 32, 32, 32, 0, false, "any float",
                 "IEEE 754 binary32 bits, lossless", "IEEE 754-2008"});
    v.push_back({"depth24", K::Scalar, 1, 24, 24, 24, 0, false, "[0,1]",
                 "24-bit unorm depth (D24S8 / X8_D24), quantised in float",
                 "Vulkan spec, D24 depth formats"});
    v.push_back({"gloss", K::Scalar, 1, 8, 1, 16, 0, false, "roughness in [0,1]",
                 "stores gloss = 1 - roughness as unorm", "CryEngine 2/3 glossiness convention"});
    v.push_back({"smoothness_cry", K::Scalar, 1, 8, 1, 16, 0, false, "roughness in [0,1]",
                 "stores smoothness = 1 - sqrt(roughness) as unorm; roughness = (1 - s)^2",
                 "Schulz, 'Moving to the Next Generation - The Rendering Technology of Ryse', GDC 2014"});
    v.push_back({"cry_gloss_power", K::Scalar, 1, 8, 8, 8, 0, false, "roughness in [0.1767, 0.8409] (clamps)",
                 "8-bit gloss g read as a Blinn-Phong power n = exp2(10 g + 1) (2..2048), to GGX roughness = "
                 "(2 / (n + 2))^(1/4); table exact; round-trip error <= 0.0018 inside the range",
                 "Sousa, Kasyan, Schulz, 'Secrets of CryENGINE 3 Graphics Technology', SIGGRAPH 2011 (gloss "
                 "in RT1.a); power mapping assumed (CryENGINE 3-era shaders); Walter et al., EGSR 2007 "
                 "(n = 2/alpha^2 - 2)"});
    v.push_back({"kz2_log_power", K::Scalar, 1, 8, 8, 8, 0, false, "roughness in [0.1927, 0.9036] (clamps)",
                 "8-bit g = log2(n) / 10.5 of a Blinn-Phong power n = 2^(10.5 g) (1..1448), to GGX roughness = "
                 "(2 / (n + 2))^(1/4) as cry_gloss_power; table exact; round-trip error <= 0.0019 inside the range",
                 "Valient, 'Deferred Rendering in Killzone 2', Develop 2007 ('Specular power - stored as "
                 "log2(original)/10.5'); Walter et al., EGSR 2007 (n = 2/alpha^2 - 2)"});

    v.push_back({"reflectance", K::Scalar, 1, 8, 1, 16, 0, false, "specular in [0,1]",
                 "Filament / Bevy reflectance r = sqrt(specular / 2) as unorm (F0 = 0.16 r^2 = 0.08 specular); "
                 "decodes specular = 2 r^2",
                 "Filament documentation, 'Reflectance' (F0 = 0.16 reflectance^2); Bevy StandardMaterial::reflectance"});
    v.push_back({"reflectance_bevy_webgl2", K::Scalar, 1, 4, 1, 16, 0, false, "specular in [0,1]",
                 "`reflectance` read back as Bevy reads its 4-bit WebGL2 reflectance: r = saturate(code / (2^b - 1) "
                 "- 0.03333333333), specular = 2 r^2 (code 8 of 4 bits reads 0.5; the others half a step low)",
                 "bevyengine/bevy v0.16.0 crates/bevy_pbr/src/deferred/pbr_deferred_functions.wgsl:36-40, 104-106"});
}

// Material layers as the engines store them (engine_encodings.h), then the remaining engine
// packings.
void addLayerAndEngineEncodings(std::vector<EncodingInfo>& v) {
    v.push_back({"unorm_round_even", K::Scalar, 1, 4, 1, 16, 0, false, "[0,1]",
                 "unorm rounded with ties to even (WGSL's round): code = roundEven(saturate(x) * (2^b - 1)); "
                 "decoded as unorm",
                 "bevyengine/bevy v0.19.0 c6f634ca crates/bevy_pbr/src/deferred/pbr_deferred_functions.wgsl:42, "
                 "115 (clear-coat strength, pull request 23359)"});
    v.push_back({"coat_roughness_bevy", K::Scalar, 1, 4, 1, 16, 0, false, "coat roughness in [0,0.5] (clamps)",
                 "clamp(r, 0, 0.5) * 2 (2^b - 1) rounded with ties to even; decoded code / (2 (2^b - 1)): 4 bits "
                 "over [0, 0.5], error <= 1/60 inside",
                 "bevyengine/bevy v0.19.0 c6f634ca crates/bevy_pbr/src/deferred/pbr_deferred_functions.wgsl:43-44, "
                 "116 (clear-coat perceptual roughness, pull request 23359)"});
    v.push_back({"unorm_sqrt", K::Scalar, 1, 8, 8, 8, 0, false, "[0,1]",
                 "sqrt(saturate(x)) as 8-bit unorm, exact via 255 thresholds (no sqrt); decodes (code / 255)^2",
                 "UE 5.3.2 DeferredShadingCommon.ush:189-192, 1031-1034 (EncodeSubsurfaceColor / "
                 "ExtractSubsurfaceColor: the Cloth model's fuzz colour, ShadingModelsMaterial.ush:133-139)"});
    v.push_back({"unorm_signed", K::Scalar, 1, 8, 2, 16, 0, false, "[-1,1]",
                 "x * 0.5 + 0.5 as unorm; decoded code / (2^b - 1) * 2 - 1 (0 reads 1 / (2^b - 1))",
                 "UE 5.3.2 DeferredShadingCommon.ush:222-228, 1018 (EncodeWorldTangentAndAnisotropy: GBufferF.a "
                 "= anisotropy * 0.5 + 0.5)"});

    v.push_back({"srgb8", K::Color, 3, 8, 8, 8, 0, false, "[0,1]^3 linear",
                 "exact sRGB 8-bit per channel via 255 linear thresholds (no pow)",
                 "IEC 61966-2-1 sRGB transfer function"});
    v.push_back({"ycbcr", K::Color, 3, 8, 2, 16, 0, false, "[0,1]^3",
                 "BT.601 full-range YCbCr, Cb/Cr offset by 0.5, unorm per code",
                 "ITU-R BT.601 / JPEG JFIF; Sousa et al., 'The Rendering Technologies of Crysis 3', GDC 2013"});
    v.push_back({"ycbcr_sqrt", K::Color, 3, 8, 2, 16, 0, false, "[0,1]^3",
                 "sqrt(rgb) then BT.601 YCbCr (gamma-2 pre-transform), squared after decode",
                 "Sousa et al., 'The Rendering Technologies of Crysis 3', GDC 2013; Schulz, Ryse, GDC 2014"});
    v.push_back({"ycocg", K::Color, 3, 8, 2, 16, 0, false, "[0,1]^3",
                 "YCoCg, Co/Cg offset by 0.5, unorm per code",
                 "Malvar & Sullivan, 'YCoCg-R', JVT-I014 2003; Mavridis & Papaioannou, JCGT 2012"});
    v.push_back({"luma", K::Color, 1, 8, 2, 16, 0, false, "[0,1]^3",
                 "BT.601 luma only (Crysis 3 specular Y); decodes to grey",
                 "Sousa et al., 'The Rendering Technologies of Crysis 3', GDC 2013"});
    v.push_back({"ycocg_checkerboard", K::Color, 2, 8, 2, 16, 0, true, "[0,1]^3",
                 "Y + one chroma per pixel (Co on even (x+y), Cg on odd), edge-directed reconstruction",
                 "Mavridis & Papaioannou, 'The Compact YCoCg Frame Buffer', JCGT 1(1) 2012"});
    v.push_back({"ycbcr_checkerboard", K::Color, 2, 8, 2, 16, 0, true, "[0,1]^3",
                 "Y + one chroma per pixel (Cb on even (x+y), Cr on odd), edge-directed reconstruction",
                 "Sousa et al., Crysis 3, GDC 2013; Mavridis & Papaioannou, JCGT 2012"});
    v.push_back({"gamma22", K::Color, 3, 8, 8, 8, 0, false, "[0,1]^3 linear",
                 "gamma 2.2 (not sRGB): code = round(255 x^(1/2.2)), exact via 255 thresholds; decodes code^2.2",
                 "Bevy 0.12+ deferred G-buffer (pbr_deferred_functions.wgsl: pow(base_color, 1/2.2) in pack4x8unorm)"});
    v.push_back({"srgb8_fast_hdrp", K::Color, 3, 8, 8, 8, 0, false, "[0,1]^3 linear",
                 "HDRP's fast sRGB for fresnel0 in a UNORM target: code = round(255 saturate(1.055 |x|^(1/2.4) - "
                 "0.055)) (no linear toe), exact via 255 thresholds; decoded with HDRP's cubic x (x (0.305306011 x + "
                 "0.682171111) + 0.012522878)",
                 "Unity HDRP Lit.hlsl EncodeIntoGBuffer (GBuffer2.rgb = FastLinearToSRGB(fresnel0)); core Color.hlsl "
                 "FastLinearToSRGB, FastSRGBToLinear (HDRP / core 13.0.0 c667268a / 6363fa25)"});
    v.push_back({"float11_11_10", K::Color, 2, 11, 11, 11, 10, false, "[0, 65024]^3 (HDR)",
                 "B10G11R11's three unsigned floats as one colour: r, g float11 (5e6m), b float10 (5e5m)",
                 "Vulkan spec, 'Unsigned 11-Bit / 10-Bit Floating-Point Numbers'; HDRP GBuffer3 (Lit.hlsl)"});
    EncodingInfo aoTag{"float11_11_10_hdrp_ao_tag", K::Color, 2, 11, 11, 11, 10, false,
                       "[0, 65024]^3 emissive, with occlusion",
                       "float11_11_10, except where emissive is exactly 0: HDRP's AO tag, the codes of (2048, "
                       "occlusion, 1024) (word 0xC8000680 | float11(occlusion) << 11); decodes the tag to emissive 0 "
                       "and occlusion = float11 g, anything else to the floats and occlusion 1",
                       "Unity HDRP Lit.hlsl EncodeIntoGBuffer / DecodeFromGBuffer, AO_IN_GBUFFER3_TAG (HDRP 13.0.0 "
                       "c667268a Runtime/Material/Lit/Lit.hlsl:686-705, 944-953; Unity-Technologies/Graphics "
                       "1390609c)"};
    aoTag.carries = "occlusion";
    v.push_back(aoTag);
    v.push_back({"rgb9e5", K::Color, 3, 9, 9, 9, 5, false, "[0, 65408]^3 (HDR, e.g. emissive)",
                 "shared exponent: 9-bit mantissas r, g, b + 5-bit exponent (bias 15); error <= 2^-9 of max(r,g,b)",
                 "Vulkan spec, 'Shared Exponent' (E5B9G9R9_UFLOAT_PACK32); EXT_texture_shared_exponent; Bevy rgb9e5.wgsl"});

    v.push_back({"normal_xyz", K::Normal, 3, 8, 2, 16, 0, false, "unit vector",
                 "unorm of n*0.5+0.5 per component, normalised on decode", "common practice"});
    v.push_back({"normal_bestfit", K::Normal, 3, 8, 8, 8, 0, false, "unit vector",
                 "best-fit normals: n scaled to the 8-bit unorm vector of best direction, length from a 1024x1024 table",
                 "Kaplanyan, 'CryENGINE 3: Reaching the Speed of Light', SIGGRAPH 2010"});
    v.push_back({"normal_xy_zsign", K::Normal, 2, 8, 2, 16, 1, false, "unit vector",
                 "unorm x, y + 1 z-sign bit; z = sign*sqrt(max(0, 1-x^2-y^2))",
                 "Sousa et al., 'The Rendering Technologies of Crysis 3', GDC 2013"});
    v.push_back({"normal_spheremap", K::Normal, 2, 8, 2, 16, 0, false, "unit vector",
                 "Lambert azimuthal equal-area projection, full sphere",
                 "Pranckevicius, 'Compact Normal Storage for Small G-Buffers', 2009 (method #4)"});
    v.push_back({"normal_stereographic", K::Normal, 2, 8, 2, 16, 0, false, "unit vector",
                 "stereographic projection from -z, scaled by 1/1.7777: covers ~120 deg around +z "
                 "(view-space normals); directions beyond clamp (not a full-sphere mapping)",
                 "Pranckevicius, 'Compact Normal Storage for Small G-Buffers', 2009 (method #7)"});
    v.push_back({"normal_octahedral", K::Normal, 2, 8, 2, 16, 0, false, "unit vector",
                 "octahedral projection, snorm per component",
                 "Cigolle et al., 'A Survey of Efficient Representations for Independent Unit Vectors', JCGT 3(2) 2014"});
    v.push_back({"normal_octahedral_precise", K::Normal, 2, 8, 2, 16, 0, false, "unit vector",
                 "octahedral, best of the 4 floor/ceil neighbours by decoded dot product",
                 "Cigolle et al., JCGT 3(2) 2014, 'oct*P' precise variant"});
    v.push_back({"normal_octahedral_bevy", K::Normal, 2, 12, 2, 16, 0, false, "unit vector",
                 "octahedral as Bevy's octahedral_encode (n / |n|_1; fold for z < 0 with sign(0) = -1), unorm of "
                 "p*0.5+0.5 rounded: u32(saturate(u) * (2^b - 1) + 0.5) (Bevy's oct24 normal)",
                 "Bevy 0.12+ (bevyengine/bevy v0.16.0 e9418b38): crates/bevy_pbr/src/deferred/"
                 "pbr_deferred_types.wgsl:39-43 (pack_24bit_normal_and_flags), crates/bevy_pbr/src/render/"
                 "utils.wgsl:48-53 (octahedral_encode); Cigolle et al., JCGT 2014"});
    v.push_back({"normal_octahedral_unity", K::Normal, 2, 12, 2, 16, 0, false, "unit vector",
                 "octahedral as Unity's PackNormalOctQuadEncode (n * rcp(|n|_1), p = n.xy +- saturate(-n.z)), "
                 "unorm of saturate(p*0.5+0.5) truncated: uint(u * (2^b - 0.5)), decoded code / (2^b - 1)",
                 "Unity core Packing.hlsl PackNormalOctQuadEncode, PackFloat2To888 (URP accurate G-buffer "
                 "normals, UnityGBuffer.hlsl PackNormal; core 13.0.0 6363fa25 Packing.hlsl:57-69, 543-552)"});
    v.push_back({"normal_octahedral_hdrp", K::Normal, 2, 12, 2, 16, 0, false, "unit vector",
                 "normal_octahedral_unity after HDRP's seam clamp: |n.z| raised to at least 1/1024, its sign kept "
                 "(-0 as +), not renormalised",
                 "Unity HDRP NormalBuffer.hlsl EncodeIntoNormalBuffer (HDRP 13.0.0 c667268a "
                 "Runtime/Material/NormalBuffer.hlsl:27-33); core Packing.hlsl PackNormalOctQuadEncode, PackFloat2To888"});
    v.push_back({"normal_xy_float16", K::Normal, 2, 16, 16, 16, 0, false, "unit vector, view space",
                 "x, y as IEEE half floats; z = +sqrt(1 - x^2 - y^2) (facing the camera), no sign bit",
                 "Valient, 'Deferred Rendering in Killzone 2', Develop Conference 2007 (RT1: FP16 normal X, Y)"});
    EncodingInfo hdrpAniso{"anisotropy_angle_hdrp", K::Normal, 2, 8, 8, 8, 1, false,
                           "unit tangent, with anisotropy_strength and the normal",
                           "HDRP's anisotropic GBuffer2: the tangent's angle to GetLocalFrame(normal)'s x axis "
                           "folded into the first quadrant (min(|sin|, |cos|) remapped to 8-bit cells) + a storeSin "
                           "bit, and the anisotropy round(a * 127.5 + 127.5), 255 - it in the 2nd and 4th quadrants; "
                           "decoded against the decoded normal's frame as strength |a| along the tangent, or along "
                           "the bitangent where the stored anisotropy is negative",
                           "Unity HDRP Lit.hlsl EncodeIntoGBuffer / DecodeFromGBuffer, GBUFFER_LIT_ANISOTROPIC "
                           "(HDRP 13.0.0 c667268a Runtime/Material/Lit/Lit.hlsl:575-634, 880-905); core "
                           "CommonLighting.hlsl GetLocalFrame (6363fa25 :442-459)"};
    hdrpAniso.reads = "normal";
    hdrpAniso.carries = "anisotropy_strength";
    v.push_back(hdrpAniso);
    // UE's bottom normal is stored relative to the coat's (the pixel's GBufferA normal on a
    // ClearCoat pixel): it reads coat_normal, which a conditional field may read where a field of
    // its models stores it before it (layout_validate.cpp).
    EncodingInfo ueDelta{"normal_octahedral_delta_ue", K::Normal, 2, 8, 8, 8, 0, false,
                         "unit vector near coat_normal (the base normal under a clear coat)",
                         "UE's clear-coat bottom normal: (oct(normal) - oct(coat_normal)) * 0.25 + 128/255 as two "
                         "unorm codes with UE's octahedron (folded where z <= 0), decoded code * 4 - 512/255 + "
                         "oct(decoded coat_normal), unfolded and normalised; saturates where the two octahedral "
                         "points lie more than about 2 apart",
                         "Unreal Engine 5.3.2 ShadingModelsMaterial.ush:96-116 (CLEAR_COAT_BOTTOM_NORMAL, "
                         "r.ClearCoatNormal = 1), ClearCoatCommon.ush:5-14 GetClearCoatBottomNormal, "
                         "OctahedralCommon.ush:18-34 (mirror Mephisto1024/Toon_Engine@1a10ef19)"};
    ueDelta.reads = "coat_normal";
    v.push_back(ueDelta);
}

// zeux/niagara (src/shaders/mesh.frag.glsl, final.comp.glsl @95f289b7): niagara_encodings.h.
void addNiagaraEncodings(std::vector<EncodingInfo>& v) {
    EncodingInfo ratio{"emissive_albedo_ratio", K::Color, 1, 8, 1, 16, 0, false,
                       "[0, inf)^3 emissive, with base_color",
                       "x = log2(1 + L(emissive) / (L(base_color) + 0.001)) / 5 as unorm, L = (0.3, 0.6, 0.1); "
                       "decodes emissive = base_color * (2^(5x) - 1) from the decoded base_color (its hue only)",
                       "zeux/niagara mesh.frag.glsl (gbuffer[0].a) and final.comp.glsl"};
    ratio.reads = "base_color";
    v.push_back(ratio);
    EncodingInfo dither{"normal_octahedral_dithered", K::Normal, 2, 10, 2, 16, 0, false, "unit vector",
                        "octahedral as niagara's encodeOct (n.xy * (1 / |n|_1)), unorm of p*0.5+0.5 plus "
                        "interleaved gradient noise of the pixel * 0.5 / (2^b - 1) before rounding (niagara's "
                        "deband); error up to one step",
                        "zeux/niagara @95f289b7 src/shaders/mesh.frag.glsl:60,86 (gbuffer[1].rg), math.h:52-58 "
                        "(encodeOct), 99-102 (gradientNoise); Jimenez, SIGGRAPH 2014 (gradient noise)"};
    dither.dithered = true;
    v.push_back(dither);
}

std::vector<EncodingInfo> makeRegistry() {
    std::vector<EncodingInfo> v;
    addGeneralEncodings(v);
    addLayerAndEngineEncodings(v);
    addNiagaraEncodings(v);
    return v;
}

}  // namespace

const std::vector<EncodingInfo>& listEncodings() {
    static const std::vector<EncodingInfo> registry = makeRegistry();
    return registry;
}

const EncodingInfo* findEncoding(std::string_view name) {
    for (const EncodingInfo& e : listEncodings())
        if (e.name == name) return &e;
    return nullptr;
}

std::string knownEncodingNames() {
    std::string s;
    for (const EncodingInfo& e : listEncodings()) {
        if (!s.empty()) s += ", ";
        s += e.name;
    }
    return s;
}

int encodingTotalBits(const EncodingInfo& info, int bits) { return info.codeCount * bits + info.extraBits; }

bool encodingBitsValid(const EncodingInfo& info, int bits) { return bits >= info.minBits && bits <= info.maxBits; }

const char* attributeKindName(AttributeKind kind) {
    switch (kind) {
        case AttributeKind::Normal: return "normal";
        case AttributeKind::Color: return "color";
        case AttributeKind::Scalar: return "scalar";
    }
    return "?";
}

}  // namespace gbl
