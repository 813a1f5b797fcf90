// `gbufferlab layouts export`: the structs, encode, decode and kernel of one layout, in GLSL syntax
// first (the encodings' own language), then, for HLSL, through translateGlslToHlsl. The header
// comment is export_header.cpp's.
#include "layout_export.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "encoding_registry.h"
#include "export_header.h"
#include "glsl_text.h"
#include "wiring_field_codegen.h"
#include "wiring_plan.h"

namespace gbl {

using namespace wiring;

namespace {

const char* kVec[] = {"float", "vec2", "vec3", "vec4"};
const char* kUvec[] = {"uint", "uvec2", "uvec3", "uvec4"};

std::string memberType(const ExportMember& m) { return (m.isUint ? kUvec : kVec)[m.components - 1]; }

bool fieldNeedsNeighbours(const Field& f) {
    const EncodingInfo* e = findEncoding(f.encoding);
    return e && e->needsNeighbours;
}

// The GLSL-syntax parts every language shares (structs, conversions, encode, decode, kernel body).
class Generator {
public:
    Generator(const Layout& layout, const ExportOptions& options)
        : l_(layout), opt_(options), p_(exportPrefix(layout)), members_(exportSurfaceMembers(layout)) {}

    std::string body() {
        emitStructs();
        emitDefaults();
        for (size_t t = 0; t < l_.targets.size(); ++t) emitConversions(t);
        emitEncode();
        emitDecode();
        if (opt_.kernel) emitKernelBody();
        return o_.str();
    }

private:
    std::string targetMember(size_t t) const {
        return "rt" + std::to_string(t) + "_" + exportIdentifier(l_.targets[t].name);
    }
    bool uintTarget(size_t t) const { return realKind(l_.targets[t], l_.targets[t].channels[0]) == RealKind::Uint; }
    std::string targetType(size_t t) const {
        if (!uintTarget(t)) return "vec4";
        const size_t n = l_.targets[t].channels.size();
        return n == 1 ? "uint" : n == 2 ? "uvec2" : "uvec4";
    }
    bool hlsl() const { return opt_.language == ExportLanguage::Hlsl; }

    void emitStructs() {
        o_ << "// The surface, in the units engines use (see the header).\n";
        o_ << "struct " << p_ << "_Surface {\n";
        for (const ExportMember& m : members_)
            o_ << "    " << memberType(m) << " " << m.name << ";" << (m.stored ? "" : "  // derived by decode, not stored")
               << "\n";
        o_ << "};\n\n";
        o_ << "// The values written to (and read from) each render target, in attachment order.\n";
        o_ << "struct " << p_ << "_Targets {\n";
        for (size_t t = 0; t < l_.targets.size(); ++t) {
            o_ << "    " << targetType(t) << " " << targetMember(t);
            if (hlsl()) o_ << " : SV_Target" << t;
            o_ << ";  // " << glslCommentText(l_.targets[t].format) << "\n";
        }
        o_ << "};\n\n";
    }

    void emitDefaults() {
        o_ << "// Zeros (normal +Z), and each extra the value the layout declares.\n";
        o_ << p_ << "_Surface " << p_ << "_surfaceDefaults() {\n    " << p_ << "_Surface s;\n";
        for (const ExportMember& m : members_) {
            std::vector<std::string> v;
            for (int c = 0; c < m.components; ++c) {
                const double x = m.defaultValue.empty() ? (m.attribute == Attribute::Normal && c == 2 ? 1.0 : 0.0)
                                                        : m.defaultValue[std::min<size_t>(size_t(c), m.defaultValue.size() - 1)];
                v.push_back(m.isUint ? ulit(uint64_t(x)) : glslFloatLiteral(x));
            }
            std::string e = v.size() == 1 ? v[0] : memberType(m) + "(";
            if (v.size() > 1) {
                for (size_t i = 0; i < v.size(); ++i) e += (i ? ", " : "") + v[i];
                e += ")";
            }
            o_ << "    s." << m.name << " = " << e << ";\n";
        }
        o_ << "    return s;\n}\n\n";
    }

