// The compiled, multithreaded CPU codec (src/codec/cpu_codec.h) against the per-pixel codec it replaced,
// kept below as the specification (`reference`, the former src/codec/cpu_codec.cpp with its string
// dispatch): for every layout in layouts/, the words of a 1-thread run, of several multithreaded
// runs and of the reference must be identical, and so must the decoded Surfaces, bit for bit.
// parallelFor has its own test (tests/base), and so have the fast encoders (tests/encoding); the
// codec's properties that need no reference are cpu_codec_properties_test.cpp's.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "cpu_codec.h"
#include "encoding_registry.h"
#include "encodings.h"
#include "layout_files.h"
#include "niagara_encodings.h"
#include "layout_catalog.h"
#include "encodings_fast.h"
#include "parallel_for.h"
#include "surface_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

// ---------------------------------------------------------------------------------------------
// The former per-pixel codec, unchanged apart from its namespace and the Surface member lookup,
// which is the tests' own (surface_support.h), and the shading-model selector added as
// layouts/README.md states it: the pixel's model by the stated rule (test::statedModel), its id in
// the selector's bits, only the fields that hold under it written; on decode a field read where the
// stored id is one of its models', a conditional attribute starting from 0, and its fallback
// applied where the stored id's model does not store it.
namespace reference {

using namespace enc;

int components(Attribute a) { return attributeInfo(a).components; }

using test::memberOf;  // the Surface member of an attribute (a stored window depth rides in position.z)

bool isScalar(const Field& f) {
    return f.encoding == kIdEncoding || findEncoding(f.encoding)->kind == AttributeKind::Scalar;
}

float componentValue(const Field& f, const Surface& s, int i) {
    if (const float* m = memberOf(s, f.attribute)) return m[i];
    return f.value.empty() ? 0.0f : float(f.value[std::min<size_t>(size_t(i), f.value.size() - 1)]);
}
vec3 wholeValue(const Field& f, const Surface& s) {
    return vec3(componentValue(f, s, 0), componentValue(f, s, 1), componentValue(f, s, 2));
}

uint scalarEncode(const Field& f, float x, size_t i) {
    const std::string& e = f.encoding;
    const uint b = uint(f.bitsOfCode(i));
    if (e == kIdEncoding) {
        const double v = f.value.empty() ? 0.0 : f.value[std::min(i, f.value.size() - 1)];
        return uint(v);
    }
    if (e == "unorm") return quantizeUnorm(x, b);
    if (e == "snorm") return quantizeSnorm(x, b);
    if (e == "float16") return encodeFloat16(x);
    if (e == "float11") return encodeFloat11(x);
    if (e == "float10") return encodeFloat10(x);
    if (e == "float32") return encodeFloat32(x);
    if (e == "depth24") return quantizeDepth24(x);
    if (e == "gloss") return quantizeUnorm(glossFromRoughness(x), b);
    if (e == "smoothness_cry") return quantizeUnorm(smoothnessFromRoughnessCry(x), b);
    if (e == "cry_gloss_power") return encodeCryGlossPower(x);
    if (e == "kz2_log_power") return encodeKz2LogPower(x);
    if (e == "reflectance" || e == "reflectance_bevy_webgl2") return quantizeUnorm(reflectanceFromSpecular(x), b);
    if (e == "unorm_round_even") return quantizeUnormRoundEven(x, b);
    if (e == "coat_roughness_bevy") return encodeCoatRoughnessBevy(x, b);
    if (e == "unorm_signed") return quantizeUnormSigned(x, b);
    if (e == "unorm_sqrt") return encodeUnormSqrt(x);
    throw std::logic_error("cpu codec: no scalar encoder for " + e);
}

float scalarDecode(const Field& f, uint c, size_t i) {
    const std::string& e = f.encoding;
    const uint b = uint(f.bitsOfCode(i));
    if (e == "unorm") return dequantizeUnorm(c, b);
    if (e == "snorm") return dequantizeSnorm(c, b);
    if (e == "float16") return decodeFloat16(c);
    if (e == "float11") return decodeFloat11(c);
    if (e == "float10") return decodeFloat10(c);
    if (e == "float32") return decodeFloat32(c);
    if (e == "depth24") return dequantizeDepth24(c);
    if (e == "gloss") return roughnessFromGloss(dequantizeUnorm(c, b));
    if (e == "smoothness_cry") return roughnessFromSmoothnessCry(dequantizeUnorm(c, b));
    if (e == "cry_gloss_power") return decodeCryGlossPower(c);
    if (e == "kz2_log_power") return decodeKz2LogPower(c);
    if (e == "reflectance") return specularFromReflectance(dequantizeUnorm(c, b));
    if (e == "reflectance_bevy_webgl2") return specularFromReflectanceBevyWebgl2(dequantizeUnorm(c, b));
    if (e == "unorm_round_even") return dequantizeUnorm(c, b);
    if (e == "coat_roughness_bevy") return decodeCoatRoughnessBevy(c, b);
    if (e == "unorm_signed") return dequantizeUnormSigned(c, b);
    if (e == "unorm_sqrt") return decodeUnormSqrt(c);
    throw std::logic_error("cpu codec: no scalar decoder for " + e);
}

using ColorFn = vec3 (*)(vec3);
bool colorTransform(const std::string& e, ColorFn& fwd, ColorFn& inv) {
    if (e == "ycbcr" || e == "ycbcr_checkerboard") {
        fwd = rgbToYCbCr;
        inv = yCbCrToRgb;
    } else if (e == "ycbcr_sqrt") {
        fwd = rgbToYCbCrSqrt;
        inv = yCbCrSqrtToRgb;
    } else if (e == "ycocg" || e == "ycocg_checkerboard") {
        fwd = rgbToYCoCg;
        inv = yCoCgToRgb;
    } else {
        return false;
    }
    return true;
}

// The YCbCr family's chroma uses the midpoint quantiser (neutral = code 2^(bits-1) - 1).
bool midpoint(const std::string& e) { return e == "ycbcr" || e == "ycbcr_sqrt" || e == "ycbcr_checkerboard"; }
uint quantizeC(const std::string& e, float x, uint b) { return midpoint(e) ? quantizeChroma(x, b) : quantizeUnorm(x, b); }
float dequantizeC(const std::string& e, uint c, uint b) {
    return midpoint(e) ? dequantizeChroma(c, b) : dequantizeUnorm(c, b);
}

std::vector<uint> encodeField(const Field& f, const Surface& s, ivec2 pixel) {
    std::vector<uint> c;
    if (isScalar(f)) {
        for (size_t i = 0; i < f.codes.size(); ++i) c.push_back(scalarEncode(f, componentValue(f, s, int(i)), i));
        return c;
    }
    const std::string& e = f.encoding;
    const uint b = uint(f.bitsOfCode(0));
    const vec3 v = wholeValue(f, s);
    ColorFn fwd = nullptr, inv = nullptr;
    if (e == "srgb8") {
        c = {encodeSrgb8(v.x), encodeSrgb8(v.y), encodeSrgb8(v.z)};
    } else if (e == "gamma22") {
        c = {encodeGamma22(v.x), encodeGamma22(v.y), encodeGamma22(v.z)};
    } else if (e == "srgb8_fast_hdrp") {
        c = {encodeSrgb8FastHdrp(v.x), encodeSrgb8FastHdrp(v.y), encodeSrgb8FastHdrp(v.z)};
    } else if (e == "float11_11_10") {
        c = {encodeFloat11(v.x), encodeFloat11(v.y), encodeFloat10(v.z)};
    } else if (e == "float11_11_10_hdrp_ao_tag") {  // HDRP: the AO tag where emissive is exactly 0
        const uvec3 u = encodeFloat111110HdrpAoTag(v, s.occlusion);
        c = {u.x, u.y, u.z};
    } else if (e == "anisotropy_angle_hdrp") {  // HDRP: against the unquantised normal, with the strength
        const uvec3 u = encodeAnisotropyHdrp(v, s.anisotropyStrength, s.normal);
        c = {u.x, u.y, u.z};
    } else if (e == "normal_octahedral_delta_ue") {  // UE: against the unquantised coat normal
        const uvec2 u = encodeNormalOctahedralDeltaUe(v, s.coatNormal, b);
        c = {u.x, u.y};
    } else if (e == "rgb9e5") {
        const uvec4 u = encodeRgb9e5(v);
        c = {u.x, u.y, u.z, u.w};
    } else if (e == "normal_octahedral_bevy" || e == "normal_octahedral_unity" || e == "normal_octahedral_hdrp") {
        const uvec2 u = e == "normal_octahedral_bevy"    ? encodeNormalOctahedralBevy(v, b)
                        : e == "normal_octahedral_unity" ? encodeNormalOctahedralUnity(v, b)
                                                         : encodeNormalOctahedralHdrp(v, b);
        c = {u.x, u.y};
    } else if (e == "normal_xy_float16") {
        const uvec2 u = encodeNormalXyFloat16(v);
        c = {u.x, u.y};
    } else if (e == "emissive_albedo_ratio") {  // niagara: relative to the unquantised albedo
        c = {encodeEmissiveAlbedoRatio(v, s.baseColor, b)};
    } else if (e == "normal_octahedral_dithered") {
        const uvec2 u = encodeNormalOctahedralDithered(v, b, pixel);
        c = {u.x, u.y};
    } else if (e == "luma") {
        c = {quantizeUnorm(lumaBt601(v), b)};
    } else if (e == "ycbcr_checkerboard" || e == "ycocg_checkerboard") {
        colorTransform(e, fwd, inv);
        const vec3 t = fwd(v);
        c = {quantizeUnorm(t.x, b), quantizeC(e, chromaForPixel(pixel, vec2(t.y, t.z)), b)};
    } else if (colorTransform(e, fwd, inv)) {
        const vec3 t = fwd(v);
        c = {quantizeUnorm(t.x, b), quantizeC(e, t.y, b), quantizeC(e, t.z, b)};
    } else if (e == "normal_xyz" || e == "normal_bestfit" || e == "normal_xy_zsign") {
        const uvec3 u = e == "normal_xyz"       ? encodeNormalXyz(v, b)
                        : e == "normal_bestfit" ? encodeNormalBestFit(v)
                                                : encodeNormalXyZSign(v, b);
        c = {u.x, u.y, u.z};
    } else {
        const uvec2 u = e == "normal_spheremap"       ? encodeNormalSpheremap(v, b)
                        : e == "normal_stereographic" ? encodeNormalStereographic(v, b)
                        : e == "normal_octahedral"    ? encodeNormalOctahedral(v, b)
                        : e == "normal_octahedral_precise" ? encodeNormalOctahedralPrecise(v, b)
                                                           : throw std::logic_error("cpu codec: no encoder for " + e);
        c = {u.x, u.y};
    }
    return c;
}

// `s`: the Surface decoded so far (emissive_albedo_ratio reads its base colour).
vec3 decodeField(const Field& f, const std::vector<uint>& c, const Surface& s) {
    const std::string& e = f.encoding;
    if (isScalar(f)) {
        vec3 r(0.0f);
        for (size_t i = 0; i < c.size() && i < 3; ++i) r[int(i)] = scalarDecode(f, c[i], i);
        return r;
    }
    const uint b = uint(f.bitsOfCode(0));
    ColorFn fwd = nullptr, inv = nullptr;
    if (e == "srgb8") return vec3(decodeSrgb8(c[0]), decodeSrgb8(c[1]), decodeSrgb8(c[2]));
    if (e == "gamma22") return vec3(decodeGamma22(c[0]), decodeGamma22(c[1]), decodeGamma22(c[2]));
    if (e == "srgb8_fast_hdrp")
        return vec3(decodeSrgb8FastHdrp(c[0]), decodeSrgb8FastHdrp(c[1]), decodeSrgb8FastHdrp(c[2]));
    if (e == "float11_11_10") return vec3(decodeFloat11(c[0]), decodeFloat11(c[1]), decodeFloat10(c[2]));
    if (e == "float11_11_10_hdrp_ao_tag") return decodeFloat111110HdrpAoTag(uvec3(c[0], c[1], c[2]));
    if (e == "rgb9e5") return decodeRgb9e5(uvec4(c[0], c[1], c[2], c[3]));
    if (e == "anisotropy_angle_hdrp") return decodeAnisotropyHdrp(uvec3(c[0], c[1], c[2]), s.normal);
    if (e == "normal_octahedral_delta_ue") return decodeNormalOctahedralDeltaUe(uvec2(c[0], c[1]), s.coatNormal, b);
    if (e == "normal_octahedral_bevy" || e == "normal_octahedral_unity" || e == "normal_octahedral_hdrp" ||
        e == "normal_octahedral_dithered")
        return decodeNormalOctahedralUnorm(uvec2(c[0], c[1]), b);
    if (e == "emissive_albedo_ratio") return decodeEmissiveAlbedoRatio(c[0], b, s.baseColor);
    if (e == "normal_xy_float16") return decodeNormalXyFloat16(uvec2(c[0], c[1]));
    if (e == "luma") return vec3(dequantizeUnorm(c[0], b));
    if (colorTransform(e, fwd, inv))
        return inv(vec3(dequantizeUnorm(c[0], b), dequantizeC(e, c[1], b), dequantizeC(e, c[2], b)));
    if (e == "normal_xyz") return decodeNormalXyz(uvec3(c[0], c[1], c[2]), b);
    if (e == "normal_bestfit") return decodeNormalBestFit(uvec3(c[0], c[1], c[2]));
    if (e == "normal_xy_zsign") return decodeNormalXyZSign(uvec3(c[0], c[1], c[2]), b);
    if (e == "normal_spheremap") return decodeNormalSpheremap(uvec2(c[0], c[1]), b);
    if (e == "normal_stereographic") return decodeNormalStereographic(uvec2(c[0], c[1]), b);
    if (e == "normal_octahedral") return decodeNormalOctahedral(uvec2(c[0], c[1]), b);
    return decodeNormalOctahedralPrecise(uvec2(c[0], c[1]), b);
}

void placeCode(const Target& t, const CodePlace& cp, uint code, uint32_t* words) {
    int shift = 0;
    for (const BitRange& r : cp.pieces) {
        const int at = t.channels[size_t(r.channel)].offset + r.first;
        const uint mask = r.count >= 32 ? 0xffffffffu : (1u << r.count) - 1u;
        words[at / 32] |= ((code >> shift) & mask) << (at % 32);
        shift += r.count;
    }
}

uint extractCode(const Target& t, const CodePlace& cp, const uint32_t* words) {
    uint code = 0;
    int shift = 0;
    for (const BitRange& r : cp.pieces) {
        const int at = t.channels[size_t(r.channel)].offset + r.first;
        const uint mask = r.count >= 32 ? 0xffffffffu : (1u << r.count) - 1u;
        code |= ((words[at / 32] >> (at % 32)) & mask) << shift;
        shift += r.count;
    }
    return code;
}

int mirror(int p, int size) {
    p = std::abs(p);
    p = (size - 1) - std::abs((size - 1) - p);
    return std::clamp(p, 0, size - 1);
}

void setMember(Surface& s, Attribute a, vec3 v) {
    float* m = memberOf(s, a);
    if (!m) return;
    for (int i = 0; i < components(a); ++i) m[i] = v[i];
}

void applyFallback(const Fallback& fb, Surface& s) {
    switch (fb.kind) {
        case FallbackKind::Constant: {
            vec3 v(0.0f);
            for (int i = 0; i < 3; ++i)
                v[i] = fb.value.empty() ? 0.0f : float(fb.value[std::min<size_t>(size_t(i), fb.value.size() - 1)]);
            setMember(s, fb.attribute, v);
            return;
        }
        case FallbackKind::FromMetallic:
            setMember(s, fb.attribute, vec3(0.04f) * (1.0f - s.metallic) + s.baseColor * s.metallic);
            return;
        case FallbackKind::Ue4:
            setMember(s, fb.attribute, specularColorUE4(s.baseColor, s.metallic, s.specular));
            return;
        case FallbackKind::FromBaseColor:
            setMember(s, fb.attribute, s.baseColor * (1.0f - s.metallic));
            return;
        case FallbackKind::FromDiffuseSpecular:
            setMember(s, fb.attribute, s.diffuseColor + s.metallic * s.specularColor);
            return;
        case FallbackKind::FromSpecularColor: {
            const vec3 f0 = s.specularColor;
            setMember(s, fb.attribute, vec3(clamp((max(f0.x, max(f0.y, f0.z)) - 0.04f) / 0.96f, 0.0f, 1.0f)));
            return;
        }
        case FallbackKind::FromRoughness:
            setMember(s, fb.attribute, vec3(s.roughness));
            return;
        case FallbackKind::Forward:
            setMember(s, fb.attribute, vec3(0.0f));
            return;
        case FallbackKind::MaterialPass:
            return;
    }
}

// The id the selector gives model m (0 when it names none, never asked then).
uint selectorId(const Layout& layout, ShadingModel m) {
    if (const Field* sel = layout.selector())
        for (const Field::ModelId& e : sel->selector)
            if (e.model == m) return e.id;
    return 0;
}

// Whether a pixel whose selector holds `id` is of one of the models in the mask `models`.
bool idAmong(const Layout& layout, uint id, uint32_t models) {
    for (int m = 0; m < kShadingModels; ++m)
        if (((models >> unsigned(m)) & 1u) && ((layout.selectorModels() >> unsigned(m)) & 1u) &&
            selectorId(layout, ShadingModel(m)) == id)
            return true;
    return false;
}

CpuGBuffer encodeGBuffer(const Layout& layout, const std::vector<Surface>& surfaces, int width, int height) {
    CpuGBuffer g;
    g.width = width;
    g.height = height;
    const size_t pixels = surfaces.size();
    for (const Target& t : layout.targets) {
        const int wpp = wordsPerPixel(t);
        std::vector<uint32_t> words(pixels * size_t(wpp), 0u);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const size_t i = size_t(y) * size_t(width) + size_t(x);
                uint32_t* w = &words[i * size_t(wpp)];
                const ShadingModel model = test::statedModel(layout, surfaces[i]);
                for (const Field& f : t.fields) {
                    if (!f.selector.empty()) {
                        placeCode(t, f.codes[0], selectorId(layout, model), w);
                        continue;
                    }
                    if (!test::fieldHolds(f, model)) continue;
                    const std::vector<uint> codes = encodeField(f, surfaces[i], ivec2(x, y));
                    for (size_t k = 0; k < codes.size(); ++k) placeCode(t, f.codes[k], codes[k], w);
                }
            }
        g.targetWords.push_back(std::move(words));
    }
    const int mt = materialTargetCount(layout);
    g.materialWords.assign(size_t(mt), std::vector<uint32_t>(pixels * 4, 0u));
    for (const MaterialSlot& slot : materialPassSlots(layout))
        for (size_t i = 0; i < pixels; ++i)
            for (int c = 0; c < slot.components; ++c) {
                const int k = slot.firstFloat + c;
                g.materialWords[size_t(k / 4)][i * 4 + size_t(k % 4)] =
                    floatBitsToUint(memberOf(surfaces[i], slot.attribute)[c]);
            }
    return g;
}

