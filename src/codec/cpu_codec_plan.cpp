#include "cpu_codec_plan.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "cpu_codec_kernels.h"
#include "encoding_registry.h"
#include "wiring_codegen.h"

namespace gbl::codec {

namespace {

constexpr int kFloat = int(sizeof(float));

Codec resolveCodec(const std::string& e) {
    static const std::pair<const char*, Codec> names[] = {
        {kIdEncoding, Codec::Id},
        {"unorm", Codec::Unorm},
        {"snorm", Codec::Snorm},
        {"float16", Codec::Float16},
        {"float11", Codec::Float11},
        {"float10", Codec::Float10},
        {"float32", Codec::Float32},
        {"depth24", Codec::Depth24},
        {"gloss", Codec::Gloss},
        {"smoothness_cry", Codec::SmoothnessCry},
        {"cry_gloss_power", Codec::CryGlossPower},
        {"kz2_log_power", Codec::Kz2LogPower},
        {"reflectance", Codec::Reflectance},
        {"reflectance_bevy_webgl2", Codec::ReflectanceBevyWebgl2},
        {"unorm_round_even", Codec::UnormRoundEven},
        {"coat_roughness_bevy", Codec::CoatRoughnessBevy},
        {"unorm_signed", Codec::UnormSigned},
        {"unorm_sqrt", Codec::UnormSqrt},
        {"srgb8", Codec::Srgb8},
        {"luma", Codec::Luma},
        {"ycbcr", Codec::YCbCr},
        {"ycbcr_sqrt", Codec::YCbCrSqrt},
        {"ycocg", Codec::YCoCg},
        {"ycbcr_checkerboard", Codec::YCbCrCheckerboard},
        {"ycocg_checkerboard", Codec::YCoCgCheckerboard},
        {"normal_xyz", Codec::NormalXyz},
        {"normal_bestfit", Codec::NormalBestFit},
        {"normal_xy_zsign", Codec::NormalXyZSign},
        {"normal_spheremap", Codec::NormalSpheremap},
        {"normal_stereographic", Codec::NormalStereographic},
        {"normal_octahedral", Codec::NormalOctahedral},
        {"normal_octahedral_precise", Codec::NormalOctahedralPrecise},
        {"gamma22", Codec::Gamma22},
        {"rgb9e5", Codec::Rgb9e5},
        {"float11_11_10", Codec::Float111110},
        {"float11_11_10_hdrp_ao_tag", Codec::Float111110HdrpAoTag},
        {"normal_octahedral_bevy", Codec::NormalOctahedralBevy},
        {"normal_octahedral_unity", Codec::NormalOctahedralUnity},
        {"normal_octahedral_hdrp", Codec::NormalOctahedralHdrp},
        {"srgb8_fast_hdrp", Codec::Srgb8FastHdrp},
        {"normal_xy_float16", Codec::NormalXyFloat16},
        {"emissive_albedo_ratio", Codec::EmissiveAlbedoRatio},
        {"normal_octahedral_dithered", Codec::NormalOctahedralDithered},
        {"anisotropy_angle_hdrp", Codec::AnisotropyTangentAngleHdrp},
        {"normal_octahedral_delta_ue", Codec::NormalOctahedralDeltaUe},
    };
    for (const auto& [name, codec] : names)
        if (e == name) return codec;
    throw std::logic_error("cpu codec: no encoder for " + e);
}

// Codes the encoder produces (0: one per component, any number).
size_t codeCount(Codec c) {
    switch (c) {
        case Codec::Srgb8:
        case Codec::YCbCr:
        case Codec::YCbCrSqrt:
        case Codec::YCoCg:
        case Codec::NormalXyz:
        case Codec::NormalBestFit:
        case Codec::NormalXyZSign:
        case Codec::Gamma22:
        case Codec::Srgb8FastHdrp:
        case Codec::Float111110HdrpAoTag:
        case Codec::AnisotropyTangentAngleHdrp:
        case Codec::Float111110: return 3;
        case Codec::Rgb9e5: return 4;
        case Codec::Luma:
        case Codec::EmissiveAlbedoRatio: return 1;
        case Codec::YCbCrCheckerboard:
        case Codec::YCoCgCheckerboard:
        case Codec::NormalSpheremap:
        case Codec::NormalStereographic:
        case Codec::NormalOctahedral:
        case Codec::NormalOctahedralPrecise:
        case Codec::NormalOctahedralBevy:
        case Codec::NormalOctahedralUnity:
        case Codec::NormalOctahedralHdrp:
        case Codec::NormalXyFloat16:
        case Codec::NormalOctahedralDeltaUe:
        case Codec::NormalOctahedralDithered: return 2;
        default: return 0;
    }
}

CodePlan planCode(const Target& t, const CodePlace& cp, int words) {
    CodePlan code;
    code.bits = uint32_t(cp.bits());
    int codeShift = 0;
    for (const BitRange& r : cp.pieces) {
        const int at = t.channels.at(size_t(r.channel)).offset + r.first;
        if (at / 32 >= words || r.count <= 0 || at % 32 + r.count > 32)
            throw std::logic_error("cpu codec: " + cp.text + " does not fit the words of target " + t.name);
        code.pieces.push_back({at / 32, at % 32, codeShift, r.count >= 32 ? 0xffffffffu : (1u << r.count) - 1u});
        codeShift += r.count;
    }
    return code;
}

void placeConstant(const CodePlan& code, uint32_t value, uint32_t* words) {
    for (const Piece& p : code.pieces) words[p.word] |= ((value >> p.codeShift) & p.mask) << p.shift;
}

FieldPlan planField(const Target& t, const Field& f, int words) {
    FieldPlan fp;
    fp.codec = resolveCodec(f.encoding);
    fp.ditherPerFrame = f.ditherPerFrame;
    fp.source = surfaceOffset(f.attribute);
    fp.components = fp.source >= 0 ? attributeInfo(f.attribute).components : 0;
    for (const CodePlace& cp : f.codes) fp.codes.push_back(planCode(t, cp, words));
    const size_t expected = codeCount(fp.codec);
    if (fp.codes.empty() || fp.codes.size() > 4 || (expected != 0 && fp.codes.size() != expected))
        throw std::logic_error("cpu codec: field " + std::string(attributeName(f.attribute)) + " (" + f.encoding +
                               ") has " + std::to_string(f.codes.size()) + " codes");
    fp.inputs = isScalar(fp.codec) ? int(fp.codes.size()) : 3;
    if (const EncodingInfo* e = findEncoding(f.encoding); e && !e->reads.empty()) {
        const AttributeInfo* r = findAttribute(e->reads);
        fp.reads = r ? surfaceOffset(r->id) : -1;
        if (fp.reads < 0 || fp.source < 0)
            throw std::logic_error("cpu codec: field " + std::string(attributeName(f.attribute)) + " (" + f.encoding +
                                   ") reads " + e->reads + ", not a Surface member, or is an extra");
    }
    if (const EncodingInfo* e = findEncoding(f.encoding); e && !e->carries.empty()) {
        const AttributeInfo* r = findAttribute(e->carries);
        fp.carried = r ? surfaceOffset(r->id) : -1;
        if (fp.carried < 0 || fp.source < 0)
            throw std::logic_error("cpu codec: field " + std::string(attributeName(f.attribute)) + " (" + f.encoding +
                                   ") also stores " + e->carries + ", not a Surface member, or is an extra");
    }
    if (fp.source >= 0 && fp.source + fp.inputs > kSurfaceFloats)
        throw std::logic_error("cpu codec: field " + std::string(attributeName(f.attribute)) +
                               " reads past the Surface");
    for (size_t i = 0; i < 4; ++i)
        fp.constant[i] = f.value.empty() ? 0.0f : float(f.value[std::min(i, f.value.size() - 1)]);
    return fp;
}

}  // namespace

bool isScalar(Codec c) { return c <= Codec::Kz2LogPower; }

bool isCheckerboard(Codec c) { return c == Codec::YCbCrCheckerboard || c == Codec::YCoCgCheckerboard; }

int surfaceOffset(Attribute a) {
    switch (a) {
        case Attribute::Normal: return int(offsetof(Surface, normal)) / kFloat;
        case Attribute::BaseColor: return int(offsetof(Surface, baseColor)) / kFloat;
        case Attribute::Metallic: return int(offsetof(Surface, metallic)) / kFloat;
        case Attribute::Roughness: return int(offsetof(Surface, roughness)) / kFloat;
        case Attribute::Specular: return int(offsetof(Surface, specular)) / kFloat;
        case Attribute::SpecularColor: return int(offsetof(Surface, specularColor)) / kFloat;
        case Attribute::DiffuseColor: return int(offsetof(Surface, diffuseColor)) / kFloat;
        case Attribute::Occlusion: return int(offsetof(Surface, occlusion)) / kFloat;
        case Attribute::Emissive: return int(offsetof(Surface, emissive)) / kFloat;
        case Attribute::Position: return int(offsetof(Surface, position)) / kFloat;
        case Attribute::Depth: return int(offsetof(Surface, position)) / kFloat + 2;  // position.z (wiring_plan.h)
        case Attribute::Coat: return int(offsetof(Surface, coat)) / kFloat;
        case Attribute::CoatRoughness: return int(offsetof(Surface, coatRoughness)) / kFloat;
        case Attribute::CoatNormal: return int(offsetof(Surface, coatNormal)) / kFloat;
        case Attribute::SheenColor: return int(offsetof(Surface, sheenColor)) / kFloat;
        case Attribute::SheenRoughness: return int(offsetof(Surface, sheenRoughness)) / kFloat;
        case Attribute::AnisotropyStrength: return int(offsetof(Surface, anisotropyStrength)) / kFloat;
        case Attribute::AnisotropyDirection: return int(offsetof(Surface, anisotropyDirection)) / kFloat;
        case Attribute::ShadingModel: return int(offsetof(Surface, shadingModel)) / kFloat;
        default: return -1;
    }
}

CodecPlan compilePlan(const Layout& layout) {
    CodecPlan plan;
    const uint32_t named = layout.selectorModels();
    if (named)
        for (const ShadingModelInfo& m : listShadingModels()) {
            if (m.id == ShadingModel::Default || !((named >> unsigned(m.id)) & 1u)) continue;
            plan.modelTests.push_back({uint32_t(m.id), surfaceOffset(m.test), attributeInfo(m.test).components});
        }
    for (size_t ti = 0; ti < layout.targets.size(); ++ti) {
        const Target& t = layout.targets[ti];
        TargetPlan tp;
        tp.words = wordsPerPixel(t);
        if (tp.words != 1 && tp.words != 2 && tp.words != 4)
            throw std::logic_error("cpu codec: target " + t.name + " has " + std::to_string(tp.words) +
                                   " words per pixel");
        for (const Field& f : t.fields) {
            FieldPlan fp = planField(t, f, tp.words);
            if (f.attribute == Attribute::ShadingModel) {
                // The selector: its code per pixel from the model (encode), the stored id decoded
                // before every field (decodeRows), into Surface::shadingModel.
                fp.selector = true;
                for (const Field::ModelId& m : f.selector) fp.modelIds[size_t(m.model)] = m.id;
                plan.selectorTarget = int(ti);
                plan.selectorWords = tp.words;
                plan.selectorCode = fp.codes.at(0);
                tp.encodeFields.push_back(std::move(fp));
                continue;
            }
            if (f.conditional()) {
                fp.models = f.models;
                for (size_t i = 0; i < 4; ++i)
                    fp.idValue[i] = uint32_t(f.value.empty() ? 0.0 : f.value[std::min(i, f.value.size() - 1)]);
                fp.ids = layout.selectorIds(f.models);
                if (fp.source >= 0) tp.decodeFields.push_back(fp);
                tp.encodeFields.push_back(std::move(fp));  // never folded: its bits depend on the pixel's model
                continue;
            }
            if (fp.source >= 0) {
                if (fp.codec == Codec::Id && !plan.decodeError)
                    plan.decodeError = "cpu codec: no scalar decoder for id";
                tp.decodeFields.push_back(fp);
            }
            if (fp.codec == Codec::Id) {
                // The declared integer is the code, uint(v) of the double, whatever the attribute.
                for (size_t i = 0; i < fp.codes.size(); ++i) {
                    const double v = f.value.empty() ? 0.0 : f.value[std::min(i, f.value.size() - 1)];
                    placeConstant(fp.codes[i], uint32_t(v), tp.constantWords);
                }
            } else if (fp.source < 0 && !isCheckerboard(fp.codec)) {
                // A constant extra: encode its value once, through the same loop as the pixels.
                EncodeBlock b;
                for (int c = 0; c < 4; ++c) b.in[c][0] = fp.constant[c];
                encodeCodes(fp, 1, 0, 0, b);
                for (size_t i = 0; i < fp.codes.size(); ++i) placeConstant(fp.codes[i], b.code[i][0], tp.constantWords);
            } else {
                tp.encodeFields.push_back(std::move(fp));  // per pixel (a checkerboard extra: by parity)
            }
        }
        plan.targets.push_back(std::move(tp));
    }

    const std::vector<MaterialSlot> slots = materialPassSlots(layout);
    plan.materialTargets = materialTargetCount(layout);
    plan.materialSource.assign(size_t(plan.materialTargets) * 4, -1);
    for (const MaterialSlot& s : slots) {
        const int dest = surfaceOffset(s.attribute);
        if (dest < 0) throw std::logic_error("cpu codec: material slot of an extra");
        for (int c = 0; c < s.components; ++c) plan.materialSource.at(size_t(s.firstFloat + c)) = dest + c;
        plan.materialSlots.push_back({dest, attributeInfo(s.attribute).components, s.components, s.firstFloat});
    }

    for (const Fallback* fb : orderedFallbacks(layout)) {
        FallbackPlan p;
        p.kind = fb->kind;
        p.dest = surfaceOffset(fb->attribute);
        if (layout.storesConditionally(fb->attribute))
            p.storedIds = layout.selectorIds(layout.conditionalModels(fb->attribute));
        if (p.dest < 0) continue;  // an extra: nothing in the Surface to set
        // The decode loop writes a fallback straight into its attribute while reading its inputs.
        for (const Attribute in : fallbackInputs(fb->kind))
            if (in == fb->attribute)
                throw std::logic_error("cpu codec: fallback of " + std::string(attributeName(in)) + " reads itself");
        p.components = attributeInfo(fb->attribute).components;
        for (size_t i = 0; i < 3; ++i)
            p.value[i] = fb->value.empty() ? 0.0f : float(fb->value[std::min(i, fb->value.size() - 1)]);
        plan.fallbacks.push_back(p);
    }

    std::vector<bool> written(kSurfaceFloats, false);
    auto mark = [&](int first, int count) {
        for (int c = 0; c < count; ++c) written.at(size_t(first + c)) = true;
    };
    if (plan.selectorTarget >= 0) mark(surfaceOffset(Attribute::ShadingModel), 1);
    for (const TargetPlan& t : plan.targets)
        for (const FieldPlan& f : t.decodeFields) {
            if (f.ids) continue;  // conditional: elsewhere the attribute keeps 0 (or its fallback's value)
            mark(f.source, f.components);
            if (f.carried >= 0) mark(f.carried, 1);  // occlusion, anisotropy_strength: one float
        }
    for (const MaterialSlotPlan& s : plan.materialSlots) mark(s.dest, s.components);
    for (const FallbackPlan& f : plan.fallbacks)
        // An attribute stored under some models starts from 0 as in readGBuffer, whatever sets it
        // later: a fallback that reads it before its own fallback (a pixel of an id no model has,
        // where fallbacks derive from each other) reads that 0.
        if (f.kind != FallbackKind::MaterialPass && f.storedIds == 0) mark(f.dest, f.components);
    for (int k = 0; k < kSurfaceFloats; ++k)
        if (!written[size_t(k)]) plan.unwritten.push_back(k);

    auto read = [&](int first, int count) {
        for (int c = 0; c < count; ++c) plan.encodeGroups |= 1u << ((first + c) / 4);
    };
    for (const ModelTest& m : plan.modelTests) read(m.first, m.components);
    for (const TargetPlan& t : plan.targets)
        for (const FieldPlan& f : t.encodeFields)
            if (f.source >= 0 && !f.selector) {
                read(f.source, f.inputs);
                if (f.reads >= 0) read(f.reads, 3);
                if (f.carried >= 0) read(f.carried, 1);
            }
    for (const int src : plan.materialSource)
        if (src >= 0) read(src, 1);
    return plan;
}

}  // namespace gbl::codec