    // Target t: its words -> the real format's values, and back.
    void emitConversions(size_t t) {
        const Target& tg = l_.targets[t];
        const std::string ts = std::to_string(t);
        o_ << "// " << glslCommentText(tg.format) << ": packed words -> the values the format stores exactly, and back.\n";
        o_ << targetType(t) << " " << p_ << "_rt" << ts << "Values(uvec4 w) {\n";
        std::vector<std::string> comps(4, uintTarget(t) ? "0u" : "0.0");
        for (const Channel& ch : tg.channels) {
            const std::string v = "((w[" + std::to_string(ch.offset / 32) + "] >> " + ulit(uint64_t(ch.offset % 32)) +
                                  ") & " + maskLit(ch.bits) + ")";
            const std::string b = ulit(uint64_t(ch.bits));
            std::string x;
            switch (realKind(tg, ch)) {
                case RealKind::Uint: x = v; break;
                case RealKind::Unorm: x = "float(" + v + ") * " + glslFloatLiteral(exportNormScale(ch.bits, false)); break;
                case RealKind::Snorm:
                    x = "float(int(" + v + " << " + ulit(uint64_t(32 - ch.bits)) + ") >> " + ulit(uint64_t(32 - ch.bits)) +
                        ") * " + glslFloatLiteral(exportNormScale(ch.bits, true));
                    break;
                case RealKind::Srgb: x = "decodeSrgb8(" + v + ")"; break;
                case RealKind::Float16: x = "decodeFloat16(" + v + ")"; break;
                case RealKind::Float32: x = "uintBitsToFloat(" + v + ")"; break;
                case RealKind::Float11: x = "decodeFloat11(" + v + ")"; break;
                case RealKind::Float10: x = "decodeFloat10(" + v + ")"; break;
            }
            (void)b;
            comps[size_t(channelComponent(ch))] = x;
        }
        const size_t n = tg.channels.size();
        if (targetType(t) == "uint") o_ << "    return " << comps[0] << ";\n}\n";
        else if (targetType(t) == "uvec2") o_ << "    return uvec2(" << comps[0] << ", " << comps[1] << ");\n}\n";
        else
            o_ << "    return " << targetType(t) << "(" << comps[0] << ", " << comps[1] << ", " << comps[2] << ", "
               << comps[3] << ");\n}\n";
        (void)n;
        o_ << "uvec4 " << p_ << "_rt" << ts << "Words(" << targetType(t) << " v) {\n    uvec4 w = uvec4(0u);\n";
        for (const Channel& ch : tg.channels) {
            const int c = channelComponent(ch);
            const std::string x = targetType(t) == "uint" ? "v" : "v." + std::string(kComp[c]);
            const std::string m = glslFloatLiteral(std::ldexp(1.0, ch.bits) - 1.0);
            const std::string s = glslFloatLiteral(std::ldexp(1.0, ch.bits - 1) - 1.0);
            std::string code;
            switch (realKind(tg, ch)) {
                case RealKind::Uint: code = x; break;
                case RealKind::Unorm: code = "uint(floor(clamp(" + x + ", 0.0, 1.0) * " + m + " + 0.5))"; break;
                case RealKind::Snorm: code = "uint(int(floor(clamp(" + x + ", -1.0, 1.0) * " + s + " + 0.5)))"; break;
                case RealKind::Srgb: code = "encodeSrgb8(" + x + ")"; break;
                case RealKind::Float16: code = "encodeFloat16(" + x + ")"; break;
                case RealKind::Float32: code = "floatBitsToUint(" + x + ")"; break;
                case RealKind::Float11: code = "encodeFloat11(" + x + ")"; break;
                case RealKind::Float10: code = "encodeFloat10(" + x + ")"; break;
            }
            o_ << "    w[" << ch.offset / 32 << "] |= (" << code << " & " << maskLit(ch.bits) << ") << "
               << ulit(uint64_t(ch.offset % 32)) << ";\n";
        }
        o_ << "    return w;\n}\n\n";
    }

