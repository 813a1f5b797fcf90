#include "wiring_codegen.h"

#include "visibility_wiring.h"

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>

#include "cpu_codec.h"
#include "encoding_registry.h"
#include "glsl_text.h"
#include "light_buffer_wiring.h"

namespace gbl {

namespace {

std::string ulit(uint64_t v) { return std::to_string(v) + "u"; }

std::string maskLit(int bits) { return bits >= 32 ? "0xffffffffu" : ulit((uint64_t(1) << bits) - 1); }

const char* kComp[] = {"x", "y", "z", "w"};

int channelComponent(const Channel& c) {
    if (c.name == "r") return 0;
    if (c.name == "g") return 1;
    if (c.name == "b") return 2;
    return 3;
}

int attributeComponents(Attribute a) { return attributeInfo(a).components; }

// Value of component `i` of a field's attribute: a Surface member or the extra's constant.
std::string componentExpr(const Field& f, int i) {
    const int n = attributeComponents(f.attribute);
    if (const char* m = surfaceMemberName(f.attribute)) {
        std::string e = std::string("s.") + m;
        return n == 1 ? e : e + "." + kComp[i];
    }
    const double v = f.value.empty() ? 0.0 : f.value[std::min<size_t>(size_t(i), f.value.size() - 1)];
    if (f.encoding == kIdEncoding) return ulit(uint64_t(v));
    return glslFloatLiteral(v);
}

// The whole value (vec3) of a field's attribute.
std::string wholeExpr(const Field& f) {
    if (const char* m = surfaceMemberName(f.attribute)) return std::string("s.") + m;
    return "vec3(" + componentExpr(f, 0) + ", " + componentExpr(f, 1) + ", " + componentExpr(f, 2) + ")";
}

const EncodingInfo& encodingOf(const Field& f) {
    const EncodingInfo* e = findEncoding(f.encoding);
    if (!e) throw std::logic_error("wiring: unknown encoding " + f.encoding);
    return *e;
}

// The Surface member of the attribute an encoding reads besides its own (emissive_albedo_ratio:
// "s.baseColor"): at write time the unquantised value, at read time the value decoded before it.
std::string readsExpr(const EncodingInfo& e) {
    const AttributeInfo* a = findAttribute(e.reads);
    const char* m = a ? surfaceMemberName(a->id) : nullptr;
    if (!m) throw std::logic_error("wiring: encoding " + e.name + " reads unknown attribute " + e.reads);
    return std::string("s.") + m;
}

bool isScalarField(const Field& f) { return f.encoding == kIdEncoding || encodingOf(f).kind == AttributeKind::Scalar; }

std::string scalarEncode(const std::string& enc, const std::string& x, int bits) {
    const std::string b = ulit(uint64_t(bits));
    if (enc == kIdEncoding) return x;
    if (enc == "unorm") return "quantizeUnorm(" + x + ", " + b + ")";
    if (enc == "snorm") return "quantizeSnorm(" + x + ", " + b + ")";
    if (enc == "float16") return "encodeFloat16(" + x + ")";
    if (enc == "float11") return "encodeFloat11(" + x + ")";
    if (enc == "float10") return "encodeFloat10(" + x + ")";
    if (enc == "float32") return "encodeFloat32(" + x + ")";
    if (enc == "depth24") return "quantizeDepth24(" + x + ")";
    if (enc == "gloss") return "quantizeUnorm(glossFromRoughness(" + x + "), " + b + ")";
    if (enc == "smoothness_cry") return "quantizeUnorm(smoothnessFromRoughnessCry(" + x + "), " + b + ")";
    if (enc == "cry_gloss_power") return "encodeCryGlossPower(" + x + ")";
    if (enc == "reflectance") return "quantizeUnorm(reflectanceFromSpecular(" + x + "), " + b + ")";
    throw std::logic_error("wiring: no scalar encoder for " + enc);
}

std::string scalarDecode(const std::string& enc, const std::string& c, int bits) {
    const std::string b = ulit(uint64_t(bits));
    if (enc == "unorm") return "dequantizeUnorm(" + c + ", " + b + ")";
    if (enc == "snorm") return "dequantizeSnorm(" + c + ", " + b + ")";
    if (enc == "float16") return "decodeFloat16(" + c + ")";
    if (enc == "float11") return "decodeFloat11(" + c + ")";
    if (enc == "float10") return "decodeFloat10(" + c + ")";
    if (enc == "float32") return "decodeFloat32(" + c + ")";
    if (enc == "depth24") return "dequantizeDepth24(" + c + ")";
    if (enc == "gloss") return "roughnessFromGloss(dequantizeUnorm(" + c + ", " + b + "))";
    if (enc == "smoothness_cry") return "roughnessFromSmoothnessCry(dequantizeUnorm(" + c + ", " + b + "))";
    if (enc == "cry_gloss_power") return "decodeCryGlossPower(" + c + ")";
    if (enc == "reflectance") return "specularFromReflectance(dequantizeUnorm(" + c + ", " + b + "))";
    throw std::logic_error("wiring: no scalar decoder for " + enc);
}

// Colour transforms of the YCbCr family: forward, inverse.
bool colorTransform(const std::string& enc, std::string& fwd, std::string& inv) {
    if (enc == "ycbcr" || enc == "ycbcr_checkerboard") {
        fwd = "rgbToYCbCr";
        inv = "yCbCrToRgb";
    } else if (enc == "ycbcr_sqrt") {
        fwd = "rgbToYCbCrSqrt";
        inv = "yCbCrSqrtToRgb";
    } else if (enc == "ycocg" || enc == "ycocg_checkerboard") {
        fwd = "rgbToYCoCg";
        inv = "yCoCgToRgb";
    } else {
        return false;
    }
    return true;
}

// The YCbCr family (CryEngine's) quantises its chroma with quantizeChroma, whose midpoint code is
// exactly neutral; YCoCg keeps the paper's quantizeUnorm of chroma + 0.5.
bool midpointChroma(const std::string& enc) {
    return enc == "ycbcr" || enc == "ycbcr_sqrt" || enc == "ycbcr_checkerboard";
}
std::string chromaQuantize(const std::string& enc) { return midpointChroma(enc) ? "quantizeChroma" : "quantizeUnorm"; }
std::string chromaDequantize(const std::string& enc) {
    return midpointChroma(enc) ? "dequantizeChroma" : "dequantizeUnorm";
}

// Emits the encoder of a field: setup lines, returns one uint expression per code.
std::vector<std::string> emitEncodeField(std::ostream& o, const std::string& ind, const Field& f, const std::string& id) {
    std::vector<std::string> codes;
    if (isScalarField(f)) {
        for (size_t i = 0; i < f.codes.size(); ++i)
            codes.push_back(scalarEncode(f.encoding, componentExpr(f, int(i)), f.bitsOfCode(i)));
        return codes;
    }
    const std::string& e = f.encoding;
    const std::string b = ulit(uint64_t(f.bitsOfCode(0)));
    const std::string v = wholeExpr(f);
    std::string fwd, inv;
    if (e == "srgb8" || e == "gamma22") {
        const std::string fn = e == "srgb8" ? "encodeSrgb8(" : "encodeGamma22(";
        for (int i = 0; i < 3; ++i) codes.push_back(fn + v + "." + kComp[i] + ")");
    } else if (e == "float11_11_10") {
        codes.push_back("encodeFloat11(" + v + ".x)");
        codes.push_back("encodeFloat11(" + v + ".y)");
        codes.push_back("encodeFloat10(" + v + ".z)");
    } else if (e == "rgb9e5") {
        o << ind << "uvec4 " << id << " = encodeRgb9e5(" << v << ");\n";
        for (int i = 0; i < 4; ++i) codes.push_back(id + "." + kComp[i]);
    } else if (e == "normal_octahedral_bevy" || e == "normal_octahedral_unity") {
        o << ind << "uvec2 " << id << " = encodeNormalOctahedralTrunc(" << v << ", " << b << ", "
          << (e == "normal_octahedral_bevy" ? "0.0" : "0.5") << ");\n";
        for (int i = 0; i < 2; ++i) codes.push_back(id + "." + kComp[i]);
    } else if (e == "normal_xy_float16") {
        o << ind << "uvec2 " << id << " = encodeNormalXyFloat16(" << v << ");\n";
        for (int i = 0; i < 2; ++i) codes.push_back(id + "." + kComp[i]);
    } else if (e == "luma") {
        codes.push_back("quantizeUnorm(lumaBt601(" + v + "), " + b + ")");
    } else if (e == "emissive_albedo_ratio") {
        codes.push_back("encodeEmissiveAlbedoRatio(" + v + ", " + readsExpr(encodingOf(f)) + ", " + b + ")");
    } else if (e == "normal_octahedral_dithered") {
        o << ind << "uvec2 " << id << " = encodeNormalOctahedralDithered(" << v << ", " << b << ", pixel);\n";
        for (int i = 0; i < 2; ++i) codes.push_back(id + "." + kComp[i]);
    } else if (e == "ycbcr_checkerboard" || e == "ycocg_checkerboard") {
        colorTransform(e, fwd, inv);
        o << ind << "vec3 " << id << " = " << fwd << "(" << v << ");\n";
        codes.push_back("quantizeUnorm(" + id + ".x, " + b + ")");
        codes.push_back(chromaQuantize(e) + "(chromaForPixel(pixel, vec2(" + id + ".y, " + id + ".z)), " + b + ")");
    } else if (colorTransform(e, fwd, inv)) {
        o << ind << "vec3 " << id << " = " << fwd << "(" << v << ");\n";
        for (int i = 0; i < 3; ++i)
            codes.push_back((i ? chromaQuantize(e) : std::string("quantizeUnorm")) + "(" + id + "." + kComp[i] + ", " + b + ")");
    } else if (e == "normal_xyz" || e == "normal_bestfit" || e == "normal_xy_zsign") {
        const std::string call = e == "normal_xyz"       ? "encodeNormalXyz(" + v + ", " + b + ")"
                                 : e == "normal_bestfit" ? "encodeNormalBestFit(" + v + ")"
                                                         : "encodeNormalXyZSign(" + v + ", " + b + ")";
        o << ind << "uvec3 " << id << " = " << call << ";\n";
        for (int i = 0; i < 3; ++i) codes.push_back(id + "." + kComp[i]);
    } else if (e == "normal_spheremap" || e == "normal_stereographic" || e == "normal_octahedral" ||
               e == "normal_octahedral_precise") {
        const std::string fn = e == "normal_spheremap"       ? "encodeNormalSpheremap"
                               : e == "normal_stereographic" ? "encodeNormalStereographic"
                               : e == "normal_octahedral"    ? "encodeNormalOctahedral"
                                                             : "encodeNormalOctahedralPrecise";
        o << ind << "uvec2 " << id << " = " << fn << "(" << v << ", " << b << ");\n";
        for (int i = 0; i < 2; ++i) codes.push_back(id + "." + kComp[i]);
    } else {
        throw std::logic_error("wiring: no encoder for " + e);
    }
    return codes;
}

// Decoded value of a (non-checkerboard) field from its code expressions; "" for extras.
std::string decodeFieldExpr(const Field& f, const std::vector<std::string>& c) {
    const std::string& e = f.encoding;
    if (isScalarField(f)) {
        if (e == kIdEncoding) return "";
        std::vector<std::string> parts;
        for (size_t i = 0; i < c.size(); ++i) parts.push_back(scalarDecode(e, c[i], f.bitsOfCode(i)));
        if (parts.size() == 1) return parts[0];
        std::string s = "vec" + std::to_string(parts.size()) + "(";
        for (size_t i = 0; i < parts.size(); ++i) s += (i ? ", " : "") + parts[i];
        return s + ")";
    }
    const std::string b = ulit(uint64_t(f.bitsOfCode(0)));
    std::string fwd, inv;
    if (e == "srgb8") return "vec3(decodeSrgb8(" + c[0] + "), decodeSrgb8(" + c[1] + "), decodeSrgb8(" + c[2] + "))";
    if (e == "gamma22")
        return "vec3(decodeGamma22(" + c[0] + "), decodeGamma22(" + c[1] + "), decodeGamma22(" + c[2] + "))";
    if (e == "float11_11_10")
        return "vec3(decodeFloat11(" + c[0] + "), decodeFloat11(" + c[1] + "), decodeFloat10(" + c[2] + "))";
    if (e == "rgb9e5") return "decodeRgb9e5(uvec4(" + c[0] + ", " + c[1] + ", " + c[2] + ", " + c[3] + "))";
    if (e == "emissive_albedo_ratio")
        return "decodeEmissiveAlbedoRatio(" + c[0] + ", " + b + ", " + readsExpr(encodingOf(f)) + ")";
    if (e == "normal_octahedral_bevy" || e == "normal_octahedral_unity" || e == "normal_octahedral_dithered")
        return "decodeNormalOctahedralTrunc(uvec2(" + c[0] + ", " + c[1] + "), " + b + ")";
    if (e == "normal_xy_float16") return "decodeNormalXyFloat16(uvec2(" + c[0] + ", " + c[1] + "))";
    if (e == "luma") return "vec3(dequantizeUnorm(" + c[0] + ", " + b + "))";
    if (colorTransform(e, fwd, inv))
        return inv + "(vec3(dequantizeUnorm(" + c[0] + ", " + b + "), " + chromaDequantize(e) + "(" + c[1] + ", " + b +
               "), " + chromaDequantize(e) + "(" + c[2] + ", " + b + ")))";
    if (e == "normal_xyz") return "decodeNormalXyz(uvec3(" + c[0] + ", " + c[1] + ", " + c[2] + "), " + b + ")";
    if (e == "normal_bestfit") return "decodeNormalBestFit(uvec3(" + c[0] + ", " + c[1] + ", " + c[2] + "))";
    if (e == "normal_xy_zsign") return "decodeNormalXyZSign(uvec3(" + c[0] + ", " + c[1] + ", " + c[2] + "), " + b + ")";
    const std::string fn = e == "normal_spheremap"       ? "decodeNormalSpheremap"
                           : e == "normal_stereographic" ? "decodeNormalStereographic"
                           : e == "normal_octahedral"    ? "decodeNormalOctahedral"
                                                         : "decodeNormalOctahedralPrecise";
    return fn + "(uvec2(" + c[0] + ", " + c[1] + "), " + b + ")";
}

// Native formats: the float written for each code of a field, or {} when the field cannot go
// native. Decoding from those floats: nativeDecodeExpr.
bool nativeField(const Target& t, const Field& f) {
    if (f.encoding == kIdEncoding) return false;
    // An SNORM target's hardware conversion is not any encoding's: its fields stay packed words.
    if (t.format.find("SNORM") != std::string::npos) return false;
    const std::string& e = f.encoding;
    for (size_t i = 0; i < f.codes.size(); ++i) {
        const CodePlace& cp = f.codes[i];
        if (cp.pieces.size() != 1) return false;
        const Channel& ch = t.channels[size_t(cp.pieces[0].channel)];
        if (cp.pieces[0].first != 0 || cp.pieces[0].count != ch.bits) return false;
        bool ok = false;
        switch (ch.type) {
            case ChannelType::Unorm:
                ok = e == "unorm" || e == "gloss" || e == "smoothness_cry" || e == "cry_gloss_power" || e == "normal_xyz" || e == "ycbcr" ||
                     e == "ycbcr_sqrt" || e == "ycocg" || e == "luma";
                break;
            case ChannelType::Srgb: ok = e == "srgb8"; break;
            case ChannelType::Sfloat: ok = (e == "float16" && ch.bits == 16) || (e == "float32" && ch.bits == 32); break;
            case ChannelType::Ufloat: ok = (e == "float11" && ch.bits == 11) || (e == "float10" && ch.bits == 10); break;
            case ChannelType::Uint: ok = false; break;
        }
        if (!ok) return false;
    }
    return true;
}

std::vector<std::string> emitNativeEncode(std::ostream& o, const std::string& ind, const Field& f, const std::string& id) {
    const std::string& e = f.encoding;
    std::vector<std::string> v;
    std::string fwd, inv;
    if (isScalarField(f)) {
        for (size_t i = 0; i < f.codes.size(); ++i) {
            const std::string x = componentExpr(f, int(i));
            v.push_back(e == "gloss" ? "glossFromRoughness(" + x + ")"
                        : e == "smoothness_cry" ? "smoothnessFromRoughnessCry(" + x + ")"
                        // The code's own float: the hardware's round(x * 255) gives the code back.
                        : e == "cry_gloss_power" ? "dequantizeUnorm(encodeCryGlossPower(" + x + "), 8u)"
                                                : x);
        }
    } else if (e == "srgb8") {
        for (int i = 0; i < 3; ++i) v.push_back(wholeExpr(f) + "." + kComp[i]);
    } else if (e == "luma") {
        v.push_back("lumaBt601(" + wholeExpr(f) + ")");
    } else if (e == "normal_xyz") {
        o << ind << "vec3 " << id << " = " << wholeExpr(f) << " * 0.5 + 0.5;\n";
        for (int i = 0; i < 3; ++i) v.push_back(id + "." + kComp[i]);
    } else if (colorTransform(e, fwd, inv)) {
        o << ind << "vec3 " << id << " = " << fwd << "(" << wholeExpr(f) << ");\n";
        // The hardware rounds x * (2^bits - 1); scaling by (2^bits - 2) / (2^bits - 1) gives
        // quantizeChroma's codes (up to the hardware's rounding of ties).
        const double s1 = double((uint64_t(1) << f.bitsOfCode(0)) - 1);
        for (int i = 0; i < 3; ++i)
            v.push_back(i && midpointChroma(e) ? "(" + id + "." + kComp[i] + " * " + glslFloatLiteral((s1 - 1.0) / s1) + ")"
                                               : id + "." + kComp[i]);
    }
    return v;
}

std::string nativeDecodeExpr(const Field& f, const std::vector<std::string>& u) {
    const std::string& e = f.encoding;
    std::string fwd, inv;
    if (isScalarField(f)) {
        std::vector<std::string> parts;
        for (const std::string& x : u)
            parts.push_back(e == "gloss" ? "roughnessFromGloss(" + x + ")"
                            : e == "smoothness_cry" ? "roughnessFromSmoothnessCry(" + x + ")"
                            : e == "cry_gloss_power" ? "decodeCryGlossPower(quantizeUnorm(" + x + ", 8u))"
                                                    : x);
        if (parts.size() == 1) return parts[0];
        std::string s = "vec" + std::to_string(parts.size()) + "(";
        for (size_t i = 0; i < parts.size(); ++i) s += (i ? ", " : "") + parts[i];
        return s + ")";
    }
    if (e == "srgb8") return "vec3(" + u[0] + ", " + u[1] + ", " + u[2] + ")";
    if (e == "luma") return "vec3(" + u[0] + ")";
    if (e == "normal_xyz") return "normalize(vec3(" + u[0] + ", " + u[1] + ", " + u[2] + ") * 2.0 - 1.0)";
    colorTransform(e, fwd, inv);
    if (midpointChroma(e)) {
        const double s1 = double((uint64_t(1) << f.bitsOfCode(0)) - 1);
        const std::string k = glslFloatLiteral(s1 / (s1 - 1.0));
        return inv + "(vec3(" + u[0] + ", " + u[1] + " * " + k + ", " + u[2] + " * " + k + "))";
    }
    return inv + "(vec3(" + u[0] + ", " + u[1] + ", " + u[2] + "))";
}

// Word index and bit position of a piece in a target's pixel.
void pieceAddress(const Target& t, const BitRange& r, int& word, int& bit) {
    const int at = t.channels[size_t(r.channel)].offset + r.first;
    word = at / 32;
    bit = at % 32;
}

void emitPlaceCode(std::ostream& o, const std::string& ind, const Target& t, const CodePlace& cp,
                   const std::string& words, const std::string& code) {
    int shift = 0;
    for (const BitRange& r : cp.pieces) {
        int word = 0, bit = 0;
        pieceAddress(t, r, word, bit);
        std::string piece = "(" + code + (shift ? " >> " + ulit(uint64_t(shift)) : "") + ")";
        if (r.count < 32) piece = "(" + piece + " & " + maskLit(r.count) + ")";
        if (bit) piece += " << " + ulit(uint64_t(bit));
        o << ind << words << "[" << word << "] |= " << piece << ";\n";
        shift += r.count;
    }
}

std::string extractCode(const Target& t, const CodePlace& cp, const std::string& words) {
    std::string s;
    int shift = 0;
    for (const BitRange& r : cp.pieces) {
        int word = 0, bit = 0;
        pieceAddress(t, r, word, bit);
        std::string piece = words + "[" + std::to_string(word) + "]";
        if (bit) piece = "(" + piece + " >> " + ulit(uint64_t(bit)) + ")";
        if (r.count < 32) piece = "(" + piece + " & " + maskLit(r.count) + ")";
        if (shift) piece = "(" + piece + " << " + ulit(uint64_t(shift)) + ")";
        s += (s.empty() ? "" : " | ") + piece;
        shift += r.count;
    }
    return s.empty() ? "0u" : s;
}

std::string outTypeOf(int words, int bits) {
    if (bits <= 32) return "uint";
    return words == 2 ? "uvec2" : "uvec4";
}

std::string wordsToOut(int words, int bits, const std::string& w) {
    if (bits <= 32) return w + ".x";
    return words == 2 ? w + ".xy" : w;
}

std::string zeroOf(Attribute a) { return attributeComponents(a) == 1 ? "0.0" : "vec3(0.0)"; }

void emitFallback(std::ostream& o, const Fallback& fb, const Layout& layout) {
    const char* m = surfaceMemberName(fb.attribute);
    if (!m) return;
    const std::string lhs = std::string("    s.") + m + " = ";
    switch (fb.kind) {
        case FallbackKind::Constant: {
            if (attributeComponents(fb.attribute) == 1) {
                o << lhs << glslFloatLiteral(fb.value.empty() ? 0.0 : fb.value[0]) << ";\n";
            } else {
                auto v = [&](size_t i) { return glslFloatLiteral(fb.value.empty() ? 0.0 : fb.value[std::min(i, fb.value.size() - 1)]); };
                o << lhs << "vec3(" << v(0) << ", " << v(1) << ", " << v(2) << ");\n";
            }
            return;
        }
        case FallbackKind::FromMetallic:
            o << lhs << "vec3(0.04) * (1.0 - s.metallic) + s.baseColor * s.metallic;  // from_metallic\n";
            return;
        case FallbackKind::Ue4:
            o << lhs << "specularColorUE4(s.baseColor, s.metallic, s.specular);  // ue4\n";
            return;
        case FallbackKind::FromBaseColor:
            o << lhs << "s.baseColor * (1.0 - s.metallic);  // from_base_color\n";
            return;
        case FallbackKind::FromDiffuseSpecular:
            o << lhs << "s.diffuseColor + s.metallic * s.specularColor;  // from_diffuse_specular\n";
            return;
        case FallbackKind::FromSpecularColor:
            o << lhs
              << "clamp((max(s.specularColor.x, max(s.specularColor.y, s.specularColor.z)) - 0.04) / 0.96, 0.0, 1.0);"
                 "  // from_specular_color\n";
            return;
        case FallbackKind::Forward:
            o << lhs << zeroOf(fb.attribute) << ";  // forward: the renderer adds it in a forward pass\n";
            return;
        case FallbackKind::MaterialPass: {
            for (const MaterialSlot& slot : materialPassSlots(layout)) {
                if (slot.attribute != fb.attribute) continue;
                std::vector<std::string> parts;
                for (int c = 0; c < slot.components; ++c) {
                    const int k = slot.firstFloat + c;
                    parts.push_back("uintBitsToFloat(m" + std::to_string(k / 4) + "." + kComp[k % 4] + ")");
                }
                if (parts.size() == 1) {
                    o << lhs << parts[0] << ";  // material pass\n";
                } else {
                    o << lhs << "vec3(" << parts[0] << ", " << parts[1] << ", " << parts[2] << ");  // material pass\n";
                }
            }
            return;
        }
    }
}

}  // namespace

std::string nativeFormatObstacle(const Target& target) {
    bool anyUint = false;
    for (const Channel& c : target.channels) anyUint |= c.type == ChannelType::Uint;
    if (anyUint) return target.format + " is an integer format";
    for (const Field& f : target.fields)
        if (!nativeField(target, f))
            return "field '" + std::string(attributeName(f.attribute)) + "' (" + f.encoding +
                   ") packs codes that " + target.format + " cannot express as whole channels of its own encoding";
    return "";
}

std::string generateWiringGlsl(const Layout& layout, const WiringOptions& options) {
    if (layout.pipeline == Pipeline::VisibilityBuffer) return generateVisibilityWiringGlsl(layout);
    std::ostringstream o;
    o << "// generated from layouts/" << glslCommentText(layout.name) << ".toml by gbufferlab -- do not edit\n";
    o << "// " << glslCommentText(layout.title) << " (" << pipelineName(layout.pipeline) << ")\n";
    o << "// Integer-only wiring: every code is placed with shifts and masks; src/codec/cpu_codec.cpp mirrors it.\n";
    if (!layout.depth.stencil.empty())
        o << "// Stencil extras are constants written by the renderer's stencil reference, not here.\n";
    o << "#include \"encodings.glsl\"\n";

    std::vector<bool> native(layout.targets.size(), false);
    for (size_t t = 0; t < layout.targets.size(); ++t) {
        const Target& tg = layout.targets[t];
        if (!options.nativeFormats) continue;
        const std::string why = nativeFormatObstacle(tg);
        native[t] = why.empty();
        if (!why.empty()) o << "// --native-formats: target " << t << " '" << glslCommentText(tg.name) << "' stays UINT: " << why << "\n";
    }
    const bool materialPass = materialTargetCount(layout) > 0;
    const int materialTargets = materialTargetCount(layout);

    // ---- write ----
    o << "\n#if defined(MATERIAL_PASS_WRITE)\n";
    if (materialPass) {
        o << "// Material pass: the attributes the G-buffer leaves to it, as float32 bits.\n";
        for (int i = 0; i < materialTargets; ++i)
            o << "layout(location = " << i << ") out uvec4 materialTarget" << i << ";\n";
        o << "void writeGBuffer(Surface s, ivec2 pixel) {\n";
        for (int i = 0; i < materialTargets; ++i) o << "    uvec4 m" << i << " = uvec4(0u);\n";
        for (const MaterialSlot& slot : materialPassSlots(layout)) {
            const std::string m = std::string("s.") + surfaceMemberName(slot.attribute);
            for (int c = 0; c < slot.components; ++c) {
                const int k = slot.firstFloat + c;
                o << "    m" << k / 4 << "." << kComp[k % 4] << " = floatBitsToUint("
                  << (slot.components == 1 ? m : m + "." + kComp[c]) << ");\n";
            }
        }
        for (int i = 0; i < materialTargets; ++i) o << "    materialTarget" << i << " = m" << i << ";\n";
        o << "}\n";
    } else {
        o << "#error \"layout " << glslCommentText(layout.name) << " has no material pass\"\n";
    }
    o << "#elif defined(GBUFFER_WRITE)\n";
    for (size_t t = 0; t < layout.targets.size(); ++t) {
        const Target& tg = layout.targets[t];
        o << "layout(location = " << t << ") out "
          << (native[t] ? "vec4" : outTypeOf(wordsPerPixel(tg), tg.bits())) << " gbufferTarget" << t << ";  // "
          << glslCommentText(tg.name) << ", " << tg.format << (native[t] ? " (native)" : "") << "\n";
    }
    const Fallback* emissiveFb = layout.findFallback(Attribute::Emissive);
    const bool emissiveForward = emissiveFb && emissiveFb->kind == FallbackKind::Forward;
    if (emissiveForward)
        o << "layout(location = " << layout.targets.size()
          << ") out vec4 gblSceneColorEmissive;  // emissive = forward: scene colour, RGBA32F, unquantised\n";
    o << "void writeGBuffer(Surface s, ivec2 pixel) {\n";
    if (emissiveForward)
        o << "    // emissive = forward: into scene colour, as UE4's base pass does; the lighting pass adds it\n"
             "    gblSceneColorEmissive = vec4(s.emissive, 0.0);\n";
    for (size_t t = 0; t < layout.targets.size(); ++t) {
        const Target& tg = layout.targets[t];
        const std::string ts = std::to_string(t);
        o << "    // target " << t << " '" << glslCommentText(tg.name) << "'\n";
        if (native[t]) {
            o << "    vec4 v" << ts << " = vec4(0.0);\n";
        } else {
            o << "    uvec4 w" << ts << " = uvec4(0u);\n";
        }
        for (size_t fi = 0; fi < tg.fields.size(); ++fi) {
            const Field& f = tg.fields[fi];
            const std::string id = "e" + ts + "_" + std::to_string(fi);
            std::string at;
            for (const CodePlace& cp : f.codes) at += (at.empty() ? "" : ", ") + cp.text;
            o << "    // " << attributeName(f.attribute) << ": " << f.encoding << " at " << at << "\n";
            if (native[t]) {
                const std::vector<std::string> v = emitNativeEncode(o, "    ", f, id);
                for (size_t i = 0; i < v.size(); ++i) {
                    const Channel& ch = tg.channels[size_t(f.codes[i].pieces[0].channel)];
                    o << "    v" << ts << "." << kComp[channelComponent(ch)] << " = " << v[i] << ";\n";
                }
                continue;
            }
            const std::vector<std::string> codes = emitEncodeField(o, "    ", f, id);
            for (size_t i = 0; i < codes.size(); ++i) {
                if (f.codes[i].pieces.size() == 1 && codes[i].find('(') != std::string::npos) {
                    emitPlaceCode(o, "    ", tg, f.codes[i], "w" + ts, codes[i]);
                } else {
                    const std::string cv = id + "_c" + std::to_string(i);
                    o << "    uint " << cv << " = " << codes[i] << ";\n";
                    emitPlaceCode(o, "    ", tg, f.codes[i], "w" + ts, cv);
                }
            }
        }
        o << "    gbufferTarget" << ts << " = "
          << (native[t] ? "v" + ts : wordsToOut(wordsPerPixel(tg), tg.bits(), "w" + ts)) << ";\n";
    }
    o << "}\n#endif\n";

    // ---- read ----
    o << "\n#ifdef GBUFFER_READ\n";
    for (size_t t = 0; t < layout.targets.size(); ++t)
        o << "layout(set = 1, binding = " << t << ") uniform " << (native[t] ? "sampler2D" : "usampler2D")
          << " gbufferTarget" << t << ";  // " << glslCommentText(layout.targets[t].name) << "\n";
    for (int i = 0; i < materialTargets; ++i)
        o << "layout(set = 2, binding = " << i << ") uniform usampler2D materialTarget" << i
          << ";  // material pass, float32 bits\n";
    // Helpers for checkerboard chroma: (Y, C) of a pixel, and the mirrored neighbour address.
    bool anyCheckerboard = false;
    for (size_t t = 0; t < layout.targets.size(); ++t) {
        const Target& tg = layout.targets[t];
        for (size_t fi = 0; fi < tg.fields.size(); ++fi) {
            const Field& f = tg.fields[fi];
            if (!findEncoding(f.encoding) || !findEncoding(f.encoding)->needsNeighbours) continue;
            anyCheckerboard = true;
            const std::string b = ulit(uint64_t(f.bitsOfCode(0)));
            o << "vec2 gblLumaChroma" << t << "_" << fi << "(ivec2 p) {\n";
            o << "    uvec4 w = texelFetch(gbufferTarget" << t << ", p, 0);\n";
            o << "    return vec2(dequantizeUnorm(" << extractCode(tg, f.codes[0], "w") << ", " << b << "), "
              << chromaDequantize(f.encoding) << "(" << extractCode(tg, f.codes[1], "w") << ", " << b << "));\n}\n";
        }
    }
    if (anyCheckerboard)
        o << "// Which neighbours hold geometry: a shader that defines GBL_GEOMETRY_MASK defines\n"
             "// bool gblHasGeometry(ivec2 p) (the lighting and decode passes: depth != clear depth);\n"
             "// without it every pixel counts as covered.\n"
             "#ifdef GBL_GEOMETRY_MASK\n"
             "bool gblHasGeometry(ivec2 p);\n"
             "float gblCovered(ivec2 p) { return gblHasGeometry(p) ? 1.0 : 0.0; }\n"
             "#else\n"
             "float gblCovered(ivec2 p) { return 1.0; }\n"
             "#endif\n";
    if (anyCheckerboard)
        o << "// Mirrored at borders (x = -1 reads x = 1), so a neighbour always holds the other chroma.\n"
             "ivec2 gblMirror(ivec2 p, ivec2 size) {\n"
             "    p = abs(p);\n"
             "    p = (size - 1) - abs((size - 1) - p);\n"
             "    return clamp(p, ivec2(0), size - 1);\n"
             "}\n";
    o << "Surface readGBuffer(ivec2 pixel) {\n    Surface s;\n";
    for (size_t t = 0; t < layout.targets.size(); ++t)
        o << "    " << (native[t] ? "vec4 v" : "uvec4 w") << t << " = texelFetch(gbufferTarget" << t
          << ", pixel, 0);\n";
    for (int i = 0; i < materialTargets; ++i)
        o << "    uvec4 m" << i << " = texelFetch(materialTarget" << i << ", pixel, 0);\n";
    for (size_t t = 0; t < layout.targets.size(); ++t) {
        const Target& tg = layout.targets[t];
        const std::string ts = std::to_string(t);
        for (size_t fi = 0; fi < tg.fields.size(); ++fi) {
            const Field& f = tg.fields[fi];
            const char* m = surfaceMemberName(f.attribute);
            if (!m) continue;  // extras: no shading meaning
            const std::string lhs = std::string("    s.") + m + " = ";
            if (native[t]) {
                std::vector<std::string> u;
                for (const CodePlace& cp : f.codes)
                    u.push_back("v" + ts + "." + kComp[channelComponent(tg.channels[size_t(cp.pieces[0].channel)])]);
                o << lhs << nativeDecodeExpr(f, u) << ";\n";
                continue;
            }
            if (findEncoding(f.encoding) && findEncoding(f.encoding)->needsNeighbours) {
                std::string fwd, inv;
                colorTransform(f.encoding, fwd, inv);
                const std::string fn = "gblLumaChroma" + ts + "_" + std::to_string(fi);
                o << "    {\n        ivec2 size = textureSize(gbufferTarget" << ts << ", 0);\n";
                o << "        vec2 c = " << fn << "(pixel);\n";
                const char* off[4] = {"ivec2(1, 0)", "ivec2(-1, 0)", "ivec2(0, 1)", "ivec2(0, -1)"};
                for (int k = 0; k < 4; ++k) {
                    o << "        ivec2 p" << k << " = gblMirror(pixel + " << off[k] << ", size);\n";
                    o << "        vec2 n" << k << " = " << fn << "(p" << k << ");\n";
                }
                o << "        vec2 ch = reconstructChroma(pixel, c.x, c.y, vec4(n0.x, n1.x, n2.x, n3.x), "
                     "vec4(n0.y, n1.y, n2.y, n3.y), vec4(gblCovered(p0), gblCovered(p1), gblCovered(p2), "
                     "gblCovered(p3)));\n";
                o << "    " << lhs << inv << "(vec3(c.x, ch.x, ch.y));\n    }\n";
                continue;
            }
            std::vector<std::string> codes;
            for (const CodePlace& cp : f.codes) codes.push_back(extractCode(tg, cp, "w" + ts));
            o << lhs << decodeFieldExpr(f, codes) << ";\n";
        }
    }
    // Unstored attributes without a fallback (position: the lighting pass rebuilds it from depth).
    for (Attribute a : {Attribute::Normal, Attribute::BaseColor, Attribute::Metallic, Attribute::Roughness,
                        Attribute::Specular, Attribute::SpecularColor, Attribute::DiffuseColor, Attribute::Occlusion,
                        Attribute::Emissive, Attribute::Position})
        if (!layout.stores(a) && !layout.findFallback(a))
            o << "    s." << surfaceMemberName(a) << " = " << zeroOf(a) << ";  // not stored"
              << (a == Attribute::Position ? ": rebuilt from depth by the lighting pass" : "") << "\n";
    for (const Fallback* fb : orderedFallbacks(layout)) emitFallback(o, *fb, layout);
    o << "    return s;\n}\n#endif\n";
    return o.str();
}

GBufferWiring generateWiring(const Layout& layout, const WiringOptions& options) {
    if (layout.pipeline == Pipeline::VisibilityBuffer) return generateVisibilityWiring(layout);
    GBufferWiring w;
    w.layoutName = layout.name;
    for (const Target& t : layout.targets) {
        w.targetNames.push_back(t.name);
        const bool native = options.nativeFormats && nativeFormatObstacle(t).empty();
        w.targetFormats.push_back(native ? vkFormatFromName(t.format) : uintFormatOf(t));
    }
    const std::vector<std::array<uint32_t, 4>> clear = clearWords(layout);
    for (size_t t = 0; t < layout.targets.size(); ++t) {
        const bool native = options.nativeFormats && nativeFormatObstacle(layout.targets[t]).empty();
        w.targetClearWords.push_back(native ? std::array<uint32_t, 4>{0, 0, 0, 0} : clear[t]);
    }
    w.depthFormat = vkFormatFromName(layout.depth.format);
    w.normalSpace = int(layout.space.normal);
    w.positionSpace = int(layout.space.position);
    w.storesPosition = layout.stores(Attribute::Position);
    for (const Field& f : layout.depth.stencil) {
        // Integer extras, one code; its pieces take the value's bits, low bits first.
        if (f.codes.empty() || f.value.empty()) continue;
        int consumed = 0;
        for (const BitRange& r : f.codes[0].pieces) {
            GBufferWiring::StencilField sf;
            sf.attribute = attributeName(f.attribute);
            sf.shift = uint32_t(r.first);
            sf.mask = (1u << r.count) - 1u;
            sf.valueShift = uint32_t(consumed);
            sf.value = uint32_t(f.value[0]);
            consumed += r.count;
            w.stencilWriteMask |= sf.mask << r.first;
            w.stencilFields.push_back(sf);
        }
    }
    w.reversedZ = layout.depth.reversedZ;
    const Fallback* emissive = layout.findFallback(Attribute::Emissive);
    w.emissiveForward = emissive && emissive->kind == FallbackKind::Forward;
    w.materialPass = materialTargetCount(layout) > 0;
    w.materialTargetFormats.assign(size_t(materialTargetCount(layout)), VK_FORMAT_R32G32B32A32_UINT);
    w.glsl = generateWiringGlsl(layout, options);
    w.lightBufferGlsl = generateLightBufferGlsl(layout);
    if (!w.lightBufferGlsl.empty()) w.lightBufferWordsPerPixel = lightBufferWordsPerPixel(layout);
    return w;
}

}  // namespace gbl
