// The shading models a layout's selector may name, and the encoder's rule for which one a pixel
// gets (layouts/README.md, "Shading models: the selector"). This table is the rule's one statement:
// the generated writeGBuffer (src/codec/wiring_codegen.cpp) and the CPU codec
// (src/codec/cpu_codec_plan.cpp) both build their test from it, so they cannot drift; the bit
// tests (tests/codec/gpu_cpu_bits_test.cpp) hold them to the same codes.
//
// The order is the preference: a pixel is of the first model the layout names whose layer it
// carries, as UE's material has one shading model (ShadingCommon.ush's SHADINGMODELID_*: a
// clear-coat material writes CLEAR_COAT and its CustomData holds the coat, whatever else it has)
// and HDRP's GBuffer2 holds one feature's data (Lit.hlsl's materialFeatureId).
// Only the models the selector names compete: HDRP's names default and anisotropic, not clear_coat,
// because its coat mask is a flag beside any feature (Lit.hlsl:663-667 @c667268a), so a coated
// anisotropic pixel is anisotropic and keeps the coat its unconditional field stores (held by
// tests/encoding/layer_packings_test.cpp, HdrpAnisotropicFeatureEqualsEncodeIntoGBuffer).
#include <string>

#include "layout.h"

namespace gbl {

const std::vector<ShadingModelInfo>& listShadingModels() {
    static const std::vector<ShadingModelInfo> table = {
        {ShadingModel::ClearCoat, "clear_coat", Attribute::Coat, "coat > 0: the coat, its roughness and normal"},
        {ShadingModel::Cloth, "cloth", Attribute::SheenColor, "some sheen_color component > 0: the sheen"},
        {ShadingModel::Anisotropic, "anisotropic", Attribute::AnisotropyStrength,
         "anisotropy_strength > 0: the anisotropy and its direction"},
        {ShadingModel::Default, "default", Attribute::Normal, "every other pixel: no layer"},
    };
    return table;
}

const ShadingModelInfo& shadingModelInfo(ShadingModel m) {
    for (const ShadingModelInfo& i : listShadingModels())
        if (i.id == m) return i;
    return listShadingModels().back();
}

const ShadingModelInfo* findShadingModel(std::string_view name) {
    for (const ShadingModelInfo& i : listShadingModels())
        if (name == i.name) return &i;
    return nullptr;
}

std::string knownShadingModelNames() { return "default, clear_coat, cloth, anisotropic"; }

std::string shadingModelNames(uint32_t models) {
    std::string s;
    for (int m = 0; m < kShadingModels; ++m)
        if ((models >> m) & 1u) s += (s.empty() ? "" : ", ") + std::string(shadingModelInfo(ShadingModel(m)).name);
    return s;
}

}  // namespace gbl