std::vector<Surface> decodeGBuffer(const Layout& layout, const CpuGBuffer& g) {
    const int width = g.width, height = g.height;
    const size_t pixels = size_t(width) * size_t(height);
    std::vector<Surface> out(pixels);
    const std::vector<const Fallback*> fallbacks = orderedFallbacks(layout);
    const std::vector<MaterialSlot> slots = materialPassSlots(layout);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            Surface& s = out[i];
            s = Surface{};
            s.normal = vec3(0.0f);
            s.occlusion = 0.0f;
            uint id = 0;  // the stored id, read first: it decides which fields hold
            bool hasId = false;
            for (size_t t = 0; t < layout.targets.size(); ++t)
                for (const Field& f : layout.targets[t].fields)
                    if (!f.selector.empty()) {
                        const size_t wpp = size_t(wordsPerPixel(layout.targets[t]));
                        id = extractCode(layout.targets[t], f.codes[0], &g.targetWords[t][i * wpp]);
                        hasId = true;
                    }
            if (hasId) s.shadingModel = float(id);
            for (const AttributeInfo& a : listAttributes())  // stored under some models: from 0
                if (layout.storesConditionally(a.id)) setMember(s, a.id, vec3(0.0f));
            for (size_t t = 0; t < layout.targets.size(); ++t) {
                const Target& tg = layout.targets[t];
                const int wpp = wordsPerPixel(tg);
                auto wordsAt = [&](int px, int py) {
                    return &g.targetWords[t][(size_t(py) * size_t(width) + size_t(px)) * size_t(wpp)];
                };
                const uint32_t* w = wordsAt(x, y);
                for (const Field& f : tg.fields) {
                    if (!memberOf(s, f.attribute)) continue;
                    if (f.conditional() && !idAmong(layout, id, f.models)) continue;
                    const EncodingInfo* info = findEncoding(f.encoding);
                    if (info && info->needsNeighbours) {
                        ColorFn fwd = nullptr, inv = nullptr;
                        colorTransform(f.encoding, fwd, inv);
                        const uint b = uint(f.bitsOfCode(0));
                        auto lumaChroma = [&](int px, int py) {
                            const uint32_t* nw = wordsAt(px, py);
                            return vec2(dequantizeUnorm(extractCode(tg, f.codes[0], nw), b),
                                        dequantizeC(f.encoding, extractCode(tg, f.codes[1], nw), b));
                        };
                        auto cover = [&](int px, int py) {
                            return g.covered.empty() || g.covered[size_t(py) * size_t(width) + size_t(px)] ? 1.0f
                                                                                                             : 0.0f;
                        };
                        const vec2 c = lumaChroma(x, y);
                        const vec2 n0 = lumaChroma(mirror(x + 1, width), mirror(y, height));
                        const vec2 n1 = lumaChroma(mirror(x - 1, width), mirror(y, height));
                        const vec2 n2 = lumaChroma(mirror(x, width), mirror(y + 1, height));
                        const vec2 n3 = lumaChroma(mirror(x, width), mirror(y - 1, height));
                        const vec4 covered(cover(mirror(x + 1, width), mirror(y, height)),
                                           cover(mirror(x - 1, width), mirror(y, height)),
                                           cover(mirror(x, width), mirror(y + 1, height)),
                                           cover(mirror(x, width), mirror(y - 1, height)));
                        const vec2 ch = reconstructChroma(ivec2(x, y), c.x, c.y, vec4(n0.x, n1.x, n2.x, n3.x),
                                                          vec4(n0.y, n1.y, n2.y, n3.y), covered);
                        setMember(s, f.attribute, inv(vec3(c.x, ch.x, ch.y)));
                        continue;
                    }
                    std::vector<uint> codes;
                    for (const CodePlace& cp : f.codes) codes.push_back(extractCode(tg, cp, w));
                    setMember(s, f.attribute, decodeField(f, codes, s));
                    if (f.encoding == "float11_11_10_hdrp_ao_tag")  // what the AO tag also stores
                        s.occlusion = decodeHdrpAoTagOcclusion(uvec3(codes[0], codes[1], codes[2]));
                    if (f.encoding == "anisotropy_angle_hdrp")  // HDRP's anisotropy: the strength
                        s.anisotropyStrength = decodeAnisotropyHdrpStrength(uvec3(codes[0], codes[1], codes[2]));
                }
            }
            for (const MaterialSlot& slot : slots) {
                vec3 v(0.0f);
                for (int c = 0; c < slot.components; ++c) {
                    const int k = slot.firstFloat + c;
                    v[c] = uintBitsToFloat(g.materialWords[size_t(k / 4)][i * 4 + size_t(k % 4)]);
                }
                setMember(s, slot.attribute, v);
            }
            for (const Fallback* fb : fallbacks)
                if (!idAmong(layout, id, layout.conditionalModels(fb->attribute))) applyFallback(*fb, s);
        }
    return out;
}

}  // namespace reference

