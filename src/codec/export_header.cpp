// The header comment of an exported layout (export_header.h).
#include "export_header.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <sstream>

#include "cpu_codec.h"
#include "encodings.h"
#include "glsl_text.h"
#include "layout_export.h"
#include "wiring_field_codegen.h"
#include "wiring_plan.h"

namespace gbl {

namespace {

std::string c(const std::string& text) { return glslCommentText(text); }

std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

std::string provenanceText(const Provenance& p) {
    if (!p.given()) return "";
    std::string s = std::string(" [") + provenanceStatusName(p.status);
    if (!p.from.empty()) s += ": " + p.from;
    s += "]";
    if (!p.differs.empty()) s += " differs: " + p.differs;
    return c(s);
}

const char* kindText(RealKind k) {
    switch (k) {
        case RealKind::Unorm: return "UNORM";
        case RealKind::Snorm: return "SNORM";
        case RealKind::Srgb: return "sRGB";
        case RealKind::Float16: return "float16";
        case RealKind::Float32: return "float32";
        case RealKind::Float11: return "float11";
        case RealKind::Float10: return "float10";
        case RealKind::Uint: return "UINT";
    }
    return "?";
}

// The value a channel code is written as (what a clear with that value stores).
std::string channelValue(RealKind k, uint32_t code, int bits) {
    switch (k) {
        case RealKind::Uint: return std::to_string(code);
        case RealKind::Unorm: return number(std::min(1.0, double(float(code) * exportNormScale(bits, false))));
        case RealKind::Snorm: {
            const int32_t v = int32_t(code << (32 - bits)) >> (32 - bits);
            return number(std::clamp(double(float(v) * exportNormScale(bits, true)), -1.0, 1.0));
        }
        case RealKind::Srgb: return number(double(enc::decodeSrgb8(code)));
        case RealKind::Float16: return number(double(enc::decodeFloat16(code)));
        case RealKind::Float11: return number(double(enc::decodeFloat11(code)));
        case RealKind::Float10: return number(double(enc::decodeFloat10(code)));
        case RealKind::Float32: {
            float f;
            std::memcpy(&f, &code, 4);
            return number(double(f));
        }
    }
    return "?";
}

std::string fallbackText(const Fallback& f) {
    switch (f.kind) {
        case FallbackKind::Constant: {
            std::string s;
            for (double v : f.value) s += (s.empty() ? "" : ", ") + number(v);
            return "the constant " + s;
        }
        case FallbackKind::FromMetallic: return "mix(0.04, baseColor, metallic) (from_metallic)";
        case FallbackKind::Ue4: return "mix(0.08 * specular, baseColor, metallic) (ue4, Karis 2013)";
        case FallbackKind::FromBaseColor: return "baseColor * (1 - metallic) (from_base_color)";
        case FallbackKind::FromDiffuseSpecular: return "diffuseColor + metallic * specularColor (from_diffuse_specular)";
        case FallbackKind::FromSpecularColor: return "clamp((max3(specularColor) - 0.04) / 0.96, 0, 1) (from_specular_color)";
        case FallbackKind::FromRoughness: return "roughness (from_roughness)";
        case FallbackKind::MaterialPass: return "not here: the material (second geometry) pass supplies it";
        case FallbackKind::Forward: return "not here: written by a forward pass into scene colour (forward)";
    }
    return "?";
}

}  // namespace

std::string exportHeaderComment(const Layout& l, const ExportOptions& options) {
    const bool hlsl = options.language == ExportLanguage::Hlsl;
    const std::string p = exportPrefix(l);
    std::ostringstream o;
    o << "// " << p << ": the G-buffer layout '" << c(l.name) << "', exported by gbufferlab (layouts export) -- generated, do not edit\n";
    o << "// " << c(l.title) << "\n";
    o << "// " << (hlsl ? "HLSL, Shader Model 5 or 6 (FXC, DXC; checked with glslang's HLSL front end)"
                        : "GLSL 450: include it, or paste it, after #version 450")
      << "; pipeline " << pipelineName(l.pipeline) << ".\n";
    o << "// Source: " << c(l.source.text()) << "\n";
    if (!l.citations.empty()) {
        o << "// Sources cited per entry below ([status: key:locator]):\n";
        for (const Citation& ci : l.citations) o << "//   " << c(ci.key) << " = " << c(ci.text()) << "\n";
    }
    o << "//\n// Use: base pass  " << p << "_Targets t = " << p << "_encode(surface"
      << (exportEncodeTakesPixel(l) ? ", pixel" : "") << ");  then write t's members to the targets, in order.\n";
    o << "//      lighting   " << p << "_Surface s = " << p << "_decode(targets"
      << (exportDecodeReconstructs(l) ? ", the +x, -x, +y, -y neighbours' targets, their coverage, pixel" : "") << ");\n";
    o << "//      " << p << "_surfaceDefaults() gives zeros and the layout's values of its extras.\n";
    if (l.pipeline == Pipeline::VisibilityBuffer) {
        const VisibilityIds& ids = l.ids;
        o << "//\n// Target 0 'ids': " << c(ids.format) << " (UINT), cleared to 0: triangle id bits 0.." << ids.triangleBits - 1
          << ", draw id bits " << ids.triangleBits << ".." << ids.triangleBits + ids.drawBits - 1;
        if (ids.alphaMaskBit) o << ", bit " << ids.bits - 1 << " = alpha-tested";
        o << provenanceText(ids.provenance) << "\n";
        o << "// Depth: " << c(l.depth.format) << (l.depth.reversedZ ? ", reversed Z" : "") << "; the lighting pass rebuilds the surface from the triangle.\n//\n";
        return o.str();
    }
    o << "//\n// Units: normal unit, in the layout's space: " << storedSpaceName(l.space.normal)
      << " (transform into it before encode); baseColor, specularColor, diffuseColor, emissive linear;\n"
         "// roughness perceptual (GGX alpha = roughness^2); specular UE4's scalar (F0 = 0.08 specular).\n";
    if (l.stores(Attribute::Position)) o << "// position: in the space " << storedSpaceName(l.space.position) << ".\n";
    o << "//\n// Render targets (attachment order), real formats; bits from bit 0 of the pixel, little-endian:\n";
    const std::vector<std::array<uint32_t, 4>> clear = clearWords(l);
    for (size_t t = 0; t < l.targets.size(); ++t) {
        const Target& tg = l.targets[t];
        o << "//   " << t << " '" << c(tg.name) << "' " << c(tg.format) << " (" << tg.bits() << " bits)" << provenanceText(tg.provenance) << "\n";
        std::string channels, clears;
        for (const Channel& ch : tg.channels) {
            const RealKind k = realKind(tg, ch);
            channels += (channels.empty() ? "" : ", ") + ch.name + ":" + kindText(k) + std::to_string(ch.bits);
            const uint32_t code = (clear[t][size_t(ch.offset / 32)] >> (ch.offset % 32)) &
                                  (ch.bits >= 32 ? 0xffffffffu : (1u << ch.bits) - 1u);
            clears += (clears.empty() ? "" : ", ") + ch.name + " = " + channelValue(k, code, ch.bits) + " (code " +
                      std::to_string(code) + ")";
        }
        o << "//     channels " << channels << "\n//     clear: " << clears << "\n";
        for (const Field& f : tg.fields) {
            std::string at;
            for (const CodePlace& cp : f.codes) at += (at.empty() ? "" : ", ") + c(cp.text);
            o << "//     " << attributeName(f.attribute) << ": " << c(f.encoding) << " at " << at << " (" << f.totalBits()
              << " bits)";
            if (!f.value.empty()) {
                std::string v;
                for (double x : f.value) v += (v.empty() ? "" : ", ") + number(x);
                o << ", layout value " << v;
            }
            o << provenanceText(f.provenance) << "\n";
        }
    }
    o << "// Depth: " << c(l.depth.format) << (l.depth.reversedZ ? ", reversed Z (near = 1)" : "")
      << provenanceText(l.depth.provenance) << "\n";
    for (const Field& f : l.depth.stencil) {
        std::string at;
        for (const CodePlace& cp : f.codes) at += (at.empty() ? "" : ", ") + c(cp.text);
        o << "//   stencil " << attributeName(f.attribute) << " at " << at << " = "
          << (f.value.empty() ? std::string("0") : number(f.value[0])) << " (stencil reference; not in this file)"
          << provenanceText(f.provenance) << "\n";
    }
    o << "//\n// Derived instead of stored (decode computes them; encode ignores them):\n";
    bool any = false;
    for (const Fallback& f : l.fallbacks) {
        o << "//   " << attributeName(f.attribute) << " = " << fallbackText(f) << provenanceText(f.provenance) << "\n";
        any = true;
    }
    if (l.stores(Attribute::Depth)) {
        o << "//   position: not stored; rebuild it in the lighting pass from `depth` (gl_FragCoord.z, this layout's Z\n"
             "//     convention), which the G-buffer pass writes and the lighting reads instead of the depth buffer\n";
        any = true;
    } else if (!l.stores(Attribute::Position)) {
        o << "//   position: not stored; rebuild it from depth in the lighting pass\n";
        any = true;
    }
    if (!any) o << "//   nothing\n";
    o << "//\n// Exact values. Encode packs the same words as gbufferlab's renderer and CPU mirror, then writes\n"
         "// each channel as the value its format stores exactly:\n"
         "//   UNORM / SNORM: float(code) * k, k = 1 / (2^b - 1) (SNORM: 1 / (2^(b-1) - 1)) raised by 2^-20. Vulkan\n"
         "//     converts f * (2^b - 1) to 'one of the two closest integers' (round to nearest recommended);\n"
         "//     the product lies in [code, code + 0.25), so rounding to nearest and truncating both give code,\n"
         "//     however the shader's multiply rounds. (SNORM code -2^(b-1) cannot be written: it clamps to -1.)\n"
         "//   sRGB: the code's exact linear value (its decode), not the raw colour, so the hardware's own\n"
         "//     linear-to-sRGB conversion, which may differ from the exact formula near a code boundary, is\n"
         "//     never near one.\n"
         "//   float16 / float11 / float10: the code's own value, representable, so the conversion is exact.\n"
         "//   UINT: the bits.\n"
         "// Decode reads the values back to codes (round to nearest; sRGB and small floats re-encoded).\n";
    if (exportUsesBestFitTable(l))
        o << "//\n// normal_bestfit reads CryEngine's best-fit table (131200 uints, 4 entries each): bind it as\n"
             "// gbl_bestFitNormalTable ("
          << (hlsl ? "register GBL_BEST_FIT_TABLE_REGISTER, default t2" : "set GBL_BEST_FIT_TABLE_SET, binding GBL_BEST_FIT_TABLE_BINDING, default 0, 2")
          << "); `gbufferlab layouts export --out FILE` writes it to FILE.bestfit.u32.\n";
    o << "//\n";
    return o.str();
}

}  // namespace gbl