    void emitEncode() {
        const bool pixel = exportEncodeTakesPixel(l_);
        o_ << "// Base pass: the surface -> the values for each render target.\n";
        o_ << p_ << "_Targets " << p_ << "_encode(" << p_ << "_Surface s" << (pixel ? ", ivec2 pixel" : "") << ") {\n";
        o_ << "    " << p_ << "_Targets t;\n";
        // The shading-model selector (layouts/README.md, "Shading models"): the model by the rule the
        // renderer's writeGBuffer and the CPU codec take (src/layout/shading_models.cpp), from the
        // surface's layers; the surface's shadingModel member is what decode read back, not an input.
        if (l_.selector()) emitModelPick(o_, "    ", l_, "gblModel");
        for (size_t t = 0; t < l_.targets.size(); ++t) {
            const Target& tg = l_.targets[t];
            const std::string ts = std::to_string(t);
            o_ << "    // target " << t << " '" << glslCommentText(tg.name) << "'\n";
            o_ << "    uvec4 w" << ts << " = uvec4(0u);\n";
            for (size_t fi = 0; fi < tg.fields.size(); ++fi) {
                const Field& f = tg.fields[fi];
                const std::string id = "e" + ts + "_" + std::to_string(fi);
                std::string at;
                for (const CodePlace& cp : f.codes) at += (at.empty() ? "" : ", ") + glslCommentText(cp.text);
                o_ << "    // " << attributeName(f.attribute) << ": " << f.encoding << " at " << at
                   << (f.conditional() ? " (under " + shadingModelNames(f.models) + ")" : "") << "\n";
                if (f.attribute == Attribute::ShadingModel) {
                    emitPlaceCode(o_, "    ", tg, f.codes[0], "w" + ts, modelIdExpr(f, "gblModel"));
                    continue;
                }
                const std::string ind = f.conditional() ? "        " : "    ";
                if (f.conditional()) o_ << "    if (" << maskTest(f.models, "gblModel") << ") {\n";
                const std::vector<std::string> codes = emitEncodeField(o_, ind, f, id, true);
                for (size_t i = 0; i < codes.size(); ++i) {
                    const std::string cv = id + "_c" + std::to_string(i);
                    o_ << ind << "uint " << cv << " = " << codes[i] << ";\n";
                    emitPlaceCode(o_, ind, tg, f.codes[i], "w" + ts, cv);
                }
                if (f.conditional()) o_ << "    }\n";
            }
            o_ << "    t." << targetMember(t) << " = " << p_ << "_rt" << ts << "Values(w" << ts << ");\n";
        }
        o_ << "    return t;\n}\n\n";
    }

    void emitDecode() {
        const bool neighbours = exportDecodeReconstructs(l_);
        for (size_t t = 0; t < l_.targets.size(); ++t) {
            const Target& tg = l_.targets[t];
            for (size_t fi = 0; fi < tg.fields.size(); ++fi) {
                const Field& f = tg.fields[fi];
                if (!fieldNeedsNeighbours(f)) continue;
                const std::string b = ulit(uint64_t(f.bitsOfCode(0)));
                o_ << "vec2 " << p_ << "_lumaChroma" << t << "_" << fi << "(uvec4 w) {\n";
                o_ << "    return vec2(dequantizeUnorm(" << extractCode(tg, f.codes[0], "w") << ", " << b << "), "
                   << chromaDequantize(f.encoding) << "(" << extractCode(tg, f.codes[1], "w") << ", " << b << "));\n}\n";
            }
        }
        o_ << "// Lighting pass: the targets' values -> the surface";
        if (neighbours)
            o_ << ". Checkerboard chroma is rebuilt from the 4 neighbours\n"
                  "// (+x, -x, +y, -y; mirrored at the image border: x = -1 reads x = 1) and `covered`, 1 where a\n"
                  "// neighbour holds geometry (depth != clear depth), 0 where it does not";
        o_ << ".\n";
        const std::string T = p_ + "_Targets";
        o_ << p_ << "_Surface " << p_ << "_decode(" << T << " t";
        if (neighbours) o_ << ", " << T << " px, " << T << " nx, " << T << " py, " << T << " ny, vec4 covered, ivec2 pixel";
        o_ << ") {\n    " << p_ << "_Surface s = " << p_ << "_surfaceDefaults();\n";
        for (size_t t = 0; t < l_.targets.size(); ++t)
            o_ << "    uvec4 w" << t << " = " << p_ << "_rt" << t << "Words(t." << targetMember(t) << ");\n";
        // The stored model id first: the conditional fields and fallbacks test it.
        for (size_t t = 0; t < l_.targets.size(); ++t)
            for (const Field& f : l_.targets[t].fields)
                if (&f == l_.selector())
                    o_ << "    uint gblSel = " << extractCode(l_.targets[t], f.codes[0], "w" + std::to_string(t))
                       << ";  // the shading-model selector\n";
        for (size_t t = 0; t < l_.targets.size(); ++t) {
            const Target& tg = l_.targets[t];
            const std::string ts = std::to_string(t);
            for (size_t fi = 0; fi < tg.fields.size(); ++fi) {
                const Field& f = tg.fields[fi];
                const char* sm = surfaceMemberName(f.attribute);
                const std::string member = sm ? std::string(sm) : extraMemberName(f.attribute);
                const std::string lhs = (f.conditional() ? "    if (" + maskTest(l_.selectorIds(f.models), "gblSel") + ")" : std::string("   ")) +
                                        " s." + member + " = ";
                if (fieldNeedsNeighbours(f)) {
                    std::string fwd, inv;
                    colorTransform(f.encoding, fwd, inv);
                    const std::string fn = p_ + "_lumaChroma" + ts + "_" + std::to_string(fi);
                    const std::string m = targetMember(t), W = p_ + "_rt" + ts + "Words";
                    o_ << "    {\n        vec2 c = " << fn << "(w" << ts << ");\n";
                    const char* nb[4] = {"px", "nx", "py", "ny"};
                    for (int k = 0; k < 4; ++k)
                        o_ << "        vec2 n" << k << " = " << fn << "(" << W << "(" << nb[k] << "." << m << "));\n";
                    o_ << "        vec2 ch = reconstructChroma(pixel, c.x, c.y, vec4(n0.x, n1.x, n2.x, n3.x), "
                          "vec4(n0.y, n1.y, n2.y, n3.y), covered);\n";
                    o_ << "    " << lhs << inv << "(vec3(c.x, ch.x, ch.y));\n    }\n";
                    continue;
                }
                std::vector<std::string> codes;
                for (const CodePlace& cp : f.codes) codes.push_back(extractCode(tg, cp, "w" + ts));
                if (f.encoding == kIdEncoding) {
                    if (codes.size() == 1) {
                        o_ << lhs << codes[0] << ";\n";
                    } else {
                        o_ << lhs << kUvec[codes.size() - 1] << "(";
                        for (size_t i = 0; i < codes.size(); ++i) o_ << (i ? ", " : "") << codes[i];
                        o_ << ");\n";
                    }
                    continue;
                }
                const bool isUint = !sm && attributeInfo(f.attribute).type == ValueType::Integer;
                const std::string e = decodeFieldExpr(f, codes);
                o_ << lhs << (isUint ? "uint(" + e + ")" : e) << ";\n";
                // What the encoding also stores (HDRP's AO tag: occlusion; HDRP's anisotropy: the
                // strength, under the field's models only), as the renderer's decode sets it.
                if (const std::string carried = decodeCarriedStatement(f, codes); !carried.empty())
                    o_ << (f.conditional() ? "    if (" + maskTest(l_.selectorIds(f.models), "gblSel") + ") " : "    ")
                       << carried << "\n";
            }
        }
        for (const Fallback* fb : orderedFallbacks(l_))
            for (const ExportMember& m : members_) {
                if (m.stored || m.attribute != fb->attribute) continue;
                if (l_.storesConditionally(fb->attribute)) {
                    // where the pixel's model stores none of its fields
                    o_ << "    if (!(" << maskTest(l_.selectorIds(l_.conditionalModels(fb->attribute)), "gblSel")
                       << ")) {\n    ";
                    emitFallback(o_, *fb, l_);
                    o_ << "    }\n";
                    continue;
                }
                emitFallback(o_, *fb, l_);
            }
        o_ << "    return s;\n}\n\n";
    }