// ---------------------------------------------------------------------------------------------

glm::vec3 randomUnit(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    glm::vec3 n;
    do n = glm::vec3(u(rng), u(rng), u(rng));
    while (glm::dot(n, n) > 1.0f || glm::dot(n, n) < 1e-4f);
    return glm::normalize(n);
}

// Mostly in-range values, with a share of what the encoders clamp or round at the edges: exact
// 0 and 1, -0, values outside [0,1], float16 overflow, tiny and huge magnitudes, axis normals and
// non-unit normals. All finite: float -> integer conversion of NaN is undefined in C++.
std::vector<Surface> makeSurfaces(int w, int h, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float edges[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 1e-30f, -1e-30f, 1.5f, -0.25f, 70000.0f, -70000.0f,
                           1e-7f, 0.99999994f, 0.54705882f, std::numeric_limits<float>::denorm_min()};
    auto value = [&](float scale) {
        const float r = u(rng);
        if (r < 0.1f) return edges[size_t(u(rng) * float(std::size(edges))) % std::size(edges)];
        if (r < 0.2f) return (u(rng) * 3.0f - 1.0f) * scale;
        return u(rng) * scale;
    };
    std::vector<Surface> v(size_t(w) * size_t(h));
    for (Surface& s : v) {
        const float r = u(rng);
        if (r < 0.05f) {
            glm::vec3 axis(0.0f);
            axis[int(u(rng) * 3.0f) % 3] = u(rng) < 0.5f ? -1.0f : 1.0f;
            s.normal = axis;
        } else if (r < 0.1f) {
            s.normal = randomUnit(rng) * (0.5f + u(rng));
        } else {
            s.normal = randomUnit(rng);
        }
        s.baseColor = {value(1), value(1), value(1)};
        s.metallic = value(1);
        s.roughness = value(1);
        s.specular = value(1);
        s.specularColor = {value(1), value(1), value(1)};
        s.diffuseColor = {value(1), value(1), value(1)};
        s.occlusion = value(1);
        s.emissive = {value(8), value(8), value(8)};
        s.position = {value(100), value(100), value(100)};
        s.coat = value(1);
        s.coatRoughness = value(1);
        s.coatNormal = randomUnit(rng);
        s.sheenColor = {value(1), value(1), value(1)};
        s.sheenRoughness = value(1);
        s.anisotropyStrength = value(1);
        s.anisotropyDirection = randomUnit(rng);
    }
    // Each combination of layers (and so each model of a selector's rule) on its own pixels.
    test::assignLayerPatterns(v);
    return v;
}

