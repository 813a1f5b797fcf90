// The [fallback] table (what a layout derives instead of storing) and the [[light_buffer]] tables of
// deferred lighting. Part of the layout parser (layout_parser_detail.h).
#include <algorithm>
#include <cmath>

#include "encoding_registry.h"
#include "layout_parser_detail.h"

namespace gbl::layout_parser {

namespace {

struct FallbackKeyword {
    const char* name;
    FallbackKind kind;
};
constexpr FallbackKeyword kFallbackKeywords[] = {
    {"from_metallic", FallbackKind::FromMetallic},
    {"ue4", FallbackKind::Ue4},
    {"from_base_color", FallbackKind::FromBaseColor},
    {"from_diffuse_specular", FallbackKind::FromDiffuseSpecular},
    {"from_specular_color", FallbackKind::FromSpecularColor},
    {"from_roughness", FallbackKind::FromRoughness},
    {"material_pass", FallbackKind::MaterialPass},
    {"forward", FallbackKind::Forward},
};

// Which derived fallbacks each shading attribute accepts (all accept a constant except normal and
// roughness, which every layout must store).
std::vector<FallbackKind> allowedFallbacks(Attribute a) {
    using F = FallbackKind;
    switch (a) {
        case Attribute::SpecularColor:
            return {F::FromMetallic, F::Ue4, F::MaterialPass};
        case Attribute::DiffuseColor:
            return {F::FromBaseColor, F::MaterialPass};
        case Attribute::BaseColor:
            return {F::FromDiffuseSpecular, F::MaterialPass};
        case Attribute::Metallic:
            return {F::FromSpecularColor, F::MaterialPass};
        case Attribute::Specular:
            return {F::MaterialPass};
        case Attribute::Occlusion:
            return {F::MaterialPass};
        case Attribute::Emissive:
            return {F::Forward, F::MaterialPass};
        case Attribute::SheenRoughness:  // UE's Cloth: the fuzz lobe takes the base roughness
            return {F::FromRoughness};
        default:
            return {};
    }
}

}  // namespace

void Parser::parseFallbacks(const toml::table& root, Layout& layout) {
    const toml::node* n = root.get("fallback");
    layout.fallbackPlace = {1, 1};
    if (!n) return;
    layout.fallbackPlace = placeOf(*n);
    const toml::table* t = n->as_table();
    if (!t) {
        error(placeOf(*n), "'fallback' must be a table ([fallback]), not " + std::string(typeName(*n)));
        return;
    }
    for (auto&& [key, entry] : *t) {
        const FilePlace keyPlace = placeOf(key.source());
        const AttributeInfo* attr = findAttribute(key.str());
        if (!attr) {
            error(keyPlace,
                  "unknown attribute " + squote(key.str()) + " in [fallback] (known: " + knownAttributeNames() + ")");
            continue;
        }
        if (attr->cls != AttributeClass::Shading) {
            error(keyPlace, squote(attr->name) + " takes no fallback: " +
                                (attr->cls == AttributeClass::Extra ? "extras are stored with a declared value"
                                                                    : "unstored, position comes from depth"));
            continue;
        }
        if (attr->id == Attribute::Normal || attr->id == Attribute::Roughness) {
            error(keyPlace, squote(attr->name) + " cannot fall back: every layout must store normal and roughness");
            continue;
        }
        Fallback fb;
        fb.attribute = attr->id;
        // `occlusion = 1.0`, or with its provenance `occlusion = { value = 1.0, from = "...", status = "..." }`
        const toml::node* valueNode = entryValue(entry, fb.provenance, "fallback " + squote(attr->name));
        if (!valueNode) {
            fb.place = placeOf(entry);
            fb.incomplete = true;
            layout.fallbacks.push_back(std::move(fb));
            continue;
        }
        const toml::node& value = *valueNode;
        fb.place = placeOf(value);
        const std::vector<FallbackKind> allowed = allowedFallbacks(attr->id);
        auto allowedList = [&] {
            std::string list;
            for (FallbackKind k : allowed) list += std::string(list.empty() ? "" : ", ") + fallbackKindName(k);
            return list + (list.empty() ? "" : ", or ") + "a constant";
        };
        // A bad entry is still recorded (incomplete), so that the attribute does not also read as
        // "no fallback declared".
        fb.incomplete = true;
        if (value.is_string()) {
            const std::string word = value.as_string()->get();
            auto kw = std::find_if(std::begin(kFallbackKeywords), std::end(kFallbackKeywords),
                                   [&](const FallbackKeyword& k) { return word == k.name; });
            if (kw == std::end(kFallbackKeywords) ||
                std::find(allowed.begin(), allowed.end(), kw->kind) == allowed.end()) {
                error(fb.place, "unknown fallback " + squote(word) + " for " + squote(attr->name) +
                                    " (allowed: " + allowedList() + ")");
            } else {
                fb.kind = kw->kind;
                fb.incomplete = false;
            }
        } else if (auto values = getNumbers(value, "fallback for " + squote(attr->name))) {
            if (values->size() == 1 && attr->components > 1) values->assign(attr->components, values->front());
            bool ok = true;
            if (static_cast<int>(values->size()) != attr->components) {
                error(fb.place, "fallback for " + squote(attr->name) + " has " + std::to_string(values->size()) +
                                    " components, " + squote(attr->name) + " has " + std::to_string(attr->components));
                ok = false;
            }
            for (double x : *values) {
                const bool inRange = attr->domain == ValueDomain::NonNegative ? x >= 0 : (x >= 0 && x <= 1);
                if (ok && !inRange) {
                    error(fb.place, "fallback for " + squote(attr->name) + ": " + std::to_string(x) + " is outside " +
                                        (attr->domain == ValueDomain::NonNegative ? "[0, inf)" : "[0,1]"));
                    ok = false;
                }
            }
            fb.kind = FallbackKind::Constant;
            fb.value = *values;
            fb.incomplete = !ok;
        }
        layout.fallbacks.push_back(std::move(fb));
    }
    // file order (toml++ iterates keys alphabetically)
    std::stable_sort(layout.fallbacks.begin(), layout.fallbacks.end(), [](const Fallback& a, const Fallback& b) {
        return a.place.line != b.place.line ? a.place.line < b.place.line : a.place.column < b.place.column;
    });
}

// [clear]: attribute = value (a number, or one per component). Which attributes must be listed is
// checked by validation (every attribute stored in a colour target).
void Parser::parseClear(const toml::table& root, Layout& layout) {
    const toml::node* n = root.get("clear");
    layout.clearPlace = {1, 1};
    if (!n) return;
    layout.clearPlace = placeOf(*n);
    layout.clearDeclared = true;
    const toml::table* t = n->as_table();
    if (!t) {
        error(placeOf(*n), "'clear' must be a table ([clear]), not " + std::string(typeName(*n)));
        return;
    }
    for (auto&& [key, entry] : *t) {
        const FilePlace keyPlace = placeOf(key.source());
        const AttributeInfo* attr = findAttribute(key.str());
        if (!attr) {
            error(keyPlace, "unknown attribute " + squote(key.str()) + " in [clear] (known: " + knownAttributeNames() + ")");
            continue;
        }
        // `roughness = 1.0`, or with its provenance `roughness = { value = 1.0, from = "...", status = "..." }`
        Provenance provenance;
        const toml::node* valueNode = entryValue(entry, provenance, "clear value of " + squote(attr->name));
        if (!valueNode) continue;
        const toml::node& value = *valueNode;
        auto values = getNumbers(value, "clear value of " + squote(attr->name));
        if (!values) continue;
        if (values->size() == 1 && attr->components > 1) values->assign(size_t(attr->components), values->front());
        if (static_cast<int>(values->size()) != attr->components) {
            error(placeOf(value), "clear value of " + squote(attr->name) + " has " + std::to_string(values->size()) +
                                      " components, " + squote(attr->name) + " has " + std::to_string(attr->components));
            continue;
        }
        bool ok = true;
        for (double x : *values) {
            const bool inRange = attr->domain == ValueDomain::Unit          ? x >= 0 && x <= 1
                                 : attr->domain == ValueDomain::Signed      ? x >= -1 && x <= 1
                                 : attr->domain == ValueDomain::NonNegative ? x >= 0
                                 : attr->domain == ValueDomain::Id          ? x >= 0 && x == std::floor(x)
                                                                            : true;
            if (ok && !inRange) {
                error(placeOf(value), "clear value of " + squote(attr->name) + ": " + formatNumber(x) +
                                          " is outside what it can hold");
                ok = false;
            }
        }
        (void)ok;  // recorded even when out of range: one error, not also "no value for ..."
        ClearValue c;
        c.attribute = attr->id;
        c.value = *values;
        c.place = placeOf(value);
        c.provenance = std::move(provenance);
        layout.clears.push_back(std::move(c));
    }
    std::stable_sort(layout.clears.begin(), layout.clears.end(), [](const ClearValue& a, const ClearValue& b) {
        return a.place.line != b.place.line ? a.place.line < b.place.line : a.place.column < b.place.column;
    });
}

namespace {

// Whether `info` is a format the light-buffer encoding `e` fits: every channel the encoding writes
// exists with the bits it needs. Returns "" when it fits, else the formats it needs.
std::string lightBufferFormatNeed(LightBufferEncoding e, const TargetFormatInfo& info) {
    auto channel = [&](const char* name) -> const Channel* {
        for (const Channel& c : info.channels)
            if (c.name == name) return &c;
        return nullptr;
    };
    auto has = [&](const char* name, int bits, std::initializer_list<ChannelType> types) {
        const Channel* c = channel(name);
        if (!c || c->bits != bits) return false;
        for (ChannelType t : types)
            if (c->type == t) return true;
        return false;
    };
    const bool rgba = info.channels.size() == 4;
    switch (e) {
        case LightBufferEncoding::Float16:
            if (rgba && has("r", 16, {ChannelType::Sfloat}) && has("g", 16, {ChannelType::Sfloat}) &&
                has("b", 16, {ChannelType::Sfloat}) && has("a", 16, {ChannelType::Sfloat}))
                return "";
            return "four 16-bit float channels (R16G16B16A16_SFLOAT)";
        case LightBufferEncoding::Float111110:
            if (info.channels.size() == 3 && has("r", 11, {ChannelType::Ufloat}) && has("g", 11, {ChannelType::Ufloat}) &&
                has("b", 10, {ChannelType::Ufloat}))
                return "";
            return "unsigned 11:11:10-bit float channels (B10G11R11_UFLOAT_PACK32)";
        case LightBufferEncoding::Float7e3: {
            const std::initializer_list<ChannelType> t = {ChannelType::Unorm, ChannelType::Uint};
            if (rgba && has("r", 10, t) && has("g", 10, t) && has("b", 10, t) && has("a", 2, t)) return "";
            return "a 32-bit 10:10:10:2 format (A2B10G10R10_UNORM_PACK32, the Xbox 360's A2B10G10R10F container)";
        }
        case LightBufferEncoding::Rgbk: {
            const std::initializer_list<ChannelType> t = {ChannelType::Unorm};
            if (rgba && has("r", 8, t) && has("g", 8, t) && has("b", 8, t) && has("a", 8, t)) return "";
            return "four linear 8-bit UNORM channels (R8G8B8A8_UNORM, A8B8G8R8_UNORM_PACK32, B8G8R8A8_UNORM)";
        }
    }
    return "?";
}

}  // namespace

void Parser::parseMaterialPass(const toml::table& root, Layout& layout) {
    const toml::node* n = root.get("material_pass");
    if (!n) return;
    const toml::table* t = n->as_table();
    if (!t) {
        error(placeOf(*n), "'material_pass' must be a table ([material_pass]), not " + std::string(typeName(*n)));
        return;
    }
    layout.materialPass.place = placeOf(*n);
    layout.materialPass.declared = true;
    checkKeys(*t, {"fresnel", "from", "status", "differs"}, "[material_pass]");
    readProvenance(*t, layout.materialPass.provenance, layout.materialPass.place);
    if (auto f = getString(*t, "fresnel", true, layout.materialPass.place, "[material_pass]")) {
        if (*f == "none")
            layout.materialPass.fresnel = MaterialFresnel::None;
        else if (*f == "schlick_nv")
            layout.materialPass.fresnel = MaterialFresnel::SchlickNv;
        else
            error(placeOf(*t->get("fresnel")), "unknown fresnel " + squote(*f) + " (known: none, schlick_nv)");
    }
}

void Parser::parseLightBuffers(const toml::table& root, Layout& layout) {
    const toml::node* n = root.get("light_buffer");
    if (!n) return;
    const toml::array* a = n->as_array();
    if (!a) {
        error(placeOf(*n),
              "'light_buffer' must be an array of tables ([[light_buffer]]), not " + std::string(typeName(*n)));
        return;
    }
    for (const toml::node& node : *a) {
        const toml::table* t = node.as_table();
        if (!t) {
            error(placeOf(node), "each [[light_buffer]] must be a table");
            continue;
        }
        LightBuffer lb;
        lb.place = placeOf(node);
        checkKeys(*t, {"name", "format", "encoding", "range", "holds", "from", "status", "differs"}, "[[light_buffer]]");
        readProvenance(*t, lb.provenance, lb.place);
        lb.name = getString(*t, "name", true, lb.place, "[[light_buffer]]").value_or("");
        const TargetFormatInfo* info = nullptr;
        if (auto format = getString(*t, "format", true, lb.place, "[[light_buffer]]")) {
            info = findTargetFormat(*format);
            if (!info)
                error(placeOf(*t->get("format")),
                      "unknown format " + squote(*format) + " (known: " + knownTargetFormatNames() + ")");
            else {
                lb.format = info->name;
                lb.bytes = info->bits / 8;
            }
        }
        bool encodingKnown = false;
        if (auto encoding = getString(*t, "encoding", true, lb.place, "[[light_buffer]]")) {
            lb.encodingPlace = placeOf(*t->get("encoding"));
            encodingKnown = true;
            if (*encoding == "float16")
                lb.encoding = LightBufferEncoding::Float16;
            else if (*encoding == "float11_11_10")
                lb.encoding = LightBufferEncoding::Float111110;
            else if (*encoding == "float7e3")
                lb.encoding = LightBufferEncoding::Float7e3;
            else if (*encoding == "rgbk")
                lb.encoding = LightBufferEncoding::Rgbk;
            else {
                encodingKnown = false;
                error(lb.encodingPlace, "unknown light-buffer encoding " + squote(*encoding) +
                                            " (known: float16, float11_11_10, float7e3, rgbk)");
            }
            if (encodingKnown && info) {
                const std::string need = lightBufferFormatNeed(lb.encoding, *info);
                if (!need.empty())
                    error(lb.encodingPlace, "light buffer " + squote(lb.name) + ": encoding " + squote(*encoding) +
                                                " does not fit " + info->name + ": it needs " + need);
            }
        }
        if (const toml::node* range = t->get("range")) {
            if (encodingKnown && lb.encoding != LightBufferEncoding::Rgbk) {
                error(placeOf(*range), "'range' is for encoding = \"rgbk\" (the multiplier's range); " +
                                           std::string(lightBufferEncodingName(lb.encoding)) + " has a fixed range");
            } else if (auto x = getNumber(*range, "'range'")) {
                if (*x < 1.0 || *x > 65025.0)
                    error(placeOf(*range), "'range' " + formatNumber(*x) + " must lie in [1, 65025]");
                else
                    lb.range = *x;
            }
        } else if (encodingKnown && lb.encoding == LightBufferEncoding::Rgbk) {
            error(lb.encodingPlace, "light buffer " + squote(lb.name) +
                                        ": encoding 'rgbk' needs 'range', the largest value it holds (e.g. range = 32)");
        }
        const toml::node* holds = t->get("holds");
        if (!holds) {
            error(lb.place, "[[light_buffer]] has no 'holds' (diffuse_rgb, specular_rgb, specular_luminance)");
        } else {
            std::vector<const toml::node*> items;
            if (const toml::array* ha = holds->as_array())
                for (const toml::node& h : *ha) items.push_back(&h);
            else
                items.push_back(holds);
            int channelsNeeded = 0;
            for (const toml::node* h : items) {
                const std::string word = h->is_string() ? h->as_string()->get() : "";
                if (word == "diffuse_rgb") {
                    lb.holds.push_back(LightQuantity::DiffuseRgb);
                    channelsNeeded += 3;
                } else if (word == "specular_rgb") {
                    lb.holds.push_back(LightQuantity::SpecularRgb);
                    channelsNeeded += 3;
                } else if (word == "specular_luminance") {
                    lb.holds.push_back(LightQuantity::SpecularLuminance);
                    channelsNeeded += 1;
                } else {
                    error(placeOf(*h), "unknown light quantity " + squote(word) +
                                           " (known: diffuse_rgb, specular_rgb, specular_luminance)");
                }
            }
            if (info && channelsNeeded > static_cast<int>(info->channels.size()))
                error(placeOf(*holds), "light buffer " + squote(lb.name) + " holds " + std::to_string(channelsNeeded) +
                                           " channels but " + info->name + " has " +
                                           std::to_string(info->channels.size()));
            else if (encodingKnown && channelsNeeded > lightBufferEncodingChannels(lb.encoding))
                error(placeOf(*holds), "light buffer " + squote(lb.name) + " holds " + std::to_string(channelsNeeded) +
                                           " channels but encoding " + squote(lightBufferEncodingName(lb.encoding)) +
                                           " stores " + std::to_string(lightBufferEncodingChannels(lb.encoding)) +
                                           " (float7e3's 2-bit alpha and rgbk's multiplier hold no light)");
        }
        layout.lightBuffers.push_back(std::move(lb));
    }
}

}  // namespace gbl::layout_parser