    void emitKernelBody() {
        const int in = exportKernelInputFloats(l_), out = exportKernelOutputWords(l_);
        const std::string K = p_ + "_kernel";
        o_ << "// --kernel: surface i (row-major, GBL_KERNEL_WIDTH x GBL_KERNEL_HEIGHT) is floats [i * " << in << ", (i + 1) * "
           << in << ") of the input:\n// the members in declaration order (a uint member as its bits), then covered "
              "(1: geometry).\n// Output words [i * " << out << ", (i + 1) * " << out
           << "): the decoded members, then 4 words per target (floats as their bits).\n";
        o_ << p_ << "_Surface " << K << "Load(int i) {\n    " << p_ << "_Surface s;\n";
        for (const ExportMember& m : members_) {
            std::vector<std::string> v;
            for (int c = 0; c < m.components; ++c) {
                const std::string x = K + "In[i * " + std::to_string(in) + " + " + std::to_string(m.firstFloat + c) + "]";
                v.push_back(m.isUint ? "floatBitsToUint(" + x + ")" : x);
            }
            std::string e = v.size() == 1 ? v[0] : memberType(m) + "(";
            if (v.size() > 1) {
                for (size_t i = 0; i < v.size(); ++i) e += (i ? ", " : "") + v[i];
                e += ")";
            }
            o_ << "    s." << m.name << " = " << e << ";\n";
        }
        o_ << "    return s;\n}\n";
        o_ << "ivec2 " << K << "Mirror(ivec2 p) {\n    ivec2 size = ivec2(GBL_KERNEL_WIDTH, GBL_KERNEL_HEIGHT);\n"
              "    p = abs(p);\n    p = (size - 1) - abs((size - 1) - p);\n    return clamp(p, ivec2(0, 0), size - 1);\n}\n";
        const bool pixel = exportEncodeTakesPixel(l_);
        o_ << p_ << "_Targets " << K << "Encode(ivec2 p) {\n    return " << p_ << "_encode(" << K
           << "Load(p.y * GBL_KERNEL_WIDTH + p.x)" << (pixel ? ", p" : "") << ");\n}\n";
        o_ << "void " << K << "(ivec2 p) {\n    if (p.x >= GBL_KERNEL_WIDTH || p.y >= GBL_KERNEL_HEIGHT) return;\n";
        o_ << "    " << p_ << "_Targets t = " << K << "Encode(p);\n";
        if (exportDecodeReconstructs(l_)) {
            const char* off[4] = {"ivec2(1, 0)", "ivec2(-1, 0)", "ivec2(0, 1)", "ivec2(0, -1)"};
            for (int k = 0; k < 4; ++k) o_ << "    ivec2 q" << k << " = " << K << "Mirror(p + " << off[k] << ");\n";
            o_ << "    vec4 covered = vec4(";
            for (int k = 0; k < 4; ++k)
                o_ << (k ? ", " : "") << K << "In[(q" << k << ".y * GBL_KERNEL_WIDTH + q" << k << ".x) * " << in << " + "
                   << in - 1 << "]";
            o_ << ");\n";
            o_ << "    " << p_ << "_Surface d = " << p_ << "_decode(t, " << K << "Encode(q0), " << K << "Encode(q1), " << K
               << "Encode(q2), " << K << "Encode(q3), covered, p);\n";
        } else {
            o_ << "    " << p_ << "_Surface d = " << p_ << "_decode(t);\n";
        }
        o_ << "    int o = (p.y * GBL_KERNEL_WIDTH + p.x) * " << out << ";\n";
        for (const ExportMember& m : members_)
            for (int c = 0; c < m.components; ++c) {
                const std::string x = "d." + m.name + (m.components > 1 ? "." + std::string(kComp[c]) : "");
                o_ << "    " << K << "Out[o + " << m.firstFloat + c << "] = " << (m.isUint ? x : "floatBitsToUint(" + x + ")")
                   << ";\n";
            }
        int base = exportKernelInputFloats(l_) - 1;
        for (size_t t = 0; t < l_.targets.size(); ++t, base += 4) {
            const std::string type = targetType(t);
            const int n = type == "uint" ? 1 : type == "uvec2" ? 2 : 4;
            for (int c = 0; c < n; ++c) {
                const std::string x = "t." + targetMember(t) + (n > 1 ? "." + std::string(kComp[c]) : "");
                o_ << "    " << K << "Out[o + " << base + c << "] = " << (uintTarget(t) ? x : "floatBitsToUint(" + x + ")")
                   << ";\n";
            }
        }
        o_ << "}\n";
    }

