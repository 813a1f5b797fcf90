// The validator's checks of one field (its encoding suits its attribute, it places the codes its
// encoding produces with widths the encoding accepts, inside its channels) and of the bits of one
// target (they fit, no two codes share a bit).
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "layout_validator.h"

namespace gbl::layout_validation {

// Number of codes a field's encoding produces for its attribute.
int Validator::expectedCodes(const Field& f, const EncodingInfo* enc) {
    const int components = attributeInfo(f.attribute).components;
    if (!enc) return components;  // "id": one code per component
    if (enc->kind == AttributeKind::Scalar) return components * enc->codeCount;
    return enc->codeCount + (enc->extraBits > 0 ? 1 : 0);
}

// Why `enc` cannot hold `attr` ("" when it can).
std::string Validator::unsuitable(const EncodingInfo& enc, const AttributeInfo& attr) {
    const std::string a = squote(attr.name), e = squote(enc.name);
    switch (enc.kind) {
        case AttributeKind::Normal:
            if (!isDirectionAttribute(attr.id)) return e + " encodes unit normals, not " + a;
            // anisotropy_angle_hdrp: the tangent, with the strength it carries
            if (enc.carries == "anisotropy_strength" && attr.id != Attribute::AnisotropyDirection)
                return e + " stores anisotropy_direction (with anisotropy_strength), not " + a;
            // normal_octahedral_delta_ue: UE's bottom (base) normal, relative to the coat's
            if (enc.reads == "coat_normal" && attr.id != Attribute::Normal)
                return e + " stores normal (relative to coat_normal), not " + a;
            return "";
        case AttributeKind::Color:
            if (attr.components != 3 || isDirectionAttribute(attr.id) || attr.id == Attribute::Position)
                return e + " encodes RGB colours, not " + a;
            if (!enc.reads.empty() && attr.id != Attribute::Emissive)
                return e + " stores emissive relative to " + enc.reads + ", not " + a;
            if (!enc.carries.empty() && attr.id != Attribute::Emissive)
                return e + " stores emissive (and " + enc.carries + " in its tag), not " + a;
            return "";
        case AttributeKind::Scalar:
            break;
    }
    if ((enc.name == "gloss" || enc.name == "smoothness_cry" || enc.name == "cry_gloss_power" || enc.name == "kz2_log_power") &&
        attr.id != Attribute::Roughness)
        return e + " stores roughness only, not " + a;
    if ((enc.name == "reflectance" || enc.name == "reflectance_bevy_webgl2") && attr.id != Attribute::Specular)
        return e + " stores specular only, not " + a;
    if (enc.name == "coat_roughness_bevy" && attr.id != Attribute::CoatRoughness)
        return e + " stores coat_roughness only, not " + a;
    if (attr.domain == ValueDomain::Signed && enc.name != "snorm" && enc.name != "float16" && enc.name != "float32")
        return a + " has components in [-1,1] but " + e + " takes " + enc.inputRange +
               " (use a normal_* encoding, snorm, float16 or float32)";
    if (attr.domain == ValueDomain::Any && enc.name != "float16" && enc.name != "float32")
        return a + " is unbounded: store it as float16 or float32, not " + e;
    return "";
}

// Everything about one field that does not involve other fields. `channels` is the target's
// (or the stencil's) channel list, `format` its name for messages.
void Validator::checkField(const Field& f, const std::vector<Channel>& channels, const std::string& format) {
    if (f.incomplete) return;
    const AttributeInfo& attr = attributeInfo(f.attribute);
    const std::string what = "field " + squote(attr.name);
    const bool isId = f.encoding == kIdEncoding;
    const EncodingInfo* enc = isId ? nullptr : findEncoding(f.encoding);
    if (!isId && !enc) return;  // reported by the parser

    if (enc) {
        const std::string why = unsuitable(*enc, attr);
        if (!why.empty()) {
            error(f.encodingPlace, why);
            return;
        }
    }

    // code count
    const int want = expectedCodes(f, enc);
    if (static_cast<int>(f.codes.size()) != want) {
        std::string names;
        Field probe = f;
        probe.codes.resize(static_cast<size_t>(want));
        for (int i = 0; i < want; ++i) {
            const std::string l = codeLabel(probe, static_cast<size_t>(i));
            names += (names.empty() ? "" : ", ") + (l.empty() ? "value" : l);
        }
        const FilePlace at = f.atPlace.line > 0 ? f.atPlace : f.place;
        error(at, "encoding " + squote(f.encoding) + " has " + std::to_string(want) +
                      (want == 1 ? " code" : " codes") + " (" + names + ") for " + squote(attr.name) + " but " +
                      std::to_string(f.codes.size()) + (f.codes.size() == 1 ? " place is" : " places are") +
                      " given in 'at'");
        return;
    }

    // widths
    const int mainCodes = enc && enc->kind != AttributeKind::Scalar ? enc->codeCount : want;
    for (size_t i = 0; i < f.codes.size(); ++i) {
        const CodePlace& c = f.codes[i];
        const std::string label = codeLabel(f, i);
        const std::string code = label.empty() ? "its code" : "code " + label;
        const int bits = c.bits();
        if (isId) {
            if (bits > 32) {
                error(c.place, what + ": an id code holds at most 32 bits, " + squote(c.text) + " has " +
                                   std::to_string(bits));
            } else if (i < f.value.size() && f.value[i] >= std::ldexp(1.0, bits)) {
                error(c.place, what + ": value " + std::to_string(static_cast<long long>(f.value[i])) +
                                   " does not fit in " + bitsText(bits) + " at " + squote(c.text) + " (max " +
                                   std::to_string(static_cast<long long>(std::ldexp(1.0, bits)) - 1) + ")");
            }
            continue;
        }
        if (static_cast<int>(i) >= mainCodes) {  // the extra code (normal_xy_zsign's sign bit)
            if (bits != enc->extraBits)
                error(c.place, "encoding " + squote(enc->name) + " stores " + code + " in exactly " +
                                   bitsText(enc->extraBits) + "; " + squote(c.text) + " has " +
                                   std::to_string(bits));
            continue;
        }
        if (!encodingBitsValid(*enc, bits)) {
            const std::string range = enc->minBits == enc->maxBits
                                          ? bitsText(enc->minBits)
                                          : std::to_string(enc->minBits) + ".." + bitsText(enc->maxBits);
            error(c.place, "encoding " + squote(enc->name) + " takes " + range + " per code; " + code + " of " +
                               squote(attr.name) + " at " + squote(c.text) + " has " + std::to_string(bits));
        } else if (enc->kind != AttributeKind::Scalar && i > 0 && bits != f.codes[0].bits()) {
            error(c.place, "encoding " + squote(enc->name) + " takes one bit count for all its codes; " + code +
                               " at " + squote(c.text) + " has " + std::to_string(bits) + " but code " +
                               codeLabel(f, 0) + " has " + std::to_string(f.codes[0].bits()));
        }
    }

    // every piece inside its channel; float and sRGB channels hold only whole codes of their kind
    for (size_t i = 0; i < f.codes.size(); ++i) {
        const CodePlace& c = f.codes[i];
        for (const BitRange& r : c.pieces) {
            const Channel& ch = channels[static_cast<size_t>(r.channel)];
            const int end = r.first + r.count;
            if (end > ch.bits) {
                error(c.place, "bit range " + squote(bitRangeText(channels, r)) + " overflows channel " +
                                   squote(ch.name) + " of " + format + " (" + bitsText(ch.bits) + ") by " +
                                   bitsText(end - ch.bits));
                continue;
            }
            const bool whole = c.pieces.size() == 1 && r.first == 0 && r.count == ch.bits;
            if (ch.type == ChannelType::Sfloat || ch.type == ChannelType::Ufloat) {
                const std::string need = ch.type == ChannelType::Sfloat ? (ch.bits == 16 ? "float16" : "float32")
                                                                        : (ch.bits == 11 ? "float11" : "float10");
                // float11_11_10 is B10G11R11's three codes as one colour field (r, g: float11; b: float10).
                const bool packedUfloat = (f.encoding == "float11_11_10" || f.encoding == "float11_11_10_hdrp_ao_tag") &&
                                          ch.type == ChannelType::Ufloat &&
                                          (ch.bits == 11) == (i < 2);
                if (!whole || (f.encoding != need && !packedUfloat))
                    error(c.place, "channel " + squote(ch.name) + " of " + format +
                                       " is a float channel: it "
                                       "holds one whole " +
                                       need + " code, not " + squote(f.encoding) + " bits at " + squote(c.text) +
                                       " (use a UNORM or UINT format for bit fields)");
            } else if (ch.type == ChannelType::Srgb) {
                if (!whole || f.encoding != "srgb8")
                    error(c.place, "channel " + squote(ch.name) + " of " + format +
                                       " is an sRGB channel: it "
                                       "holds one whole srgb8 code, not " +
                                       squote(f.encoding) + " bits at " + squote(c.text) +
                                       " (use the _UNORM format)");
            }
        }
    }
}

// Bits of one target (or the stencil): total fits, no two codes share a bit.
void Validator::checkPacking(const std::vector<Field>& fields, const std::vector<Channel>& channels, int totalBits,
                             const std::string& where, const std::string& format, FilePlace place) {
    // Bits counted once: conditional fields of disjoint models may share them (overlaps of
    // other fields are reported below, bit by bit).
    std::vector<std::vector<bool>> taken(channels.size());
    for (size_t c = 0; c < channels.size(); ++c) taken[c].assign(static_cast<size_t>(channels[c].bits), false);
    int used = 0;
    for (const Field& f : fields) {
        if (f.incomplete) continue;
        for (const CodePlace& code : f.codes)
            for (const BitRange& r : code.pieces)
                for (int b = r.first; b < r.first + r.count; ++b) {
                    auto& t = taken[static_cast<size_t>(r.channel)];
                    if (b >= static_cast<int>(t.size())) {
                        ++used;
                    } else if (!t[static_cast<size_t>(b)]) {
                        t[static_cast<size_t>(b)] = true;
                        ++used;
                    }
                }
    }
    if (used > totalBits)
        error(place, "fields of " + where + " need " + bitsText(used) + " but " + format + " holds " +
                         std::to_string(totalBits) + " (" + bitsText(used - totalBits) + " over)");

    // owners[channel][bit] = the fields holding it: one, or several conditional fields of
    // disjoint models (layouts/README.md, "Shading models")
    struct Owner {
        int field = -1;
        const CodePlace* code = nullptr;
    };
    std::vector<std::vector<std::vector<Owner>>> owners(channels.size());
    for (size_t c = 0; c < channels.size(); ++c) owners[c].resize(static_cast<size_t>(channels[c].bits));
    std::map<std::pair<int, int>, bool> reported;
    auto compatible = [&](const Field& a, const Field& b) {
        return &a != &b && a.conditional() && b.conditional() && (a.models & b.models) == 0;
    };
    for (size_t fi = 0; fi < fields.size(); ++fi) {
        const Field& f = fields[fi];
        if (f.incomplete) continue;
        for (const CodePlace& code : f.codes) {
            for (const BitRange& r : code.pieces) {
                auto& bits = owners[static_cast<size_t>(r.channel)];
                int clashFirst = -1, clashLast = -1, other = -1;
                const CodePlace* otherCode = nullptr;
                for (int b = r.first; b < r.first + r.count && b < static_cast<int>(bits.size()); ++b) {
                    auto& list = bits[static_cast<size_t>(b)];
                    for (const Owner& o : list) {
                        if (compatible(f, fields[static_cast<size_t>(o.field)])) continue;
                        if (clashFirst < 0) {
                            clashFirst = b;
                            other = o.field;
                            otherCode = o.code;
                        }
                        if (o.field == other) clashLast = b;
                    }
                    list.push_back({static_cast<int>(fi), &code});
                }
                if (clashFirst < 0) continue;
                if (reported[{other, static_cast<int>(fi)}]) continue;
                reported[{other, static_cast<int>(fi)}] = true;
                const Field& g = fields[static_cast<size_t>(other)];
                const BitRange clash{r.channel, clashFirst, clashLast - clashFirst + 1};
                const std::string self = other == static_cast<int>(fi) ? " (the same field)" : "";
                std::string why;
                if (other != static_cast<int>(fi) && f.conditional() && g.conditional())
                    why = "; both are held under " + shadingModelNames(f.models & g.models) +
                          ": fields may share bits only under disjoint models";
                else if (other != static_cast<int>(fi) && (f.conditional() || g.conditional()))
                    why = std::string("; only fields of different models may share bits, and ") +
                          squote(attributeName(f.conditional() ? g.attribute : f.attribute)) +
                          " is written on every pixel";
                error(code.place, "bits " + bitRangeText(channels, clash) + " of field " +
                                      squote(attributeName(f.attribute)) + " at " + squote(code.text) +
                                      " overlap field " + squote(attributeName(g.attribute)) + " at " +
                                      squote(otherCode ? otherCode->text : "?") + " (" + lineText(g.place) + ")" +
                                      self + why);
            }
        }
    }
}

}  // namespace gbl::layout_validation