// Counts words that differ; reports the first few.
size_t compareWords(const CpuGBuffer& a, const CpuGBuffer& b, const std::string& what) {
    size_t bad = 0;
    EXPECT_EQ(a.targetWords.size(), b.targetWords.size()) << what;
    EXPECT_EQ(a.materialWords.size(), b.materialWords.size()) << what;
    auto compare = [&](const std::vector<std::vector<uint32_t>>& x, const std::vector<std::vector<uint32_t>>& y,
                       const char* kind) {
        for (size_t t = 0; t < std::min(x.size(), y.size()); ++t) {
            EXPECT_EQ(x[t].size(), y[t].size()) << what << " " << kind << " " << t;
            for (size_t i = 0; i < std::min(x[t].size(), y[t].size()); ++i)
                if (x[t][i] != y[t][i] && bad++ < 5)
                    ADD_FAILURE() << what << ": " << kind << " " << t << " word " << i << ": 0x" << std::hex
                                  << x[t][i] << " vs 0x" << y[t][i];
        }
    };
    compare(a.targetWords, b.targetWords, "target");
    compare(a.materialWords, b.materialWords, "material target");
    return bad;
}

// Counts Surfaces whose bytes differ (bit-identical floats: -0 and +0 differ too).
size_t compareSurfaces(const std::vector<Surface>& a, const std::vector<Surface>& b, const std::string& what) {
    EXPECT_EQ(a.size(), b.size()) << what;
    size_t bad = 0;
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
        if (std::memcmp(&a[i], &b[i], sizeof(Surface)) != 0 && bad++ < 5) {
            const float* x = &a[i].normal.x;
            const float* y = &b[i].normal.x;
            int k = 0;
            while (k < 21 && std::memcmp(x + k, y + k, sizeof(float)) == 0) ++k;
            ADD_FAILURE() << what << ": pixel " << i << " float " << k << ": " << x[k] << " vs " << y[k];
        }
    return bad;
}

