// The GLSL of one field, encoding by encoding: the expressions that turn a Surface attribute
// into its codes (emitEncodeField) and codes back into the attribute (decodeFieldExpr), and their
// native-format twins where the hardware quantises (nativeField, emitNativeEncode,
// nativeDecodeExpr). Where the codes go in a target's words is wiring_codegen.cpp's job.
#include "wiring_field_codegen.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "encoding_registry.h"
#include "glsl_text.h"
#include "wiring_plan.h"

namespace gbl::wiring {

namespace {


// Value of component `i` of a field's attribute: a Surface member or the extra's constant.
std::string componentExpr(const Field& f, int i, bool extrasFromSurface = false) {
    const int n = attributeComponents(f.attribute);
    if (const char* m = surfaceMemberName(f.attribute)) {
        std::string e = std::string("s.") + m;
        return n == 1 ? e : e + "." + kComp[i];
    }
    if (extrasFromSurface) {
        const std::string e = "s." + extraMemberName(f.attribute);
        return n == 1 ? e : e + "." + kComp[i];
    }
    if (const char* slot = surfaceSlotName(f.attribute)) return std::string("s.") + slot;  // depth: position.z
    const double v = f.value.empty() ? 0.0 : f.value[std::min<size_t>(size_t(i), f.value.size() - 1)];
    if (f.encoding == kIdEncoding) return ulit(uint64_t(v));
    return glslFloatLiteral(v);
}

// The whole value (vec3) of a field's attribute.
std::string wholeExpr(const Field& f, bool extrasFromSurface = false) {
    if (const char* m = surfaceMemberName(f.attribute)) return std::string("s.") + m;
    if (extrasFromSurface && attributeComponents(f.attribute) == 3) return "s." + extraMemberName(f.attribute);
    return "vec3(" + componentExpr(f, 0, extrasFromSurface) + ", " + componentExpr(f, 1, extrasFromSurface) + ", " +
           componentExpr(f, 2, extrasFromSurface) + ")";
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

// The Surface member of the attribute an encoding also stores (float11_11_10_hdrp_ao_tag:
// "s.occlusion"): at write time the unquantised value, at read time the one it sets.
std::string carriesExpr(const EncodingInfo& e) {
    const AttributeInfo* a = findAttribute(e.carries);
    const char* m = a ? surfaceMemberName(a->id) : nullptr;
    if (!m) throw std::logic_error("wiring: encoding " + e.name + " stores unknown attribute " + e.carries);
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
    if (enc == "kz2_log_power") return "encodeKz2LogPower(" + x + ")";
    if (enc == "reflectance" || enc == "reflectance_bevy_webgl2")
        return "quantizeUnorm(reflectanceFromSpecular(" + x + "), " + b + ")";
    if (enc == "unorm_round_even") return "quantizeUnormRoundEven(" + x + ", " + b + ")";
    if (enc == "coat_roughness_bevy") return "encodeCoatRoughnessBevy(" + x + ", " + b + ")";
    if (enc == "unorm_signed") return "quantizeUnormSigned(" + x + ", " + b + ")";
    if (enc == "unorm_sqrt") return "encodeUnormSqrt(" + x + ")";
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
    if (enc == "kz2_log_power") return "decodeKz2LogPower(" + c + ")";
    if (enc == "reflectance") return "specularFromReflectance(dequantizeUnorm(" + c + ", " + b + "))";
    if (enc == "reflectance_bevy_webgl2")
        return "specularFromReflectanceBevyWebgl2(dequantizeUnorm(" + c + ", " + b + "))";
    if (enc == "unorm_round_even") return "dequantizeUnorm(" + c + ", " + b + ")";
    if (enc == "coat_roughness_bevy") return "decodeCoatRoughnessBevy(" + c + ", " + b + ")";
    if (enc == "unorm_signed") return "dequantizeUnormSigned(" + c + ", " + b + ")";
    if (enc == "unorm_sqrt") return "decodeUnormSqrt(" + c + ")";
    throw std::logic_error("wiring: no scalar decoder for " + enc);
}

// The YCbCr family (CryEngine's) quantises its chroma with quantizeChroma, whose midpoint code is
// exactly neutral; YCoCg keeps the paper's quantizeUnorm of chroma + 0.5.
bool midpointChroma(const std::string& enc) {
    return enc == "ycbcr" || enc == "ycbcr_sqrt" || enc == "ycbcr_checkerboard";
}
std::string chromaQuantize(const std::string& enc) { return midpointChroma(enc) ? "quantizeChroma" : "quantizeUnorm"; }

}  // namespace

int channelComponent(const Channel& c) {
    if (c.name == "r") return 0;
    if (c.name == "g") return 1;
    if (c.name == "b") return 2;
    return 3;
}

int attributeComponents(Attribute a) { return attributeInfo(a).components; }

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

std::string chromaDequantize(const std::string& enc) {
    return midpointChroma(enc) ? "dequantizeChroma" : "dequantizeUnorm";
}

// Emits the encoder of a field: setup lines, returns one uint expression per code.
std::string extraMemberName(Attribute a) {
    std::string out;
    bool upper = false;
    for (const char* c = attributeName(a); *c; ++c) {
        if (*c == '_') {
            upper = true;
            continue;
        }
        out += upper ? char(std::toupper(static_cast<unsigned char>(*c))) : *c;
        upper = false;
    }
    return out;
}

std::vector<std::string> emitEncodeField(std::ostream& o, const std::string& ind, const Field& f, const std::string& id,
                                         bool extrasFromSurface) {
    std::vector<std::string> codes;
    if (isScalarField(f)) {
        for (size_t i = 0; i < f.codes.size(); ++i)
            codes.push_back(scalarEncode(f.encoding, componentExpr(f, int(i), extrasFromSurface), f.bitsOfCode(i)));
        return codes;
    }
    const std::string& e = f.encoding;
    const std::string b = ulit(uint64_t(f.bitsOfCode(0)));
    const std::string v = wholeExpr(f, extrasFromSurface);
    std::string fwd, inv;
    if (e == "srgb8" || e == "gamma22" || e == "srgb8_fast_hdrp") {
        const std::string fn = e == "srgb8" ? "encodeSrgb8(" : e == "gamma22" ? "encodeGamma22(" : "encodeSrgb8FastHdrp(";
        for (int i = 0; i < 3; ++i) codes.push_back(fn + v + "." + kComp[i] + ")");
    } else if (e == "float11_11_10") {
        codes.push_back("encodeFloat11(" + v + ".x)");
        codes.push_back("encodeFloat11(" + v + ".y)");
        codes.push_back("encodeFloat10(" + v + ".z)");
    } else if (e == "float11_11_10_hdrp_ao_tag") {
        o << ind << "uvec3 " << id << " = encodeFloat111110HdrpAoTag(" << v << ", " << carriesExpr(encodingOf(f))
          << ");\n";
        for (int i = 0; i < 3; ++i) codes.push_back(id + "." + kComp[i]);
    } else if (e == "anisotropy_angle_hdrp") {
        o << ind << "uvec3 " << id << " = encodeAnisotropyHdrp(" << v << ", " << carriesExpr(encodingOf(f)) << ", "
          << readsExpr(encodingOf(f)) << ");\n";
        for (int i = 0; i < 3; ++i) codes.push_back(id + "." + kComp[i]);
    } else if (e == "normal_octahedral_delta_ue") {
        // against the unquantised coat normal (UE's GBuffer.WorldNormal before it is written)
        o << ind << "uvec2 " << id << " = encodeNormalOctahedralDeltaUe(" << v << ", " << readsExpr(encodingOf(f))
          << ", " << b << ");\n";
        for (int i = 0; i < 2; ++i) codes.push_back(id + "." + kComp[i]);
    } else if (e == "rgb9e5") {
        o << ind << "uvec4 " << id << " = encodeRgb9e5(" << v << ");\n";
        for (int i = 0; i < 4; ++i) codes.push_back(id + "." + kComp[i]);
    } else if (e == "normal_octahedral_bevy" || e == "normal_octahedral_unity" || e == "normal_octahedral_hdrp") {
        const std::string fn = e == "normal_octahedral_bevy"    ? "encodeNormalOctahedralBevy("
                               : e == "normal_octahedral_unity" ? "encodeNormalOctahedralUnity("
                                                                : "encodeNormalOctahedralHdrp(";
        o << ind << "uvec2 " << id << " = " << fn << v << ", " << b << ");\n";
        for (int i = 0; i < 2; ++i) codes.push_back(id + "." + kComp[i]);
    } else if (e == "normal_xy_float16") {
        o << ind << "uvec2 " << id << " = encodeNormalXyFloat16(" << v << ");\n";
        for (int i = 0; i < 2; ++i) codes.push_back(id + "." + kComp[i]);
    } else if (e == "luma") {
        codes.push_back("quantizeUnorm(lumaBt601(" + v + "), " + b + ")");
    } else if (e == "emissive_albedo_ratio") {
        codes.push_back("encodeEmissiveAlbedoRatio(" + v + ", " + readsExpr(encodingOf(f)) + ", " + b + ")");
    } else if (e == "normal_octahedral_dithered") {
        // A dither that moves with time reads the frame index the including shader defines
        // (gbuffer_pass.frag.glsl gblFrameIndex: FrameConstants::band.z).
        if (f.ditherPerFrame)
            o << ind << "uvec2 " << id << " = encodeNormalOctahedralDitheredAtFrame(" << v << ", " << b
              << ", pixel, gblFrameIndex());\n";
        else
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
    if (e == "srgb8_fast_hdrp")
        return "vec3(decodeSrgb8FastHdrp(" + c[0] + "), decodeSrgb8FastHdrp(" + c[1] + "), decodeSrgb8FastHdrp(" + c[2] +
               "))";
    if (e == "float11_11_10")
        return "vec3(decodeFloat11(" + c[0] + "), decodeFloat11(" + c[1] + "), decodeFloat10(" + c[2] + "))";
    if (e == "float11_11_10_hdrp_ao_tag")
        return "decodeFloat111110HdrpAoTag(uvec3(" + c[0] + ", " + c[1] + ", " + c[2] + "))";
    if (e == "anisotropy_angle_hdrp")
        return "decodeAnisotropyHdrp(uvec3(" + c[0] + ", " + c[1] + ", " + c[2] + "), " + readsExpr(encodingOf(f)) + ")";
    if (e == "normal_octahedral_delta_ue")  // against the decoded coat normal
        return "decodeNormalOctahedralDeltaUe(uvec2(" + c[0] + ", " + c[1] + "), " + readsExpr(encodingOf(f)) + ", " + b + ")";
    if (e == "rgb9e5") return "decodeRgb9e5(uvec4(" + c[0] + ", " + c[1] + ", " + c[2] + ", " + c[3] + "))";
    if (e == "emissive_albedo_ratio")
        return "decodeEmissiveAlbedoRatio(" + c[0] + ", " + b + ", " + readsExpr(encodingOf(f)) + ")";
    if (e == "normal_octahedral_bevy" || e == "normal_octahedral_unity" || e == "normal_octahedral_hdrp" ||
        e == "normal_octahedral_dithered")
        return "decodeNormalOctahedralUnorm(uvec2(" + c[0] + ", " + c[1] + "), " + b + ")";
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

// The statement that sets what a field's encoding also stores ("" when it stores nothing else).
std::string decodeCarriedStatement(const Field& f, const std::vector<std::string>& c) {
    const EncodingInfo* e = findEncoding(f.encoding);
    if (!e || e->carries.empty()) return "";
    if (f.encoding == "float11_11_10_hdrp_ao_tag")
        return carriesExpr(*e) + " = decodeHdrpAoTagOcclusion(uvec3(" + c[0] + ", " + c[1] + ", " + c[2] + "));";
    if (f.encoding == "anisotropy_angle_hdrp")
        return carriesExpr(*e) + " = decodeAnisotropyHdrpStrength(uvec3(" + c[0] + ", " + c[1] + ", " + c[2] + "));";
    throw std::logic_error("wiring: no decoder for what " + f.encoding + " also stores");
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
                ok = e == "unorm" || e == "gloss" || e == "smoothness_cry" || e == "cry_gloss_power" || e == "kz2_log_power" ||
                     e == "normal_xyz" || e == "ycbcr" || e == "ycbcr_sqrt" || e == "ycocg" || e == "luma";
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
                        : e == "kz2_log_power"   ? "dequantizeUnorm(encodeKz2LogPower(" + x + "), 8u)"
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
                            : e == "kz2_log_power"   ? "decodeKz2LogPower(quantizeUnorm(" + x + ", 8u))"
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

void emitModelPick(std::ostream& o, const std::string& ind, const Layout& layout, const std::string& var) {
    const uint32_t named = layout.selectorModels();
    o << ind << "// the pixel's shading model: the first the selector names whose layer it carries, else default\n";
    o << ind << "uint " << var << " = 0u;  // default\n";
    const std::vector<ShadingModelInfo>& models = listShadingModels();
    for (auto it = models.rbegin(); it != models.rend(); ++it) {
        if (it->id == ShadingModel::Default || !((named >> unsigned(it->id)) & 1u)) continue;
        const std::string m = std::string("s.") + surfaceMemberName(it->test);
        const int n = attributeComponents(it->test);
        std::string test;
        for (int c = 0; c < n; ++c)
            test += (c ? " || " : "") + (n == 1 ? m : m + "." + kComp[c]) + " > 0.0";
        o << ind << "if (" << test << ") " << var << " = " << ulit(uint64_t(it->id)) << ";  // " << it->name << "\n";
    }
}

std::string modelIdExpr(const Field& selector, const std::string& var) {
    uint32_t ids[kShadingModels] = {0, 0, 0, 0};
    uint32_t named = 0;
    for (const Field::ModelId& m : selector.selector) {
        ids[size_t(m.model)] = m.id;
        named |= 1u << unsigned(m.model);
    }
    std::string e = ulit(ids[0]);  // default (and any model the selector does not name: never picked)
    for (int m = kShadingModels - 1; m >= 1; --m)
        if ((named >> m) & 1u) e = var + " == " + ulit(uint64_t(m)) + " ? " + ulit(ids[m]) + " : (" + e + ")";
    return "(" + e + ")";
}

std::string maskTest(uint32_t mask, const std::string& var) {
    return "((" + ulit(mask) + " >> " + var + ") & 1u) != 0u";
}

}  // namespace gbl::wiring