    const Layout& l_;
    ExportOptions opt_;
    std::string p_;
    std::vector<ExportMember> members_;
    std::ostringstream o_;
};

// A visibility buffer stores ids, not a surface: encode and decode of (triangle, draw, alpha-tested).
std::string visibilityBody(const Layout& l, const ExportOptions& opt) {
    const std::string p = exportPrefix(l);
    const VisibilityIds& ids = l.ids;
    const bool two = ids.bits == 64;
    std::ostringstream o;
    o << "struct " << p << "_Surface {\n    uint triangleId;\n    uint drawId;\n    uint alphaMasked;  // 0 or 1\n};\n";
    o << "struct " << p << "_Targets {\n    " << (two ? "uvec2" : "uint") << " rt0_ids"
      << (opt.language == ExportLanguage::Hlsl ? " : SV_Target0" : "") << ";  // " << glslCommentText(ids.format) << "\n};\n";
    auto put = [&](const std::string& value, int first, int count) {
        // bits [first, first + count) of the 64-bit string, word 0 = bits 0..31
        std::string s;
        int done = 0;
        while (done < count) {
            const int at = first + done, word = at / 32, bit = at % 32, n = std::min(count - done, 32 - bit);
            s += "    w[" + std::to_string(word) + "] |= ((" + value + (done ? " >> " + ulit(uint64_t(done)) : "") + ") & " +
                 maskLit(n) + ") << " + ulit(uint64_t(bit)) + ";\n";
            done += n;
        }
        return s;
    };
    auto get = [&](int first, int count) {
        std::string s;
        int done = 0;
        while (done < count) {
            const int at = first + done, word = at / 32, bit = at % 32, n = std::min(count - done, 32 - bit);
            s += std::string(s.empty() ? "" : " | ") + "(((w[" + std::to_string(word) + "] >> " + ulit(uint64_t(bit)) +
                 ") & " + maskLit(n) + ") << " + ulit(uint64_t(done)) + ")";
            done += n;
        }
        return s;
    };
    o << p << "_Targets " << p << "_encode(" << p << "_Surface s) {\n    uvec2 w = uvec2(0u, 0u);\n";
    o << put("s.triangleId", 0, ids.triangleBits) << put("s.drawId", ids.triangleBits, ids.drawBits);
    if (ids.alphaMaskBit) o << put("s.alphaMasked", ids.bits - 1, 1);
    o << "    " << p << "_Targets t;\n    t.rt0_ids = " << (two ? "w" : "w.x") << ";\n    return t;\n}\n";
    o << p << "_Surface " << p << "_decode(" << p << "_Targets t) {\n    uvec2 w = " << (two ? "t.rt0_ids" : "uvec2(t.rt0_ids, 0u)")
      << ";\n    " << p << "_Surface s;\n    s.triangleId = " << get(0, ids.triangleBits) << ";\n    s.drawId = "
      << get(ids.triangleBits, ids.drawBits) << ";\n    s.alphaMasked = " << (ids.alphaMaskBit ? get(ids.bits - 1, 1) : "0u")
      << ";\n    return s;\n}\n";
    if (opt.kernel) {
        const std::string K = p + "_kernel";
        o << "// --kernel: input 4 words per id (triangle, draw, alpha-tested, unused); output 4 words per id\n"
             "// (triangle, draw, alpha-tested decoded, then the encoded word 0) and 1 more (word 1).\n";
        o << "void " << K << "(ivec2 p) {\n    if (p.x >= GBL_KERNEL_WIDTH || p.y >= GBL_KERNEL_HEIGHT) return;\n"
          << "    int i = p.y * GBL_KERNEL_WIDTH + p.x;\n    " << p << "_Surface s;\n"
          << "    s.triangleId = floatBitsToUint(" << K << "In[i * 4]);\n    s.drawId = floatBitsToUint(" << K
          << "In[i * 4 + 1]);\n    s.alphaMasked = floatBitsToUint(" << K << "In[i * 4 + 2]);\n    " << p << "_Targets t = " << p
          << "_encode(s);\n    " << p << "_Surface d = " << p << "_decode(t);\n    " << (two ? "uvec2 w = t.rt0_ids;" : "uvec2 w = uvec2(t.rt0_ids, 0u);")
          << "\n    " << K << "Out[i * 5] = d.triangleId;\n    " << K << "Out[i * 5 + 1] = d.drawId;\n    " << K
          << "Out[i * 5 + 2] = d.alphaMasked;\n    " << K << "Out[i * 5 + 3] = w.x;\n    " << K << "Out[i * 5 + 4] = w.y;\n}\n";
    }
    return o.str();
}

std::string kernelEntry(const Layout& l, const ExportOptions& opt) {
    const std::string K = exportPrefix(l) + "_kernel";
    std::ostringstream o;
    o << "#ifndef GBL_KERNEL_WIDTH\n#define GBL_KERNEL_WIDTH 256\n#endif\n#ifndef GBL_KERNEL_HEIGHT\n#define GBL_KERNEL_HEIGHT 256\n#endif\n";
    if (opt.language == ExportLanguage::Hlsl) {
        o << "StructuredBuffer<float> " << K << "In : register(t0);\nRWStructuredBuffer<uint> " << K << "Out : register(u1);\n";
    } else {
        o << "layout(std430, set = 0, binding = 0) readonly buffer " << K << "InBuffer { float " << K << "In[]; };\n";
        o << "layout(std430, set = 0, binding = 1) writeonly buffer " << K << "OutBuffer { uint " << K << "Out[]; };\n";
    }
    return o.str();
}

std::string kernelMain(const Layout& l, const ExportOptions& opt) {
    const std::string K = exportPrefix(l) + "_kernel";
    if (opt.language == ExportLanguage::Hlsl)
        return "[numthreads(8, 8, 1)]\nvoid main(uint3 id : SV_DispatchThreadID) { " + K + "(int2(id.xy)); }\n";
    return "layout(local_size_x = 8, local_size_y = 8) in;\nvoid main() { " + K + "(ivec2(gl_GlobalInvocationID.xy)); }\n";
}

std::string bestFitTableDeclaration(ExportLanguage lang) {
    if (lang == ExportLanguage::Hlsl)
        return "#ifndef GBL_BEST_FIT_TABLE_DECLARED\n#define GBL_BEST_FIT_TABLE_DECLARED\n"
               "#ifndef GBL_BEST_FIT_TABLE_REGISTER\n#define GBL_BEST_FIT_TABLE_REGISTER t2\n#endif\n"
               "StructuredBuffer<uint> gbl_bestFitNormalTable : register(GBL_BEST_FIT_TABLE_REGISTER);\n#endif\n";
    return "#ifndef GBL_BEST_FIT_TABLE_DECLARED\n#define GBL_BEST_FIT_TABLE_DECLARED\n"
           "#ifndef GBL_BEST_FIT_TABLE_SET\n#define GBL_BEST_FIT_TABLE_SET 0\n#endif\n"
           "#ifndef GBL_BEST_FIT_TABLE_BINDING\n#define GBL_BEST_FIT_TABLE_BINDING 2\n#endif\n"
           "layout(std430, set = GBL_BEST_FIT_TABLE_SET, binding = GBL_BEST_FIT_TABLE_BINDING) readonly buffer "
           "GblBestFitNormalTable { uint gbl_bestFitNormalTable[]; };\n#endif\n";
}

}  // namespace

RealKind realKind(const Target& t, const Channel& c) {
    switch (c.type) {
        case ChannelType::Uint: return RealKind::Uint;
        case ChannelType::Srgb: return RealKind::Srgb;
        case ChannelType::Sfloat: return c.bits == 16 ? RealKind::Float16 : RealKind::Float32;
        case ChannelType::Ufloat: return c.bits == 11 ? RealKind::Float11 : RealKind::Float10;
        case ChannelType::Unorm: break;
    }
    return t.format.find("SNORM") != std::string::npos ? RealKind::Snorm : RealKind::Unorm;
}

std::string exportIdentifier(const std::string& text) {
    std::string out;
    for (char c : text) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
        if (ok) out += c;
        else if (!out.empty() && out.back() != '_') out += '_';
        if (out.size() >= 40) break;
    }
    while (!out.empty() && out.back() == '_') out.pop_back();
    return out.empty() ? "x" : out;
}