// ---------------------------------------------------------------------------------------------

TEST(CpuCodec, EveryLayoutMatchesTheReferenceAtEveryThreadCount) {
    const std::vector<Layout> layouts = test::shippedAttributeLayouts();
    ASSERT_GE(layouts.size(), 7u);
    // Sizes: block edges (kBlock = 128 pixels per row block), one row, one column, one pixel, and
    // more rows than threads and fewer.
    const std::pair<int, int> sizes[] = {{131, 67}, {128, 3}, {257, 130}, {1, 1}, {1, 9}, {9, 1}, {2, 2}};
    uint32_t seed = 11;
    for (const Layout& layout : layouts) {
        for (const auto& [w, h] : sizes) {
            SCOPED_TRACE(layout.name + " " + std::to_string(w) + "x" + std::to_string(h));
            const std::vector<Surface> in = makeSurfaces(w, h, seed++);
            const CpuGBuffer ref = reference::encodeGBuffer(layout, in, w, h);
            const std::vector<Surface> refDecoded = reference::decodeGBuffer(layout, ref);
            for (int threads : {1, 2, 3, 8}) {
                const std::string what = layout.name + " threads " + std::to_string(threads);
                const CpuCodec codec(layout, CpuCodecOptions{threads});
                const CpuGBuffer g = codec.encode(in, w, h);
                EXPECT_EQ(compareWords(g, ref, what), 0u);
                EXPECT_EQ(compareSurfaces(codec.decode(g), refDecoded, what), 0u);
            }
            // The one-shot forms and buffer reuse (a second encode into the same CpuGBuffer).
            EXPECT_EQ(compareWords(encodeGBuffer(layout, in, w, h), ref, "encodeGBuffer"), 0u);
            EXPECT_EQ(compareSurfaces(decodeGBuffer(layout, ref), refDecoded, "decodeGBuffer"), 0u);
            const CpuCodec codec(layout);
            CpuGBuffer reused = codec.encode(makeSurfaces(w, h, seed + 1000), w, h);
            std::vector<Surface> decoded(3);
            codec.encode(in, w, h, reused);
            codec.decode(reused, decoded);
            EXPECT_EQ(compareWords(reused, ref, "reused buffers"), 0u);
            EXPECT_EQ(compareSurfaces(decoded, refDecoded, "reused buffers"), 0u);
        }
    }
}

