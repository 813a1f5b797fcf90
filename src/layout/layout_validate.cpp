// Semantic checks of a parsed layout: encodings suit their attributes, each field places exactly
// the codes its encoding produces with widths the encoding accepts, bits stay inside their channels
// and targets and never overlap, required attributes are stored, every other shading attribute is
// stored or has a declared fallback whose inputs exist, and the pipeline's own rules hold.
// Runs fully before anything renders; every message names file:line:col.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "layout_coverage.h"
#include "layout_validator.h"

namespace gbl {

namespace layout_validation {

void Validator::run() {
    checkTargets();
    checkStencil();
    checkSelector();
    checkStoredOnce();
    checkReads();
    checkRequired();
    checkFallbacks();
    checkPipeline();
    checkClear();
    checkSpace();
}

void Validator::error(FilePlace place, std::string message) {
    out_.push_back({layout_.sourceFile, place, std::move(message)});
}

void Validator::checkTargets() {
    std::map<std::string, FilePlace> names;
    int count = 0;
    for (const Target& t : layout_.targets) {
        ++count;
        if (count == kMaxColorTargets + 1)
            error(t.place, "more than " + std::to_string(kMaxColorTargets) +
                               " render targets: Vulkan guarantees (and lavapipe has) 8 colour attachments");
        if (!t.name.empty()) {
            auto [it, fresh] = names.emplace(t.name, t.place);
            if (!fresh)
                error(t.place, "target name " + squote(t.name) + " is already used (" + lineText(it->second) + ")");
        }
        if (t.channels.empty()) continue;  // unknown format, reported
        for (const Field& f : t.fields) checkField(f, t.channels, t.format);
        checkPacking(t.fields, t.channels, t.bits(), "target " + squote(t.name), t.format, t.formatPlace);
    }
}

void Validator::checkStencil() {
    const Depth& d = layout_.depth;
    if (d.stencil.empty() || d.stencilBits == 0) return;
    const std::vector<Channel> channels = {{"s", d.stencilBits, 0, ChannelType::Uint}};
    for (const Field& f : d.stencil) checkField(f, channels, "the stencil");
    checkPacking(d.stencil, channels, d.stencilBits, "the stencil", d.format, d.formatPlace);
}

// An encoding that reads another attribute of the pixel (emissive_albedo_ratio reads
// base_color) decodes from that attribute's decoded value: it must be stored in a field that
// comes before this one (an earlier target, or earlier in the same target), as readGBuffer
// and the CPU codec decode fields in layout order.
// A conditional field reads an attribute stored under its models (checkSelector): the fields
// before it must store it under all of them.
void Validator::checkReads() {
    std::map<Attribute, uint32_t> before;  // the models stored before (~0u: unconditionally)
    for (const Target& t : layout_.targets)
        for (const Field& f : t.fields) {
            const EncodingInfo* enc = f.incomplete ? nullptr : findEncoding(f.encoding);
            if (enc && !enc->reads.empty()) {
                const AttributeInfo* r = findAttribute(enc->reads);
                const std::string a = squote(attributeName(f.attribute)), e = squote(enc->name);
                const uint32_t needed = f.conditional() ? f.models : ~0u;
                // stored under too few models anywhere: checkSelector says so
                const bool covered = r && layout_.storesConditionally(r->id) ? f.conditional() &&
                                                                                   storesUnder(layout_, r->id, f.models)
                                                                             : true;
                const auto it = r ? before.find(r->id) : before.end();
                if (r && covered && (it == before.end() || (it->second & needed) != needed)) {
                    const bool later = layout_.stores(r->id);
                    error(f.encodingPlace,
                          "encoding " + e + " of " + a + " reads " + squote(enc->reads) + ", which " +
                              (later ? "is stored after it" : "the layout does not store") + ": store " +
                              enc->reads + " in a field before " + a +
                              " (an earlier target, or earlier in this one), or choose another encoding for " + a);
                }
            }
            before[f.attribute] |= f.conditional() ? f.models : ~0u;
        }
}

void Validator::checkStoredOnce() {
    // An attribute is stored by one unconditional field, or by conditional fields of disjoint
    // models (layouts/README.md, "Shading models").
    std::map<Attribute, std::vector<const Field*>> seen;
    auto visit = [&](const Field& f) {
        auto& list = seen[f.attribute];
        for (const Field* g : list) {
            if (f.conditional() && g->conditional() && (f.models & g->models) == 0) continue;
            if (f.conditional() && g->conditional())
                error(f.modelPlace, "attribute " + squote(attributeName(f.attribute)) + " is already stored under " +
                                        shadingModelNames(f.models & g->models) + " (" + lineText(g->place) +
                                        "); store each attribute once per model");
            else if (f.conditional() || g->conditional())
                error(f.place, "attribute " + squote(attributeName(f.attribute)) + " is already stored (" +
                                   lineText(g->place) + ") by a" + (g->conditional() ? " conditional" : "n unconditional") +
                                   " field; an attribute is stored on every pixel or under some models, not both");
            else
                error(f.place, "attribute " + squote(attributeName(f.attribute)) + " is already stored (" +
                                   lineText(g->place) + "); store each attribute once");
            return;
        }
        list.push_back(&f);
    };
    for (const Target& t : layout_.targets)
        for (const Field& f : t.fields) visit(f);
    for (const Field& f : layout_.depth.stencil) visit(f);
    // What an encoding stores besides its attribute (HDRP's AO tag: occlusion) counts too.
    for (const Target& t : layout_.targets)
        for (const Field& f : t.fields) {
            const EncodingInfo* enc = f.incomplete ? nullptr : findEncoding(f.encoding);
            const AttributeInfo* c = enc && !enc->carries.empty() ? findAttribute(enc->carries) : nullptr;
            if (!c) continue;
            auto& list = seen[c->id];
            if (!list.empty())
                error(f.encodingPlace, "encoding " + squote(enc->name) + " of " + squote(attributeName(f.attribute)) +
                                           " also stores " + squote(enc->carries) + ", which is already stored (" +
                                           lineText(list.front()->place) + "); store each attribute once");
            list.push_back(&f);
        }
}

// The selector and the conditional fields (layouts/README.md, "Shading models: the selector").
void Validator::checkSelector() {
    const Field* sel = nullptr;
    for (const Target& t : layout_.targets)
        for (const Field& f : t.fields) {
            if (f.attribute != Attribute::ShadingModel) continue;
            if (sel) {
                error(f.place, "a second shading-model selector (the first is on " + lineText(sel->place) +
                                   "): a layout has at most one");
                continue;
            }
            sel = &f;
        }
    uint32_t named = 0;
    if (sel && !sel->incomplete) {
        const int bits = sel->codes.empty() ? 0 : sel->codes[0].bits();
        if (bits > kMaxSelectorBits)
            error(sel->codes[0].place, "the selector at " + squote(sel->codes[0].text) + " has " + bitsText(bits) +
                                           "; it takes 1.." + bitsText(kMaxSelectorBits) +
                                           " (ids 0..31: UE's shading model id takes 4, HDRP's feature id 3)");
        std::map<uint32_t, const Field::ModelId*> ids;
        for (const Field::ModelId& m : sel->selector) {
            named |= 1u << unsigned(m.model);
            const char* name = shadingModelInfo(m.model).name;
            if (bits > 0 && bits <= 32 && double(m.id) >= std::ldexp(1.0, bits))
                error(m.place, "id " + std::to_string(m.id) + " of " + squote(name) + " does not fit the selector's " +
                                   bitsText(bits) + " (0.." +
                                   std::to_string(static_cast<long long>(std::ldexp(1.0, bits)) - 1) + ")");
            auto [it, fresh] = ids.emplace(m.id, &m);
            if (!fresh)
                error(m.place, "models " + squote(shadingModelInfo(it->second->model).name) + " and " + squote(name) +
                                   " have the same id " + std::to_string(m.id) +
                                   ": the decoder could not tell their pixels apart");
        }
        if (!(named & 1u))
            error(sel->selectorPlace, "the selector's 'models' has no 'default': name the id of pixels without a "
                                      "layer its other models hold (e.g. default = 1, UE's DefaultLit)");
    }
    for (const Target& t : layout_.targets)
        for (const Field& f : t.fields) {
            if (f.incomplete || !f.conditional()) continue;
            const std::string a = squote(attributeName(f.attribute));
            if (!sel) {
                error(f.modelPlace, "field " + a + " is held under " + shadingModelNames(f.models) +
                                        " but the layout has no selector: add a field { attribute = "
                                        "\"shading_model\", at = ..., models = { default = ..., ... } } that "
                                        "stores each pixel's model, or remove 'model'");
                continue;
            }
            if (!sel->incomplete && (f.models & ~named) != 0)
                error(f.modelPlace, "field " + a + " is held under " + shadingModelNames(f.models & ~named) +
                                        ", which the selector (" + lineText(sel->place) +
                                        ") does not name: add it to the selector's 'models' (known: " +
                                        shadingModelNames(named) + ")");
            if (f.attribute == Attribute::Position || f.attribute == Attribute::Depth)
                error(f.modelPlace, "field " + a + " is geometry, which the lighting rebuilds every pixel from: it "
                                        "is stored on every pixel (remove 'model')");
            // A conditional field may read an attribute of its own pixel that every pixel stores
            // (checked below) and carry a material layer, which decodes as "no layer" on the pixels
            // of other models as the field's own attribute does (HDRP's anisotropic feature:
            // anisotropy_angle_hdrp reads the normal and carries anisotropy_strength); not
            // the neighbours, which may be of another model, nor a non-layer attribute, which would
            // be stored under some models without a fallback of its own.
            const EncodingInfo* enc = findEncoding(f.encoding);
            const AttributeInfo* carried = enc && !enc->carries.empty() ? findAttribute(enc->carries) : nullptr;
            if (enc && (enc->needsNeighbours || (carried && !isLayerAttribute(carried->id))))
                error(f.encodingPlace,
                      "encoding " + squote(enc->name) + " of the conditional field " + a + " reads " +
                          (enc->needsNeighbours ? std::string("the neighbouring pixels, which may be of another model")
                                                : squote(enc->carries) + " with it") +
                          ": a conditional field takes an encoding of its own value only (store it unconditionally, "
                          "or choose another encoding)");
        }
    // An encoding that reads another attribute reads it on every pixel the field is stored on: an
    // unconditional field an attribute stored on every pixel, a conditional one an attribute stored
    // on every pixel of the field's models (UE's bottom normal under ClearCoat reads the coat normal
    // GBufferA holds under ClearCoat); checkReads puts that field before it.
    for (const Target& t : layout_.targets)
        for (const Field& f : t.fields) {
            const EncodingInfo* enc = f.incomplete ? nullptr : findEncoding(f.encoding);
            if (!enc || enc->reads.empty()) continue;
            const AttributeInfo* r = findAttribute(enc->reads);
            if (!r || !layout_.storesConditionally(r->id)) continue;
            if (f.conditional() && storesUnder(layout_, r->id, f.models)) continue;
            const uint32_t missing = f.conditional() ? f.models & ~layout_.conditionalModels(r->id) : 0u;
            error(f.encodingPlace,
                  "encoding " + squote(enc->name) + " of " + squote(attributeName(f.attribute)) + " reads " +
                      squote(enc->reads) + ", which the layout stores under " +
                      shadingModelNames(layout_.conditionalModels(r->id)) + " only" +
                      (f.conditional() ? " (not under " + shadingModelNames(missing) + ", where " +
                                             squote(attributeName(f.attribute)) + " is held): store " + enc->reads +
                                             " under every model of this field"
                                       : ": store " + enc->reads + " on every pixel") +
                      ", or choose another encoding");
        }
}

FilePlace Validator::fallbackTablePlace() const {
    return layout_.fallbackPlace.line > 0 ? layout_.fallbackPlace : FilePlace{1, 1};
}

void Validator::checkRequired() {
    for (Attribute a : {Attribute::Normal, Attribute::Roughness})
        if (!layout_.stores(a))
            error({1, 1}, "the layout stores no " + squote(attributeName(a)) +
                              ": every layout must store normal and roughness (the lighting pass reads them "
                              "from the G-buffer)");
        else if (!storesOnEveryModel(layout_, a))
            error(layout_.findField(a)->modelPlace,
                  squote(attributeName(a)) + " is stored under " +
                      shadingModelNames(layout_.conditionalModels(a)) +
                      " only: normal and roughness are stored on every pixel (remove 'model', or store it "
                      "under the selector's other models too: " +
                      shadingModelNames(layout_.selectorModels() & ~layout_.conditionalModels(a)) + ")");
}

// What each derived fallback reads.
std::vector<Attribute> Validator::inputsOf(FallbackKind k) {
    using A = Attribute;
    switch (k) {
        case FallbackKind::FromMetallic:
            return {A::BaseColor, A::Metallic};
        case FallbackKind::Ue4:
            return {A::BaseColor, A::Metallic, A::Specular};
        case FallbackKind::FromBaseColor:
            return {A::BaseColor, A::Metallic};
        case FallbackKind::FromDiffuseSpecular:
            return {A::DiffuseColor, A::SpecularColor, A::Metallic};
        case FallbackKind::FromSpecularColor:
            return {A::SpecularColor};
        case FallbackKind::FromRoughness:
            return {A::Roughness};
        default:
            return {};
    }
}

void Validator::checkFallbacks() {
    // coverage: each shading attribute stored xor given a fallback
    std::map<Attribute, const Fallback*> fb;
    for (const Fallback& f : layout_.fallbacks) {
        auto [it, fresh] = fb.emplace(f.attribute, &f);
        if (!fresh) error(f.place, "second fallback for " + squote(attributeName(f.attribute)));
        if (const Field* stored = layout_.storesAlways(f.attribute) ? layout_.findField(f.attribute) : nullptr)
            error(f.place, "fallback for " + squote(attributeName(f.attribute)) + " but the layout stores it (" +
                               lineText(stored->place) + "); remove one");
    }
    for (const AttributeInfo& a : listAttributes()) {
        if (a.cls != AttributeClass::Shading || a.id == Attribute::Normal || a.id == Attribute::Roughness) continue;
        if (isLayerAttribute(a.id)) continue;  // unstored: "no layer" (0), as an engine without the layer
        if (layout_.storesConditionally(a.id) && !fb.count(a.id)) {
            error(fallbackTablePlace(), "the layout stores " + squote(a.name) + " under " +
                                            shadingModelNames(layout_.conditionalModels(a.id)) +
                                            " only and declares no fallback for the other pixels: add " +
                                            std::string(a.name) + " = ... to [fallback] (what the decoder yields "
                                            "where the pixel's model does not store it)");
            continue;
        }
        if (!layout_.stores(a.id) && !fb.count(a.id))
            error(fallbackTablePlace(), "the layout does not store " + squote(a.name) +
                                            " and declares no fallback for it: add " + std::string(a.name) +
                                            " = ... to [fallback] (a derivation such as " +
                                            (a.id == Attribute::SpecularColor  ? "\"from_metallic\""
                                             : a.id == Attribute::DiffuseColor ? "\"from_base_color\""
                                             : a.id == Attribute::Emissive     ? "\"forward\""
                                             : a.id == Attribute::Metallic     ? "\"from_specular_color\""
                                             : a.id == Attribute::BaseColor    ? "\"from_diffuse_specular\""
                                             : layout_.pipeline == Pipeline::DeferredLighting ? "\"material_pass\""
                                                                                              : "a constant") +
                                            ", or a constant)");
    }
    // inputs of derived fallbacks exist, without cycles
    for (const Fallback& f : layout_.fallbacks) {
        if (f.incomplete) continue;
        for (Attribute in : inputsOf(f.kind))
            if (!layout_.stores(in) && !fb.count(in))
                error(f.place, "fallback " + squote(fallbackKindName(f.kind)) + " for " +
                                   squote(attributeName(f.attribute)) + " reads " + squote(attributeName(in)) +
                                   ", which the layout neither stores nor derives");
    }
    // derived fallbacks must not feed each other in a circle (metallic from specular_color from
    // metallic): depth-first search over "derives from" edges, one report per back edge. With a
    // selector, per model: an attribute that model stores breaks the circle there (HDRP's
    // fresnel0 under its standard feature, its metallic under anisotropy), and the layout is
    // refused only where some model stores none of the circle.
    const uint32_t named = layout_.selectorModels();
    bool reportedCycle = false;
    for (int model = named ? 0 : -1; model < (named ? kShadingModels : 0) && !reportedCycle; ++model) {
        if (model >= 0 && !((named >> model) & 1u)) continue;
        auto storedHere = [&](Attribute a) {
            return layout_.storesAlways(a) ||
                   (model >= 0 && ((layout_.conditionalModels(a) >> unsigned(model)) & 1u));
        };
        std::map<Attribute, int> state;  // 0 unvisited, 1 on the stack, 2 done
        std::vector<Attribute> stack;
        std::function<void(Attribute)> visit = [&](Attribute a) {
            state[a] = 1;
            stack.push_back(a);
            for (Attribute in : inputsOf(fb.at(a)->kind)) {
                if (storedHere(in) || !fb.count(in)) continue;
                if (state[in] == 1) {
                    std::string chain;
                    auto from = std::find(stack.begin(), stack.end(), in);
                    for (auto it = from; it != stack.end(); ++it) chain += std::string(attributeName(*it)) + " -> ";
                    chain += attributeName(in);
                    error(fb.at(in)->place,
                          "fallbacks form a cycle: " + chain +
                              (model >= 0 ? " on pixels of model " + squote(shadingModelInfo(ShadingModel(model)).name)
                                          : std::string()) +
                              "; store one of them or give one a constant");
                    reportedCycle = true;
                } else if (state[in] == 0) {
                    visit(in);
                }
            }
            stack.pop_back();
            state[a] = 2;
        };
        for (const Fallback& f : layout_.fallbacks)
            if (fb.at(f.attribute) == &f && !storedHere(f.attribute) && state[f.attribute] == 0) visit(f.attribute);
    }
}

// [clear]: declared, listing every shading or geometry attribute stored in a colour target and
// only those (extras hold their declared `value` in every pixel, cleared ones included): what a
// pixel without geometry holds is part of the layout, never a default.
// [space]: the space normals are stored in is declared, never assumed (issue 11 item 4), and a
// stored position's space too; a position space without a stored position is an error.
void Validator::checkSpace() {
    const SpaceDecl& sp = layout_.space;
    if (!sp.declared) {
        error({1, 1}, "the layout declares no [space] table: say which space its normals are stored in "
                      "(normal = \"world\" with up = \"y\" or \"z\", or normal = \"view\"); the G-buffer pass "
                      "transforms into it and the lighting back");
        return;
    }
    if (!sp.normalDeclared)
        error(sp.place, "[space] has no 'normal': declare the space normals are stored in (\"world\" or \"view\")");
    const bool position = layout_.stores(Attribute::Position);
    if (position && !sp.positionDeclared)
        error(sp.place, "the layout stores 'position' but [space] has no 'position': declare \"view\" or \"world\"");
    if (!position && sp.positionDeclared)
        error(sp.positionPlace, "[space] declares a 'position' space but the layout stores no 'position'");
    // A stored window depth rides in the Surface's position slot (wiring_plan.h surfaceSlotName):
    // the lighting rebuilds position from the one or the other.
    if (position)
        for (const Target& t : layout_.targets)
            for (const Field& f : t.fields)
                if (f.attribute == Attribute::Depth)
                    error(f.place, "the layout stores both 'position' and 'depth': the lighting rebuilds the "
                                   "position from one of them; remove one");
}

void Validator::checkClear() {
    if (!layout_.clearDeclared) {
        error({1, 1}, "the layout declares no [clear] table: say what a pixel without geometry holds, one value "
                      "per attribute stored in a target (e.g. normal = [0, 0, 1], roughness = 1.0); the "
                      "renderer clears each target with the layout's own encoding of these values");
        return;
    }
    std::map<Attribute, const ClearValue*> seen;
    for (const ClearValue& c : layout_.clears) {
        seen.emplace(c.attribute, &c);
        if (c.attribute == Attribute::ShadingModel) {
            error(c.place, "the selector takes no clear value: a cleared pixel's model follows from its [clear] "
                           "values by the encoder's rule (no layer: 'default')");
            continue;
        }
        if (attributeInfo(c.attribute).cls == AttributeClass::Extra) {
            error(c.place, "extra " + squote(attributeName(c.attribute)) +
                               " takes no clear value: it holds its declared value in every pixel");
            continue;
        }
        bool inTarget = false;
        for (const Target& t : layout_.targets)
            for (const Field& f : t.fields)
                inTarget = inTarget || f.attribute == c.attribute || carriedBy(f) == c.attribute;
        if (!inTarget)
            error(c.place, "clear value for " + squote(attributeName(c.attribute)) +
                               ", which no target stores (stencil extras are cleared to 0 with the depth)");
    }
    for (const Target& t : layout_.targets)
        for (const Field& f : t.fields) {
            const AttributeClass cls = attributeInfo(f.attribute).cls;
            if (cls != AttributeClass::Extra && cls != AttributeClass::Selector && !seen.count(f.attribute))
                error(layout_.clearPlace, "[clear] has no value for " + squote(attributeName(f.attribute)) +
                                              ", which target " + squote(t.name) + " stores (" +
                                              lineText(f.place) + ")");
            const Attribute carried = carriedBy(f);
            if (carried != f.attribute && !seen.count(carried))
                error(layout_.clearPlace, "[clear] has no value for " + squote(attributeName(carried)) +
                                              ", which the encoding " + squote(f.encoding) + " of " +
                                              squote(attributeName(f.attribute)) + " in target " + squote(t.name) +
                                              " also stores (" + lineText(f.place) + ")");
        }
}

// The attribute a field's encoding stores besides its own (EncodingInfo::carries), else its own.
Attribute Validator::carriedBy(const Field& f) {
    const EncodingInfo* enc = f.incomplete ? nullptr : findEncoding(f.encoding);
    const AttributeInfo* c = enc && !enc->carries.empty() ? findAttribute(enc->carries) : nullptr;
    return c ? c->id : f.attribute;
}

void Validator::checkPipeline() {
    const bool lighting = layout_.pipeline == Pipeline::DeferredLighting;
    for (const Fallback& f : layout_.fallbacks) {
        if (f.kind == FallbackKind::MaterialPass && !lighting)
            error(f.place, "fallback 'material_pass' for " + squote(attributeName(f.attribute)) +
                               " needs pipeline = \"deferred-lighting\" (a deferred-shading layout has no "
                               "material pass)");
        if (f.kind == FallbackKind::Forward && lighting)
            error(f.place, "fallback 'forward' for " + squote(attributeName(f.attribute)) +
                               " is for deferred shading; a deferred-lighting layout adds it in the "
                               "material pass ('material_pass')");
    }
    if (lighting) {
        // The light pre-pass G-buffer holds what lighting needs; material colours come later.
        for (Attribute a : {Attribute::BaseColor, Attribute::DiffuseColor, Attribute::SpecularColor,
                            Attribute::Metallic, Attribute::Specular})
            if (const Field* f = layout_.findField(a))
                error(f->place, "a deferred-lighting layout does not store " + squote(attributeName(a)) +
                                    ": the material pass reads it (declare " + attributeName(a) +
                                    " = \"material_pass\" in [fallback])");
        bool diffuse = false, specular = false;
        for (const LightBuffer& b : layout_.lightBuffers)
            for (LightQuantity q : b.holds) {
                diffuse = diffuse || q == LightQuantity::DiffuseRgb;
                specular = specular || q != LightQuantity::DiffuseRgb;
            }
        if (layout_.lightBuffers.empty())
            error({1, 1},
                  "a deferred-lighting layout declares its light buffers: add [[light_buffer]] tables "
                  "(name, format, holds = diffuse_rgb / specular_rgb / specular_luminance)");
        else if (!diffuse || !specular)
            error(layout_.lightBuffers.front().place,
                  std::string("the light buffers hold no ") + (diffuse ? "specular" : "diffuse") +
                      " light (holds: diffuse_rgb, and specular_rgb or specular_luminance)");
        if (!layout_.materialPass.declared)
            error({1, 1},
                  "a deferred-lighting layout declares how its material pass combines the light buffers: add "
                  "[material_pass] with fresnel = \"none\" or \"schlick_nv\"");
    } else if (!layout_.lightBuffers.empty()) {
        error(layout_.lightBuffers.front().place,
              "light buffers belong to pipeline = \"deferred-lighting\"; a deferred-shading layout lights "
              "from the G-buffer directly");
    }
    if (!lighting && layout_.materialPass.declared)
        error(layout_.materialPass.place,
              "[material_pass] belongs to pipeline = \"deferred-lighting\" (a deferred-shading layout has no "
              "material pass)");
}

}  // namespace layout_validation

// layout_visibility.cpp: [ids] and the visibility buffer's rules.
void validateVisibilityLayout(const Layout& layout, std::vector<LayoutDiagnostic>& out);

// layout_provenance.cpp: citations, statuses, provenance on every entry of a layout with [sources].
void validateProvenance(const Layout& layout, std::vector<LayoutDiagnostic>& out);

void validateLayout(const Layout& layout, std::vector<LayoutDiagnostic>& out) {
    validateProvenance(layout, out);
    validateVisibilityLayout(layout, out);
    if (layout.pipeline == Pipeline::VisibilityBuffer) return;  // no attributes, so none of the checks below
    layout_validation::Validator v(layout, out);
    v.run();
}

}  // namespace gbl
