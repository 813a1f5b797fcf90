// The layout-level assembly of the wiring: where each code goes in a target's words (shifts and
// masks from the layout's bit places), the fallbacks, and writeGBuffer / readGBuffer put together
// from the per-field expressions of wiring_field_codegen.cpp.
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
#include "wiring_field_codegen.h"

namespace gbl {

// The per-encoding expressions of a field (wiring_field_codegen.cpp).
using namespace wiring;

namespace wiring {

std::string maskLit(int bits) { return bits >= 32 ? "0xffffffffu" : ulit((uint64_t(1) << bits) - 1); }

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

}  // namespace wiring

namespace {

std::string outTypeOf(int words, int bits) {
    if (bits <= 32) return "uint";
    return words == 2 ? "uvec2" : "uvec4";
}

std::string wordsToOut(int words, int bits, const std::string& w) {
    if (bits <= 32) return w + ".x";
    return words == 2 ? w + ".xy" : w;
}

std::string zeroOf(Attribute a) { return attributeComponents(a) == 1 ? "0.0" : "vec3(0.0)"; }

}  // namespace

void wiring::emitFallback(std::ostream& o, const Fallback& fb, const Layout& layout) {
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
        case FallbackKind::FromRoughness:
            o << lhs << "s.roughness;  // from_roughness\n";
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

std::string nativeFormatObstacle(const Target& target) {
    bool anyUint = false;
    for (const Channel& c : target.channels) anyUint |= c.type == ChannelType::Uint;
    if (anyUint) return target.format + " is an integer format";
    for (const Field& f : target.fields)
        if (f.conditional() || f.attribute == Attribute::ShadingModel)
            return "field '" + std::string(attributeName(f.attribute)) +
                   "' depends on the shading model: its bits are integer-placed per pixel";
    for (const Field& f : target.fields)
        if (!nativeField(target, f))
            return "field '" + std::string(attributeName(f.attribute)) + "' (" + f.encoding +
                   ") packs codes that " + target.format + " cannot express as whole channels of its own encoding";
    return "";
}

namespace {

// Which targets the write keeps in their native format (--native-formats), with a comment for each
// that stays UINT and why.
std::vector<bool> nativeTargets(std::ostringstream& o, const Layout& layout, const WiringOptions& options) {
    std::vector<bool> native(layout.targets.size(), false);
    for (size_t t = 0; t < layout.targets.size(); ++t) {
        const Target& tg = layout.targets[t];
        if (!options.nativeFormats) continue;
        const std::string why = nativeFormatObstacle(tg);
        native[t] = why.empty();
        if (!why.empty()) o << "// --native-formats: target " << t << " '" << glslCommentText(tg.name) << "' stays UINT: " << why << "\n";
    }
    return native;
}

// MATERIAL_PASS_WRITE: the attributes a slim G-buffer leaves to the material pass, as float32 bits.
void emitMaterialPassWrite(std::ostringstream& o, const Layout& layout) {
    const bool materialPass = materialTargetCount(layout) > 0;
    const int materialTargets = materialTargetCount(layout);
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
}

// One field of target t written into the target's words (or its native vector).
void emitFieldWrite(std::ostringstream& o, const Target& tg, size_t t, size_t fi, bool native) {
    const std::string ts = std::to_string(t);
    const Field& f = tg.fields[fi];
    const std::string id = "e" + ts + "_" + std::to_string(fi);
    std::string at;
    for (const CodePlace& cp : f.codes) at += (at.empty() ? "" : ", ") + cp.text;
    o << "    // " << attributeName(f.attribute) << ": " << f.encoding << " at " << at
      << (f.conditional() ? " (under " + shadingModelNames(f.models) + ")" : "") << "\n";
    if (f.attribute == Attribute::ShadingModel) {  // the selector: the id of the pixel's model
        emitPlaceCode(o, "    ", tg, f.codes[0], "w" + ts, modelIdExpr(f, "gblModel"));
        return;
    }
    if (f.conditional()) {
        // Written on the pixels of its models only: elsewhere its bits belong to another model's fields.
        o << "    if (" << maskTest(f.models, "gblModel") << ") {\n";
        const std::vector<std::string> codes = emitEncodeField(o, "        ", f, id);
        for (size_t i = 0; i < codes.size(); ++i) {
            const std::string cv = id + "_c" + std::to_string(i);
            o << "        uint " << cv << " = " << codes[i] << ";\n";
            emitPlaceCode(o, "        ", tg, f.codes[i], "w" + ts, cv);
        }
        o << "    }\n";
        return;
    }
    if (native) {
        const std::vector<std::string> v = emitNativeEncode(o, "    ", f, id);
        for (size_t i = 0; i < v.size(); ++i) {
            const Channel& ch = tg.channels[size_t(f.codes[i].pieces[0].channel)];
            o << "    v" << ts << "." << kComp[channelComponent(ch)] << " = " << v[i] << ";\n";
        }
        return;
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

// GBUFFER_WRITE: the outputs, the pixel's shading model (a selector's layout), and every field.
void emitGBufferWrite(std::ostringstream& o, const Layout& layout, const std::vector<bool>& native) {
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
    const Field* selector = layout.selector();
    if (selector) emitModelPick(o, "    ", layout, "gblModel");
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
        for (size_t fi = 0; fi < tg.fields.size(); ++fi) emitFieldWrite(o, tg, t, fi, native[t]);
        o << "    gbufferTarget" << ts << " = "
          << (native[t] ? "v" + ts : wordsToOut(wordsPerPixel(tg), tg.bits(), "w" + ts)) << ";\n";
    }
    o << "}\n#endif\n";
}

// GBUFFER_READ's declarations: the targets' samplers, the material pass's, and the checkerboard
// chroma helpers.
void emitReadDeclarations(std::ostringstream& o, const Layout& layout, const std::vector<bool>& native) {
    const int materialTargets = materialTargetCount(layout);
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
}

// One field of target t read into its Surface member.
void emitFieldRead(std::ostringstream& o, const Layout& layout, const Target& tg, size_t t, size_t fi, bool native) {
    const std::string ts = std::to_string(t);
    const Field& f = tg.fields[fi];
    const char* m = surfaceSlotName(f.attribute);
    if (!m) return;  // extras (and the selector, above): no shading meaning
    if (f.conditional()) {
        std::vector<std::string> codes;
        for (const CodePlace& cp : f.codes) codes.push_back(extractCode(tg, cp, "w" + ts));
        const std::string carried = decodeCarriedStatement(f, codes);
        o << "    if (" << maskTest(layout.selectorIds(f.models), "gblSel") << ") " << (carried.empty() ? "" : "{ ")
          << "s." << m << " = " << decodeFieldExpr(f, codes) << ";" << (carried.empty() ? "" : " " + carried + " }")
          << "  // under " << shadingModelNames(f.models) << "\n";
        return;
    }
    const std::string lhs = std::string("    s.") + m + " = ";
    if (native) {
        std::vector<std::string> u;
        for (const CodePlace& cp : f.codes)
            u.push_back("v" + ts + "." + kComp[channelComponent(tg.channels[size_t(cp.pieces[0].channel)])]);
        o << lhs << nativeDecodeExpr(f, u) << ";\n";
        return;
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
        return;
    }
    std::vector<std::string> codes;
    for (const CodePlace& cp : f.codes) codes.push_back(extractCode(tg, cp, "w" + ts));
    o << lhs << decodeFieldExpr(f, codes) << ";\n";
    if (const std::string carried = decodeCarriedStatement(f, codes); !carried.empty())
        o << "    " << carried << "\n";
}

// What no field sets: the attributes not stored (zero, "no layer", or rebuilt), then the
// fallbacks in dependency order (per model where the attribute is stored under some models).
void emitUnstoredAndFallbacks(std::ostringstream& o, const Layout& layout) {
    // Unstored attributes without a fallback (position: the lighting pass rebuilds it from depth).
    // The layers a layout does not store decode as 0, "no layer" (layouts/README.md, Attributes).
    for (Attribute a : surfaceAttributes())
        if (!layout.stores(a) && !layout.findFallback(a)) {
            const bool depthInZ = a == Attribute::Position && layout.stores(Attribute::Depth);
            o << "    s." << (depthInZ ? "position.xy" : surfaceMemberName(a)) << " = "
              << (depthInZ ? "vec2(0.0)" : zeroOf(a)) << ";  // not stored"
              << (isLayerAttribute(a)       ? ": no layer"
                  : a != Attribute::Position ? ""
                  : depthInZ              ? ": z holds the stored depth, the lighting pass rebuilds position from it"
                                          : ": rebuilt from depth by the lighting pass")
              << "\n";
        }
    if (!layout.selector()) o << "    s.shadingModel = 0.0;  // no shading-model selector\n";
    for (const Fallback* fb : orderedFallbacks(layout)) {
        if (layout.storesConditionally(fb->attribute) && surfaceMemberName(fb->attribute)) {
            // Where the pixel's model does not store it.
            o << "    if (!(" << maskTest(layout.selectorIds(layout.conditionalModels(fb->attribute)), "gblSel")
              << ")) {\n    ";
            emitFallback(o, *fb, layout);
            o << "    }\n";
            continue;
        }
        emitFallback(o, *fb, layout);
    }
}

// GBUFFER_READ's readGBuffer: the texels, the stored model id, every field, then what no field sets.
void emitGBufferRead(std::ostringstream& o, const Layout& layout, const std::vector<bool>& native) {
    const int materialTargets = materialTargetCount(layout);
    o << "Surface readGBuffer(ivec2 pixel) {\n    Surface s;\n";
    for (size_t t = 0; t < layout.targets.size(); ++t)
        o << "    " << (native[t] ? "vec4 v" : "uvec4 w") << t << " = texelFetch(gbufferTarget" << t
          << ", pixel, 0);\n";
    for (int i = 0; i < materialTargets; ++i)
        o << "    uvec4 m" << i << " = texelFetch(materialTarget" << i << ", pixel, 0);\n";
    const Field* readSelector = layout.selector();
    if (readSelector) {
        // The stored model id, before any field: the conditional fields and fallbacks test it.
        for (size_t t = 0; t < layout.targets.size(); ++t)
            for (const Field& f : layout.targets[t].fields)
                if (&f == readSelector)
                    o << "    uint gblSel = " << extractCode(layout.targets[t], f.codes[0], "w" + std::to_string(t))
                      << ";  // the shading-model selector\n";
        o << "    s.shadingModel = float(gblSel);\n";
        // An attribute stored under some models only starts as 0 ("no layer"); its fields and its
        // fallback set it where they hold.
        for (Attribute a : surfaceAttributes())
            if (layout.storesConditionally(a))
                o << "    s." << surfaceSlotName(a) << " = " << zeroOf(a) << ";  // stored under "
                  << shadingModelNames(layout.conditionalModels(a)) << " only\n";
    }
    for (size_t t = 0; t < layout.targets.size(); ++t)
        for (size_t fi = 0; fi < layout.targets[t].fields.size(); ++fi)
            emitFieldRead(o, layout, layout.targets[t], t, fi, native[t]);
    emitUnstoredAndFallbacks(o, layout);
    o << "    return s;\n}\n#endif\n";
}

}  // namespace

std::string generateWiringGlsl(const Layout& layout, const WiringOptions& options) {
    if (layout.pipeline == Pipeline::VisibilityBuffer) return generateVisibilityWiringGlsl(layout);
    std::ostringstream o;
    o << "// generated from the layout '" << glslCommentText(layout.name) << "' by gbufferlab -- do not edit\n";
    o << "// " << glslCommentText(layout.title) << " (" << pipelineName(layout.pipeline) << ")\n";
    o << "// Integer-only wiring: every code is placed with shifts and masks; src/codec/cpu_codec.cpp mirrors it.\n";
    if (!layout.depth.stencil.empty())
        o << "// Stencil extras are constants written by the renderer's stencil reference, not here.\n";
    o << "#include \"encodings.glsl\"\n";
    const std::vector<bool> native = nativeTargets(o, layout, options);
    emitMaterialPassWrite(o, layout);
    emitGBufferWrite(o, layout, native);
    emitReadDeclarations(o, layout, native);
    emitGBufferRead(o, layout, native);
    return o.str();
}

bool usesBestFitTable(const Layout& layout) {
    for (const Target& t : layout.targets)
        for (const Field& f : t.fields)
            if (f.encoding == "normal_bestfit") return true;
    return false;
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
    w.storesDepth = layout.stores(Attribute::Depth);
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
    w.bestFitTable = usesBestFitTable(layout);
    w.materialPass = materialTargetCount(layout) > 0;
    w.materialTargetFormats.assign(size_t(materialTargetCount(layout)), VK_FORMAT_R32G32B32A32_UINT);
    w.glsl = generateWiringGlsl(layout, options);
    w.lightBufferGlsl = generateLightBufferGlsl(layout);
    if (!w.lightBufferGlsl.empty()) w.lightBufferWordsPerPixel = lightBufferWordsPerPixel(layout);
    bool allUint = true;
    for (size_t t = 0; t < layout.targets.size(); ++t) allUint = allUint && w.targetFormats[t] == uintFormatOf(layout.targets[t]);
    if (allUint) {
        auto codec = std::make_shared<const CpuCodec>(layout);
        if (codec->decodes()) w.cpuDecoder = std::move(codec);
    }
    return w;
}

}  // namespace gbl