std::string exportPrefix(const Layout& layout) { return "gbl_" + exportIdentifier(layout.name); }

std::vector<ExportMember> exportSurfaceMembers(const Layout& layout) {
    std::vector<ExportMember> out;
    int next = 0;
    auto add = [&](ExportMember m) {
        m.firstFloat = next;
        next += m.components;
        out.push_back(std::move(m));
    };
    if (layout.pipeline == Pipeline::VisibilityBuffer) {
        for (const char* n : {"triangleId", "drawId", "alphaMasked"}) {
            ExportMember m;
            m.name = n;
            m.isUint = true;
            add(m);
        }
        return out;
    }
    // Stored attributes, constants, and what derives from members only (forward and material_pass
    // attributes come from other passes: not members, nor what a formula would derive from them).
    std::set<Attribute> derived;
    for (const Fallback* fb : orderedFallbacks(layout)) {
        if (fb->kind == FallbackKind::Forward || fb->kind == FallbackKind::MaterialPass) continue;
        bool inputs = true;
        for (Attribute in : fallbackInputs(fb->kind)) inputs = inputs && (layout.stores(in) || derived.count(in));
        if (inputs) derived.insert(fb->attribute);
    }
    // The layers the selector's rule tests (src/layout/shading_models.cpp) are read by encode even
    // where the layout stores none of their fields.
    std::set<Attribute> tested;
    for (const ShadingModelInfo& sm : listShadingModels())
        if (sm.id != ShadingModel::Default && ((layout.selectorModels() >> unsigned(sm.id)) & 1u)) tested.insert(sm.test);
    for (Attribute a : surfaceAttributes()) {
        // An attribute stored under some models only is a member that decode may also derive
        // (its fallback, where the pixel's model does not store it).
        const bool stored = layout.stores(a) && !(layout.storesConditionally(a) && layout.findFallback(a));
        if (!layout.stores(a) && !derived.count(a) && !tested.count(a)) continue;
        ExportMember m;
        m.name = surfaceMemberName(a);
        m.attribute = a;
        m.components = attributeInfo(a).components;
        m.stored = stored;
        add(m);
    }
    std::set<Attribute> extras;
    for (const Target& t : layout.targets)
        for (const Field& f : t.fields) {
            if (surfaceMemberName(f.attribute)) continue;
            if (!extras.insert(f.attribute).second) continue;  // an extra stored under two models: one member
            ExportMember m;
            m.name = extraMemberName(f.attribute);
            m.attribute = f.attribute;
            m.components = std::min(4, attributeInfo(f.attribute).components);
            m.isUint = attributeInfo(f.attribute).type == ValueType::Integer;
            m.defaultValue = f.value;
            add(m);
        }
    return out;
}

