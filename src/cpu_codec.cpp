#include "cpu_codec.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "encoding_registry.h"
#include "encodings.h"
#include "wiring_codegen.h"

namespace gbl {

using namespace enc;

namespace {

int components(Attribute a) { return attributeInfo(a).components; }

float* member(Surface& s, Attribute a) {
    switch (a) {
        case Attribute::Normal: return &s.normal.x;
        case Attribute::BaseColor: return &s.baseColor.x;
        case Attribute::Metallic: return &s.metallic;
        case Attribute::Roughness: return &s.roughness;
        case Attribute::Specular: return &s.specular;
        case Attribute::SpecularColor: return &s.specularColor.x;
        case Attribute::DiffuseColor: return &s.diffuseColor.x;
        case Attribute::Occlusion: return &s.occlusion;
        case Attribute::Emissive: return &s.emissive.x;
        case Attribute::Position: return &s.position.x;
        default: return nullptr;
    }
}
const float* member(const Surface& s, Attribute a) { return member(const_cast<Surface&>(s), a); }

bool isScalar(const Field& f) {
    return f.encoding == kIdEncoding || findEncoding(f.encoding)->kind == AttributeKind::Scalar;
}

// Component i of the field's attribute (a Surface member, or the extra's declared constant).
float componentValue(const Field& f, const Surface& s, int i) {
    if (const float* m = member(s, f.attribute)) return m[i];
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

// The field's codes at one pixel (mirror of emitEncodeField).
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
    } else if (e == "luma") {
        c = {quantizeUnorm(lumaBt601(v), b)};
    } else if (e == "ycbcr_checkerboard" || e == "ycocg_checkerboard") {
        colorTransform(e, fwd, inv);
        const vec3 t = fwd(v);
        c = {quantizeUnorm(t.x, b), quantizeUnorm(chromaForPixel(pixel, vec2(t.y, t.z)), b)};
    } else if (colorTransform(e, fwd, inv)) {
        const vec3 t = fwd(v);
        c = {quantizeUnorm(t.x, b), quantizeUnorm(t.y, b), quantizeUnorm(t.z, b)};
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

// Decoded attribute of a non-checkerboard field from its codes (mirror of decodeFieldExpr).
vec3 decodeField(const Field& f, const std::vector<uint>& c) {
    const std::string& e = f.encoding;
    if (isScalar(f)) {
        vec3 r(0.0f);
        for (size_t i = 0; i < c.size() && i < 3; ++i) r[int(i)] = scalarDecode(f, c[i], i);
        return r;
    }
    const uint b = uint(f.bitsOfCode(0));
    ColorFn fwd = nullptr, inv = nullptr;
    if (e == "srgb8") return vec3(decodeSrgb8(c[0]), decodeSrgb8(c[1]), decodeSrgb8(c[2]));
    if (e == "luma") return vec3(dequantizeUnorm(c[0], b));
    if (colorTransform(e, fwd, inv))
        return inv(vec3(dequantizeUnorm(c[0], b), dequantizeUnorm(c[1], b), dequantizeUnorm(c[2], b)));
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
    float* m = member(s, a);
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
        case FallbackKind::Forward:
            setMember(s, fb.attribute, vec3(0.0f));
            return;
        case FallbackKind::MaterialPass:
            return;  // read by decodeGBuffer from the material words
    }
}

}  // namespace

CpuGBuffer encodeGBuffer(const Layout& layout, const std::vector<Surface>& surfaces, int width, int height) {
    if (surfaces.size() != size_t(width) * size_t(height))
        throw std::invalid_argument("encodeGBuffer: surfaces do not match width * height");
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
                for (const Field& f : t.fields) {
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
                    floatBitsToUint(member(surfaces[i], slot.attribute)[c]);
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
            for (size_t t = 0; t < layout.targets.size(); ++t) {
                const Target& tg = layout.targets[t];
                const int wpp = wordsPerPixel(tg);
                auto wordsAt = [&](int px, int py) {
                    return &g.targetWords[t][(size_t(py) * size_t(width) + size_t(px)) * size_t(wpp)];
                };
                const uint32_t* w = wordsAt(x, y);
                for (const Field& f : tg.fields) {
                    if (!member(s, f.attribute)) continue;
                    const EncodingInfo* info = findEncoding(f.encoding);
                    if (info && info->needsNeighbours) {
                        ColorFn fwd = nullptr, inv = nullptr;
                        colorTransform(f.encoding, fwd, inv);
                        const uint b = uint(f.bitsOfCode(0));
                        auto lumaChroma = [&](int px, int py) {
                            const uint32_t* nw = wordsAt(px, py);
                            return vec2(dequantizeUnorm(extractCode(tg, f.codes[0], nw), b),
                                        dequantizeUnorm(extractCode(tg, f.codes[1], nw), b));
                        };
                        const vec2 c = lumaChroma(x, y);
                        const vec2 n0 = lumaChroma(mirror(x + 1, width), mirror(y, height));
                        const vec2 n1 = lumaChroma(mirror(x - 1, width), mirror(y, height));
                        const vec2 n2 = lumaChroma(mirror(x, width), mirror(y + 1, height));
                        const vec2 n3 = lumaChroma(mirror(x, width), mirror(y - 1, height));
                        const vec2 ch = reconstructChroma(ivec2(x, y), c.x, c.y, vec4(n0.x, n1.x, n2.x, n3.x),
                                                          vec4(n0.y, n1.y, n2.y, n3.y));
                        setMember(s, f.attribute, inv(vec3(c.x, ch.x, ch.y)));
                        continue;
                    }
                    std::vector<uint> codes;
                    for (const CodePlace& cp : f.codes) codes.push_back(extractCode(tg, cp, w));
                    setMember(s, f.attribute, decodeField(f, codes));
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
            for (const Fallback* fb : fallbacks) applyFallback(*fb, s);
        }
    return out;
}

}  // namespace gbl
