// The Layout helpers: names of the language's enums, the model's bit counts and lookups, code
// labels, places and diagnostics. (The language's tables: layout_tables.cpp.)
#include "layout.h"

#include <algorithm>
#include <cassert>
#include <charconv>

#include "encoding_registry.h"

namespace gbl {

// ---- names ------------------------------------------------------------------------------------

const char* storedSpaceName(StoredSpace s) {
    switch (s) {
        case StoredSpace::WorldYUp: return "world (Y-up)";
        case StoredSpace::WorldZUp: return "world (Z-up)";
        case StoredSpace::View: return "view";
    }
    return "?";
}

const char* pipelineName(Pipeline p) {
    switch (p) {
        case Pipeline::DeferredShading:
            return "deferred-shading";
        case Pipeline::DeferredLighting:
            return "deferred-lighting";
        case Pipeline::VisibilityBuffer:
            return "visibility-buffer";
    }
    return "?";
}

const char* fallbackKindName(FallbackKind k) {
    switch (k) {
        case FallbackKind::Constant:
            return "constant";
        case FallbackKind::FromMetallic:
            return "from_metallic";
        case FallbackKind::Ue4:
            return "ue4";
        case FallbackKind::FromBaseColor:
            return "from_base_color";
        case FallbackKind::FromDiffuseSpecular:
            return "from_diffuse_specular";
        case FallbackKind::FromSpecularColor:
            return "from_specular_color";
        case FallbackKind::FromRoughness:
            return "from_roughness";
        case FallbackKind::MaterialPass:
            return "material_pass";
        case FallbackKind::Forward:
            return "forward";
    }
    return "?";
}

const char* lightBufferEncodingName(LightBufferEncoding e) {
    switch (e) {
        case LightBufferEncoding::Float16:
            return "float16";
        case LightBufferEncoding::Float111110:
            return "float11_11_10";
        case LightBufferEncoding::Float7e3:
            return "float7e3";
        case LightBufferEncoding::Rgbk:
            return "rgbk";
    }
    return "?";
}

int lightBufferEncodingChannels(LightBufferEncoding e) { return e == LightBufferEncoding::Float16 ? 4 : 3; }

const char* lightQuantityName(LightQuantity q) {
    switch (q) {
        case LightQuantity::DiffuseRgb:
            return "diffuse_rgb";
        case LightQuantity::SpecularRgb:
            return "specular_rgb";
        case LightQuantity::SpecularLuminance:
            return "specular_luminance";
    }
    return "?";
}

// ---- model helpers ----------------------------------------------------------------------------

int CodePlace::bits() const {
    int n = 0;
    for (const BitRange& r : pieces) n += r.count;
    return n;
}

int Field::totalBits() const {
    int n = 0;
    for (const CodePlace& c : codes) n += c.bits();
    return n;
}

int Target::bits() const {
    int n = 0;
    for (const Channel& c : channels) n = std::max(n, c.offset + c.bits);
    return n;
}

int Target::usedBits() const {
    // Bits, counted once: conditional fields of different models may share them.
    std::vector<bool> used(size_t(std::max(bits(), 0)), false);
    int n = 0;
    for (const Field& f : fields)
        for (const CodePlace& c : f.codes)
            for (const BitRange& r : c.pieces) {
                if (size_t(r.channel) >= channels.size()) {
                    n += r.count;
                    continue;
                }
                for (int b = 0; b < r.count; ++b) {
                    const size_t at = size_t(channels[size_t(r.channel)].offset + r.first + b);
                    if (at >= used.size()) {
                        ++n;
                    } else if (!used[at]) {
                        used[at] = true;
                        ++n;
                    }
                }
            }
    return n;
}

std::string Source::text() const {
    std::string s;
    auto add = [&](const std::string& part) {
        if (part.empty()) return;
        if (!s.empty()) s += "; ";
        s += part;
    };
    add(game);
    add(engine);
    add(talk);
    add(code);
    if (year > 0) add(std::to_string(year));
    return s;
}

const Field* Layout::findField(Attribute a) const {
    for (const Target& t : targets)
        for (const Field& f : t.fields)
            if (f.attribute == a) return &f;
    // A field whose encoding also stores `a` (HDRP's AO tag stores occlusion with emissive).
    for (const Target& t : targets)
        for (const Field& f : t.fields)
            if (const EncodingInfo* e = findEncoding(f.encoding); e && !e->carries.empty() && e->carries == attributeName(a))
                return &f;
    for (const Field& f : depth.stencil)
        if (f.attribute == a) return &f;
    return nullptr;
}

bool Layout::storesAlways(Attribute a) const {
    for (const Target& t : targets)
        for (const Field& f : t.fields) {
            if (f.conditional()) continue;
            if (f.attribute == a) return true;
            if (const EncodingInfo* e = findEncoding(f.encoding); e && !e->carries.empty() && e->carries == attributeName(a))
                return true;
        }
    for (const Field& f : depth.stencil)
        if (f.attribute == a) return true;
    return false;
}

const Field* Layout::selector() const {
    for (const Target& t : targets)
        for (const Field& f : t.fields)
            if (f.attribute == Attribute::ShadingModel) return &f;
    return nullptr;
}

uint32_t Layout::selectorIds(uint32_t models) const {
    const Field* s = selector();
    uint32_t set = 0;
    if (!s) return 0;
    for (const Field::ModelId& m : s->selector)
        if ((models >> unsigned(m.model)) & 1u && m.id < 32) set |= 1u << m.id;
    return set;
}

uint32_t Layout::selectorModels() const {
    const Field* s = selector();
    uint32_t models = 0;
    if (s)
        for (const Field::ModelId& m : s->selector) models |= 1u << unsigned(m.model);
    return models;
}

uint32_t Layout::conditionalModels(Attribute a) const {
    uint32_t models = 0;
    for (const Target& t : targets)
        for (const Field& f : t.fields) {
            if (f.attribute == a) models |= f.models;
            // what a conditional field's encoding also stores is held under the same models
            else if (const EncodingInfo* e = findEncoding(f.encoding); e && !e->carries.empty() && e->carries == attributeName(a))
                models |= f.models;
        }
    return models;
}

const Fallback* Layout::findFallback(Attribute a) const {
    for (const Fallback& f : fallbacks)
        if (f.attribute == a) return &f;
    return nullptr;
}

const ClearValue* Layout::findClear(Attribute a) const {
    for (const ClearValue& c : clears)
        if (c.attribute == a) return &c;
    return nullptr;
}

int depthAttachmentBytes(const Layout& layout) {
    return layout.pipeline == Pipeline::VisibilityBuffer && layout.ids.depthWord >= 0 ? 0 : layout.depth.bytes;
}

int bytesPerPixel(const Layout& layout) {
    int bytes = depthAttachmentBytes(layout) + layout.ids.bytes();
    for (const Target& t : layout.targets) bytes += t.bytes();
    return bytes;
}

int lightBufferBytesPerPixel(const Layout& layout) {
    int bytes = 0;
    for (const LightBuffer& b : layout.lightBuffers) bytes += b.bytes;
    return bytes;
}

std::vector<AttributeBits> bitsPerAttribute(const Layout& layout) {
    std::vector<AttributeBits> out;
    for (const AttributeInfo& info : listAttributes()) {
        int bits = 0, widestConditional = 0;
        uint32_t models = 0;
        bool found = false, always = false;
        auto count = [&](const std::vector<Field>& fields) {
            for (const Field& f : fields)
                if (f.attribute == info.id) {
                    found = true;
                    if (f.conditional()) {
                        widestConditional = std::max(widestConditional, f.totalBits());
                        models |= f.models;
                    } else {
                        bits += f.totalBits();
                        always = true;
                    }
                }
        };
        for (const Target& t : layout.targets) count(t.fields);
        count(layout.depth.stencil);
        if (found) out.push_back({info.id, bits + widestConditional, always ? 0u : models});
    }
    return out;
}

namespace {

// Names of an encoding's codes, in order, for whole-value (normal / colour) encodings.
std::vector<std::string> wholeValueCodeNames(const std::string& encoding) {
    if (encoding == "normal_xyz" || encoding == "normal_bestfit") return {"x", "y", "z"};
    if (encoding == "normal_xy_zsign") return {"x", "y", "z_sign"};
    if (encoding == "normal_xy_float16") return {"x", "y"};
    if (encoding == "rgb9e5") return {"r", "g", "b", "e"};
    if (encoding == "gamma22" || encoding == "float11_11_10") return {"r", "g", "b"};
    // Emissive's codes, or where emissive is 0 HDRP's AO tag: (2048, occlusion, 1024).
    if (encoding == "float11_11_10_hdrp_ao_tag") return {"r|2048", "g|AO", "b|1024"};
    // HDRP's anisotropic GBuffer2: the tangent's angle, the signed anisotropy, the storeSin flag.
    if (encoding == "anisotropy_angle_hdrp") return {"angle", "aniso", "sin"};
    if (encoding.rfind("normal_", 0) == 0) return {"u", "v"};
    if (encoding == "srgb8") return {"r", "g", "b"};
    if (encoding == "ycbcr" || encoding == "ycbcr_sqrt") return {"Y", "Cb", "Cr"};
    if (encoding == "ycocg") return {"Y", "Co", "Cg"};
    if (encoding == "ycbcr_checkerboard") return {"Y", "Cb|Cr"};
    if (encoding == "ycocg_checkerboard") return {"Y", "Co|Cg"};
    if (encoding == "luma") return {"Y"};
    if (encoding == "emissive_albedo_ratio") return {"x"};  // log2(1 + L(e) / L(albedo)) / 5
    return {};
}

}  // namespace

std::string codeLabel(const Field& field, size_t code) {
    const EncodingInfo* enc = findEncoding(field.encoding);
    if (enc && enc->kind != AttributeKind::Scalar) {
        std::vector<std::string> names = wholeValueCodeNames(field.encoding);
        if (code < names.size()) return names[code];
        return "code " + std::to_string(code);
    }
    // per-component encodings (and "id"): one code per component
    const AttributeInfo& info = attributeInfo(field.attribute);
    if (info.components == 1) return "";
    static const char* xyz[] = {"x", "y", "z"};
    static const char* rgb[] = {"r", "g", "b"};
    const bool vector = isDirectionAttribute(field.attribute) || field.attribute == Attribute::Position;
    if (info.components == 3 && code < 3) return vector ? xyz[code] : rgb[code];
    return std::to_string(code);
}

std::string bitRangeText(const std::vector<Channel>& channels, const BitRange& range) {
    std::string name = range.channel >= 0 && static_cast<size_t>(range.channel) < channels.size()
                           ? channels[static_cast<size_t>(range.channel)].name
                           : "?";
    const int last = range.first + range.count - 1;
    if (range.count == 1) return name + "[" + std::to_string(range.first) + "]";
    return name + "[" + std::to_string(range.first) + ":" + std::to_string(last) + "]";
}

// ---- places -----------------------------------------------------------------------------------

namespace {
std::string trim(std::string_view s) {
    size_t b = 0, e = s.size();
    while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
    while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t')) --e;
    return std::string(s.substr(b, e - b));
}
std::string sq(std::string_view s) { return "'" + std::string(s) + "'"; }
}  // namespace

std::string parseCodePlace(std::string_view text, const std::vector<Channel>& channels, const std::string& formatName,
                           CodePlace& out) {
    out.text = std::string(text);
    out.pieces.clear();
    std::string list;
    for (const Channel& c : channels) list += (list.empty() ? "" : ", ") + c.name;
    std::string_view rest = text;
    while (true) {
        const size_t plus = rest.find('+');
        const std::string piece = trim(rest.substr(0, plus));
        size_t i = 0;
        while (i < piece.size() && piece[i] >= 'a' && piece[i] <= 'z') ++i;
        const std::string name = piece.substr(0, i);
        if (name.empty())
            return "bad place " + sq(text) + ": expected a channel (" + list +
                   ") optionally followed by [bit] or [first:last]";
        auto ch = std::find_if(channels.begin(), channels.end(), [&](const Channel& c) { return c.name == name; });
        if (ch == channels.end())
            return "unknown channel " + sq(name) + " in " + sq(text) + ": " + formatName + " has " + list;
        BitRange range;
        range.channel = static_cast<int>(ch - channels.begin());
        range.first = 0;
        range.count = ch->bits;
        if (i < piece.size()) {  // "[bit]" or "[first:last]"
            auto number = [&](size_t& pos, int& value) {
                const char* b = piece.data() + pos;
                auto [p, ec] = std::from_chars(b, piece.data() + piece.size(), value);
                if (ec != std::errc() || p == b) return false;
                pos += static_cast<size_t>(p - b);
                return true;
            };
            size_t pos = i + 1;
            int first = 0, last = 0;
            bool ok = piece[i] == '[' && number(pos, first);
            last = first;
            if (ok && pos < piece.size() && piece[pos] == ':') {
                ++pos;
                ok = number(pos, last);
            }
            ok = ok && pos + 1 == piece.size() && piece[pos] == ']';
            if (!ok)
                return "bad bit range " + sq(piece) + " in " + sq(text) +
                       ": write channel[bit] or channel[first:last], e.g. \"a[0:3]\"";
            if (first < 0 || last < first)
                return "bad bit range " + sq(piece) + ": write the lower bit first, e.g. " +
                       sq(name + "[" + std::to_string(last) + ":" + std::to_string(first) + "]");
            range.first = first;
            range.count = last - first + 1;
        }
        out.pieces.push_back(range);
        if (plus == std::string_view::npos) return "";
        rest = rest.substr(plus + 1);
    }
}

// ---- diagnostics ------------------------------------------------------------------------------

std::string LayoutDiagnostic::text() const { return formatPlace(escapeText(file), place.line, place.column) + ": " + message; }

namespace {
std::string joinDiagnostics(const std::vector<LayoutDiagnostic>& list) {
    std::string s;
    for (const LayoutDiagnostic& d : list) {
        if (!s.empty()) s += "\n";
        s += d.text();
    }
    return s;
}
}  // namespace

LayoutError::LayoutError(std::vector<LayoutDiagnostic> list)
    : UserError(joinDiagnostics(list)), diagnostics(std::move(list)) {}

}  // namespace gbl