int exportKernelInputFloats(const Layout& layout) {
    int n = 0;
    for (const ExportMember& m : exportSurfaceMembers(layout)) n += m.components;
    return n + 1;
}

int exportKernelOutputWords(const Layout& layout) {
    return exportKernelInputFloats(layout) - 1 + 4 * int(layout.targets.size());
}

bool exportEncodeTakesPixel(const Layout& layout) {
    for (const Target& t : layout.targets)
        for (const Field& f : t.fields) {
            const EncodingInfo* e = findEncoding(f.encoding);
            if (e && (e->needsNeighbours || e->dithered)) return true;
        }
    return false;
}

bool exportDecodeReconstructs(const Layout& layout) {
    for (const Target& t : layout.targets)
        for (const Field& f : t.fields)
            if (fieldNeedsNeighbours(f)) return true;
    return false;
}

bool exportUsesBestFitTable(const Layout& layout) {
    for (const Target& t : layout.targets)
        for (const Field& f : t.fields)
            if (f.encoding == "normal_bestfit") return true;
    return false;
}

float exportNormScale(int bits, bool isSigned) {
    const double m = isSigned ? std::ldexp(1.0, bits - 1) - 1.0 : std::ldexp(1.0, bits) - 1.0;
    // 2^-20 above 1/m: float(code) * k rounded to nearest or towards zero (relative error below
    // 2^-23) stays above code / m, and at most code * 2^-19.9 above it (< 0.25 for 16 bits).
    const double target = (1.0 / m) * (1.0 + std::ldexp(1.0, -20));
    float k = float(target);
    if (double(k) < target) k = std::nextafter(k, 2.0f);
    return k;
}