// A large image, where every thread gets many bands' worth of rows, at 1 and 2 threads.
TEST(CpuCodec, LargeImageIsTheSameAtOneAndTwoThreads) {
    constexpr int w = 640, h = 360;
    for (const Layout& layout : test::shippedAttributeLayouts()) {
        SCOPED_TRACE(layout.name);
        const std::vector<Surface> in = makeSurfaces(w, h, 99u);
        const CpuCodec one(layout, CpuCodecOptions{1}), two(layout, CpuCodecOptions{2});
        const CpuGBuffer a = one.encode(in, w, h), b = two.encode(in, w, h);
        EXPECT_EQ(compareWords(a, b, layout.name), 0u);
        EXPECT_EQ(compareSurfaces(one.decode(a), two.decode(b), layout.name), 0u);
    }
}

// Checkerboard chroma with a geometry mask: the optimised decode equals the per-pixel reference,
// and a silhouette pixel never takes chroma from a neighbour without geometry.
TEST(CpuCodec, CheckerboardChromaSkipsPixelsWithoutGeometry) {
    const Layout layout = test::shippedLayout("crysis3-thin");
    const CpuCodec codec(layout);
    for (const auto& [w, h] : {std::pair<int, int>{131, 67}, {2, 2}, {1, 9}}) {
        CpuGBuffer g = codec.encode(makeSurfaces(w, h, 7u), w, h);
        g.covered.resize(size_t(w) * size_t(h));
        for (size_t i = 0; i < g.covered.size(); ++i) g.covered[i] = (i * 7 % 5) != 0;
        EXPECT_EQ(compareSurfaces(codec.decode(g), reference::decodeGBuffer(layout, g), "covered"), 0u);
    }
    // 3x3: the centre and its +x neighbour are red surfaces; the other pixels hold a blue-violet
    // whose luma is within the edge threshold of red's (0.231 vs 0.299), so without the mask the
    // filter would average their chroma in.
    std::vector<Surface> in(9);
    for (Surface& s : in) s.diffuseColor = glm::vec3(0.0f, 0.2f, 1.0f);
    in[4].diffuseColor = in[5].diffuseColor = glm::vec3(1.0f, 0.0f, 0.0f);
    CpuGBuffer g = codec.encode(in, 3, 3);
    const glm::vec3 unmasked = codec.decode(g)[4].diffuseColor;
    g.covered.assign(9, 0);
    g.covered[4] = g.covered[5] = 1;
    const glm::vec3 masked = codec.decode(g)[4].diffuseColor;
    EXPECT_GT(glm::length(unmasked - glm::vec3(1, 0, 0)), 0.1f) << "the 3x3 case no longer exercises the mask";
    EXPECT_LT(glm::length(masked - glm::vec3(1, 0, 0)), 0.02f) << masked.x << " " << masked.y << " " << masked.z;
    // No covered neighbour at all: the missing chroma is neutral.
    g.covered.assign(9, 0);
    g.covered[4] = 1;
    in.assign(9, Surface{});
    for (Surface& s : in) s.diffuseColor = glm::vec3(0.5f);
    g = codec.encode(in, 3, 3);
    g.covered.assign(9, 0);
    g.covered[4] = 1;
    const glm::vec3 grey = codec.decode(g)[4].diffuseColor;
    EXPECT_NEAR(grey.x, grey.z, 1e-6f);
}

}  // namespace
}  // namespace gbl


