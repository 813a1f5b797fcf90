#include "layout_packer.h"

#include <algorithm>
#include <functional>
#include <numeric>
#include <sstream>

#include "layout.h"

namespace gbl::search {

int PlannedField::totalBits() const { return std::accumulate(codeBits.begin(), codeBits.end(), 0); }

namespace {

PlannedField encoded(const char* attribute, const EncodingChoice& e, int bits) {
    PlannedField f{attribute, e.name, std::vector<int>(size_t(e.codes), bits)};
    if (e.extraBits) f.codeBits.push_back(e.extraBits);  // the z sign, after x and y
    return f;
}

PlannedField unorm(const char* attribute, int bits) { return {attribute, "unorm", {bits}}; }

// The real formats a bin may become, smallest first; within one size, the first whose channels
// hold every code unsplit wins (byte channels first: the usual shape of a hand-made layout).
const std::vector<std::vector<const char*>>& formatsBySize() {
    static const std::vector<std::vector<const char*>> v = {
        {"R8_UNORM"},
        {"R8G8_UNORM", "R16_UNORM", "R16_UINT"},
        {"R8G8B8A8_UNORM", "A2B10G10R10_UNORM_PACK32", "R16G16_UNORM", "R32_UINT"},
        {"R16G16B16A16_UNORM", "R32G32_UINT"},
    };
    return v;
}

struct Placement {
    const TargetFormatInfo* format = nullptr;
    // Per field of the bin, per code: the place text.
    std::vector<std::vector<std::string>> places;
};

std::string placeText(const Channel& ch, int first, int count) {
    if (first == 0 && count == ch.bits) return ch.name;
    if (count == 1) return ch.name + "[" + std::to_string(first) + "]";
    return ch.name + "[" + std::to_string(first) + ":" + std::to_string(first + count - 1) + "]";
}

// First-fit decreasing of the bin's codes into the format's channels, no code split.
bool place(const TargetFormatInfo& format, const std::vector<const PlannedField*>& fields, Placement& out) {
    struct Code {
        size_t field, code;
        int bits;
    };
    std::vector<Code> codes;
    for (size_t f = 0; f < fields.size(); ++f)
        for (size_t c = 0; c < fields[f]->codeBits.size(); ++c) codes.push_back({f, c, fields[f]->codeBits[c]});
    std::stable_sort(codes.begin(), codes.end(), [](const Code& a, const Code& b) { return a.bits > b.bits; });
    std::vector<int> used(format.channels.size(), 0);
    out.format = &format;
    out.places.assign(fields.size(), {});
    for (size_t f = 0; f < fields.size(); ++f) out.places[f].resize(fields[f]->codeBits.size());
    for (const Code& code : codes) {
        bool done = false;
        for (size_t ch = 0; ch < format.channels.size() && !done; ++ch) {
            if (used[ch] + code.bits > format.channels[ch].bits) continue;
            out.places[code.field][code.code] = placeText(format.channels[ch], used[ch], code.bits);
            used[ch] += code.bits;
            done = true;
        }
        if (!done) return false;
    }
    return true;
}

bool placeBin(const std::vector<const PlannedField*>& fields, Placement& out) {
    int bits = 0;
    for (const auto* f : fields) bits += f->totalBits();
    for (const auto& size : formatsBySize())
        for (const char* name : size) {
            const TargetFormatInfo* info = findTargetFormat(name);
            if (!info || info->bits < bits) continue;
            if (place(*info, fields, out)) return true;
        }
    return false;
}

// A selector's target: each model's fields placed on their own from bit 0 (they share the bits),
// in the smallest format that holds every model's.
bool placeShared(const std::vector<const PlannedField*>& fields, const std::vector<std::string>& models, Placement& out) {
    int bits = 0;
    for (const std::string& m : models) {
        int mb = 0;
        for (const auto* f : fields)
            if (f->model == m) mb += f->totalBits();
        bits = std::max(bits, mb);
    }
    for (const auto& size : formatsBySize())
        for (const char* name : size) {
            const TargetFormatInfo* info = findTargetFormat(name);
            if (!info || info->bits < bits) continue;
            out.format = info;
            out.places.assign(fields.size(), {});
            bool ok = true;
            for (const std::string& m : models) {
                std::vector<const PlannedField*> mine;
                std::vector<size_t> at;
                for (size_t i = 0; i < fields.size(); ++i)
                    if (fields[i]->model == m) {
                        mine.push_back(fields[i]);
                        at.push_back(i);
                    }
                Placement p;
                if (!place(*info, mine, p)) {
                    ok = false;
                    break;
                }
                for (size_t k = 0; k < at.size(); ++k) out.places[at[k]] = p.places[k];
            }
            if (ok) return true;
        }
    return false;
}

// What a pixel without geometry holds: UE4 clears its G-buffer to zero; a +z normal, full
// roughness, black colours, no metal, UE4's default specular 0.5, no occlusion.
std::string clearValue(const std::string& attribute) {
    if (attribute == "normal") return "[0.0, 0.0, 1.0]";
    if (attribute == "roughness") return "1.0";
    if (attribute == "specular") return "0.5";
    if (attribute == "occlusion") return "1.0";
    if (attribute == "coat_normal" || attribute == "anisotropy_direction") return "[0.0, 0.0, 1.0]";
    return "0.0";
}

}  // namespace

std::vector<PlannedField> plannedFields(const Genome& g) {
    std::vector<PlannedField> out;
    out.push_back(encoded("normal", normalEncodings()[size_t(g.normalEncoding)], g.normalBits));
    out.push_back(encoded("roughness", roughnessEncodings()[size_t(g.roughnessEncoding)], g.roughnessBits));
    const EncodingChoice& colour = colourEncodings()[size_t(g.colourEncoding)];
    const EncodingChoice& specColour = colourEncodings()[size_t(g.specularColourEncoding)];
    if (g.workflow == Workflow::Metallic) {
        out.push_back(encoded("base_color", colour, g.colourBits));
        if (g.metallicBits > 0) out.push_back(unorm("metallic", g.metallicBits));
        if (g.specularMode == SpecularMode::Scalar) out.push_back(unorm("specular", g.specularBits));
        if (g.specularMode == SpecularMode::Colour)
            out.push_back(encoded("specular_color", specColour, g.specularColourBits));
    } else {
        out.push_back(encoded("diffuse_color", colour, g.colourBits));
        out.push_back(encoded("specular_color", specColour, g.specularColourBits));
    }
    if (g.occlusionBits > 0) out.push_back(unorm("occlusion", g.occlusionBits));
    // The material layers (Genome::coatBits ...): what each stores, and under which model with a selector.
    const bool selector = g.layerSelector && (g.coatBits || g.sheenBits || g.anisotropyBits);
    auto layer = [&](PlannedField f, const char* model) {
        if (selector) f.model = model;
        out.push_back(std::move(f));
    };
    if (g.coatBits) {
        layer(unorm("coat", g.coatBits), "clear_coat");
        layer(unorm("coat_roughness", g.coatBits), "clear_coat");
        if (g.coatNormalBits) layer({"coat_normal", "normal_octahedral", {g.coatNormalBits, g.coatNormalBits}}, "clear_coat");
    }
    if (g.sheenBits) {
        layer({"sheen_color", "unorm", {g.sheenBits, g.sheenBits, g.sheenBits}}, "cloth");
        layer(unorm("sheen_roughness", g.sheenBits), "cloth");
    }
    if (g.anisotropyBits) {
        layer(unorm("anisotropy_strength", g.anisotropyBits), "anisotropic");
        layer({"anisotropy_direction", "normal_octahedral", {g.anisotropyBits, g.anisotropyBits}}, "anisotropic");
    }
    if (selector) out.push_back({"shading_model", "id", {2}, ""});
    return out;
}

int smallestPackedBytes(const std::function<void(Genome&)>& adjust) {
    int best = 0;
    Genome g;
    g.workflow = Workflow::Metallic;
    g.metallicBits = 0;
    g.specularMode = SpecularMode::FromMetallic;
    g.occlusionBits = 0;
    for (size_t n = 0; n < normalEncodings().size(); ++n)
        for (size_t r = 0; r < roughnessEncodings().size(); ++r)
            for (size_t c = 0; c < colourEncodings().size(); ++c)
                for (size_t d = 0; d < depthFormats().size(); ++d) {
                    g.normalEncoding = int(n);
                    g.normalBits = normalEncodings()[n].minBits;
                    g.roughnessEncoding = int(r);
                    g.roughnessBits = roughnessEncodings()[r].minBits;
                    g.colourEncoding = int(c);
                    g.colourBits = colourEncodings()[c].minBits;
                    g.depthFormat = int(d);
                    Genome adjusted = g;
                    if (adjust) adjust(adjusted);
                    const int bytes = packGenome(adjusted, 0).bytesPerPixel;  // 0 when unpackable
                    if (bytes > 0 && (best == 0 || bytes < best)) best = bytes;
                }
    return best;
}

int smallestPackedBytes() {
    static const int smallest = smallestPackedBytes(nullptr);
    return smallest;
}

PackResult packGenome(const Genome& g, int budgetBytes) {
    PackResult r;
    const std::vector<PlannedField> fields = plannedFields(g);
    // Conditional fields (a selector's models) go to a target of their own, below; the rest here.
    std::vector<size_t> order;
    for (size_t i = 0; i < fields.size(); ++i)
        if (fields[i].model.empty()) order.push_back(i);
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return fields[a].totalBits() > fields[b].totalBits(); });
    struct Bin {
        int capacity = 32, used = 0;
        std::vector<size_t> fields;
    };
    std::vector<Bin> bins;
    for (size_t i : order) {
        const int bits = fields[i].totalBits();
        if (bits > 64) {
            r.why = fields[i].attribute + " needs " + std::to_string(bits) + " bits, more than any one target holds";
            return r;
        }
        bool placed = false;
        for (Bin& b : bins)
            if (b.used + bits <= b.capacity) {
                b.used += bits;
                b.fields.push_back(i);
                placed = true;
                break;
            }
        if (!placed) bins.push_back({bits > 32 ? 64 : 32, bits, {i}});
    }
    // The selector's models' fields: one target whose every model's fields are placed from bit 0,
    // in the smallest real format that holds each model's.
    std::vector<std::string> models;
    for (const PlannedField& f : fields)
        if (!f.model.empty() && std::find(models.begin(), models.end(), f.model) == models.end()) models.push_back(f.model);
    const bool shared = !models.empty();
    if (shared) {
        Bin b;
        for (size_t i = 0; i < fields.size(); ++i)
            if (!fields[i].model.empty()) b.fields.push_back(i);
        bins.push_back(b);
    }
    if (bins.size() > 8) {
        r.why = "needs " + std::to_string(bins.size()) + " targets (at most 8)";
        return r;
    }
    const DepthChoice& depth = depthFormats()[size_t(g.depthFormat)];
    std::vector<Placement> placements(bins.size());
    int bytes = depth.bytes;
    for (size_t b = 0; b < bins.size(); ++b) {
        std::vector<const PlannedField*> binFields;
        for (size_t i : bins[b].fields) binFields.push_back(&fields[i]);
        const bool sharedBin = shared && b + 1 == bins.size();
        if (sharedBin ? !placeShared(binFields, models, placements[b]) : !placeBin(binFields, placements[b])) {
            r.why = "the codes of target " + std::to_string(b) + " fit no real format unsplit";
            return r;
        }
        bytes += placements[b].format->bits / 8;
    }
    r.bytesPerPixel = bytes;
    if (bytes > budgetBytes) {
        r.why = "needs " + std::to_string(bytes) + " bytes per pixel, over the budget of " + std::to_string(budgetBytes);
        return r;
    }

    std::ostringstream t;
    t << "title = \"Found by gbufferlab search: " << describeGenome(g) << "\"\n";
    t << "pipeline = \"deferred-shading\"\n";
    t << "source = { engine = \"gbufferlab search\", code = \"src/search/layout_packer.cpp\", year = 2026 }\n\n";
    t << "[depth]\nformat = \"" << depth.format << "\"\nreversed_z = " << (depth.reversedZ ? "true" : "false") << "\n\n";
    t << "[space]\nnormal = \"world\"\nup = \"" << (g.normalSpace ? "z" : "y") << "\"\n";
    for (size_t b = 0; b < bins.size(); ++b) {
        t << "\n[[target]]\nname = \"RT" << b << "\"\nformat = \"" << placements[b].format->name << "\"\nfield = [\n";
        for (size_t k = 0; k < bins[b].fields.size(); ++k) {
            const PlannedField& f = fields[bins[b].fields[k]];
            const auto& places = placements[b].places[k];
            t << "  { attribute = \"" << f.attribute << "\", encoding = \"" << f.encoding << "\", at = ";
            if (places.size() == 1) {
                t << "\"" << places[0] << "\"";
            } else {
                t << "[";
                for (size_t p = 0; p < places.size(); ++p) t << (p ? ", " : "") << "\"" << places[p] << "\"";
                t << "]";
            }
            if (f.attribute == "shading_model") t << ", models = { default = 0, clear_coat = 1, cloth = 2, anisotropic = 3 }";
            if (!f.model.empty()) t << ", model = \"" << f.model << "\"";
            t << " },\n";
        }
        t << "]\n";
    }
    auto stores = [&](const std::string& a) {
        return std::any_of(fields.begin(), fields.end(), [&](const PlannedField& f) { return f.attribute == a; });
    };
    t << "\n[fallback]\n";
    if (g.workflow == Workflow::Metallic) {
        t << "diffuse_color = \"from_base_color\"\n";
        if (!stores("specular_color"))
            t << "specular_color = \"" << (g.specularMode == SpecularMode::Scalar ? "ue4" : "from_metallic") << "\"\n";
    } else {
        t << "base_color = \"from_diffuse_specular\"\nmetallic = \"from_specular_color\"\n";
    }
    if (!stores("metallic") && g.workflow == Workflow::Metallic) t << "metallic = 0.0\n";
    if (!stores("specular")) t << "specular = 0.5\n";
    if (!stores("occlusion")) t << "occlusion = 1.0\n";
    t << "emissive = \"forward\"\n";
    t << "\n[clear]\n";
    for (const PlannedField& f : fields)
        if (f.attribute != "shading_model") t << f.attribute << " = " << clearValue(f.attribute) << "\n";
    r.body = t.str();
    r.ok = true;
    return r;
}

std::string layoutText(const std::string& name, const std::string& comment, const std::string& body) {
    std::string out;
    std::istringstream lines(comment);
    for (std::string line; std::getline(lines, line);) out += line.empty() ? "#\n" : "# " + line + "\n";
    out += "name = \"" + name + "\"\n" + body;
    return out;
}

}  // namespace gbl::search