std::string exportLayout(const Layout& layout, const ExportOptions& options, const exporting::ShaderFileReader& read) {
    return exportLayout(layout, options, exporting::GlslLibrary(read));
}

std::string exportLayout(const Layout& layout, const ExportOptions& options, const exporting::GlslLibrary& library) {
    const bool vis = layout.pipeline == Pipeline::VisibilityBuffer;
    std::string body = vis ? visibilityBody(layout, options) : Generator(layout, options).body();
    const std::vector<const exporting::GlslDeclaration*> helpers = library.closure(exporting::identifiersOf(body), options.tables);
    std::set<std::string> rename = {"bestFitNormalTable"};
    for (const exporting::GlslDeclaration* d : helpers)
        if (d->name.rfind("GBL_", 0) != 0 && d->name.rfind("gbl", 0) != 0) rename.insert(d->name);
    const bool hlsl = options.language == ExportLanguage::Hlsl;
    auto lang = [&](const std::string& glsl) {
        const std::string named = exporting::prefixIdentifiers(glsl, rename, "gbl_");
        return hlsl ? exporting::translateGlslToHlsl(named) : named;
    };

    std::ostringstream o;
    // With the kernel, the GLSL is a whole compute shader: its #version comes first.
    if (options.kernel && !hlsl) o << "#version 450\n";
    o << exportHeaderComment(layout, options);
    const std::string guard = "GBL_EXPORT_" + exportIdentifier(layout.name);
    o << "#ifndef " << guard << "\n#define " << guard << "\n\n";
    if (!helpers.empty())
        o << "// ---- encoding helpers: shaders/*_encodings.glsl of gbufferlab, as the renderer compiles them"
          << (options.tables == exporting::ExportTables::Selects ? " (the 8-bit tables as select trees: export_tables.h)" : "")
          << " ----\n";
    if (exportUsesBestFitTable(layout)) o << bestFitTableDeclaration(options.language);
    std::map<std::string, int> seen;
    for (const exporting::GlslDeclaration* d : helpers) {
        const int k = seen[d->name]++;
        if (d->isDefine) {
            o << "#ifndef " << d->name << "\n" << d->code << "#endif\n";
            continue;
        }
        const std::string g = "GBL_HELPER_" + d->name + "_" + std::to_string(k);
        o << "#ifndef " << g << "\n#define " << g << "\n" << lang(d->comment)
          << (hlsl && d->isConstant ? "static " : "") << lang(d->code) << "#endif\n";
    }
    o << "\n// ---- the layout ----\n";
    if (options.kernel) o << kernelEntry(layout, options);
    o << lang(body);
    o << "#endif  // " << guard << "\n";
    // A harness that includes the file into a shader of its own (a raster pass that encodes the
    // kernel's input, tests/codec/layout_export_gpu_test.cpp) defines GBL_KERNEL_NO_MAIN.
    if (options.kernel) o << "\n#ifndef GBL_KERNEL_NO_MAIN\n" << kernelMain(layout, options) << "#endif\n";
    return o.str();
}

}  // namespace gbl