namespace gbl {
// The engines' own clear colours, as the layouts declare them ([clear]): the words a target is
// cleared with are the engine's. niagara clears both colour targets to (135, 206, 250, 15) / 255
// (zeux/niagara @95f289b7 src/niagara.cpp:1762): RGBA8 codes 135, 206, 250 and the emissive ratio
// 15; in A2B10G10R10 the 10-bit codes 542, 826, 1003 and 0 (its normal's dither at pixel (0, 0)
// keeps 542 and 826). HDRP's GBuffer1 clear is Color.black = (0, 0, 0, 1): octahedral codes (0, 0)
// and roughness code 255; URP's accurate-normals GBuffer2 clears to 0 (RenderGraph).
TEST(CpuCodec, EngineClearWordsAreTheEnginesClearColours) {
    const auto niagara = clearWords(test::shippedLayout("niagara"));
    ASSERT_EQ(niagara.size(), 2u);
    EXPECT_EQ(niagara[0][0], 135u | 206u << 8 | 250u << 16 | 15u << 24);
    EXPECT_EQ(niagara[1][0], 542u | 826u << 10 | 1003u << 20);
    const auto hdrp = clearWords(test::shippedLayout("hdrp-lit"));
    ASSERT_EQ(hdrp.size(), 4u);
    EXPECT_EQ(hdrp[1][0], 0xFF000000u);  // GBuffer1: R = G = B = 0 (codes (0, 0)), A = 255
    // GBuffer0: diffuse 0; its alpha, specular occlusion, is an extra (1 in every pixel: the
    // layout's documented difference from HDRP's 0).
    EXPECT_EQ(hdrp[0][0], 0xFF000000u);
    EXPECT_EQ(hdrp[2][0], 0u);
    EXPECT_EQ(hdrp[3][0], 0u);  // GBuffer3: Color.clear, the word 0, not the AO tag
    EXPECT_EQ(clearWords(test::shippedLayout("hdrp-lit-apv"))[3][0], 0u);
    const auto urp = clearWords(test::shippedLayout("urp-deferred-accurate"));
    ASSERT_EQ(urp.size(), 3u);
    EXPECT_EQ(urp[2][0], 0u);  // GBuffer2: octahedral codes (0, 0), smoothness 0
    // UE clears every G-buffer code to 0; its extras (shading model, mask, per-object, precomputed
    // shadow) are the one documented difference: gbufferlab writes their values in every pixel.
    const auto ue5 = clearWords(test::shippedLayout("ue5"));
    ASSERT_EQ(ue5.size(), 5u);
    EXPECT_EQ(ue5[0][0], 1u << 30);           // GBufferA: normal codes 0, per-object code 1
    EXPECT_EQ(ue5[1][0], 0x81u << 24);        // GBufferB: B8G8R8A8, alpha = 1 | 8 << 4
    EXPECT_EQ(ue5[2][0], 0u);                 // GBufferC: base colour 0, precomputed irradiance 0
}

}  // namespace gbl
