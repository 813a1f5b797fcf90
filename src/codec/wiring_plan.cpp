#include "wiring_plan.h"

#include <cstring>
#include <set>
#include <stdexcept>

#include "encoding_registry.h"

namespace gbl {

const char* surfaceMemberName(Attribute a) {
    switch (a) {
        case Attribute::Normal: return "normal";
        case Attribute::BaseColor: return "baseColor";
        case Attribute::Metallic: return "metallic";
        case Attribute::Roughness: return "roughness";
        case Attribute::Specular: return "specular";
        case Attribute::SpecularColor: return "specularColor";
        case Attribute::DiffuseColor: return "diffuseColor";
        case Attribute::Occlusion: return "occlusion";
        case Attribute::Emissive: return "emissive";
        case Attribute::Position: return "position";
        case Attribute::Coat: return "coat";
        case Attribute::CoatRoughness: return "coatRoughness";
        case Attribute::CoatNormal: return "coatNormal";
        case Attribute::SheenColor: return "sheenColor";
        case Attribute::SheenRoughness: return "sheenRoughness";
        case Attribute::AnisotropyStrength: return "anisotropyStrength";
        case Attribute::AnisotropyDirection: return "anisotropyDirection";
        default: return nullptr;
    }
}

const std::vector<Attribute>& surfaceAttributes() {
    static const std::vector<Attribute> list = {
        Attribute::Normal,   Attribute::BaseColor,          Attribute::Metallic,      Attribute::Roughness,
        Attribute::Specular, Attribute::SpecularColor,      Attribute::DiffuseColor,  Attribute::Occlusion,
        Attribute::Emissive, Attribute::Position,           Attribute::Coat,          Attribute::CoatRoughness,
        Attribute::CoatNormal, Attribute::SheenColor,       Attribute::SheenRoughness, Attribute::AnisotropyStrength,
        Attribute::AnisotropyDirection};
    return list;
}

const char* surfaceSlotName(Attribute a) { return a == Attribute::Depth ? "position.z" : surfaceMemberName(a); }

int wordsPerPixel(const Target& target) { return target.bits() <= 32 ? 1 : target.bits() / 32; }

VkFormat uintFormatOf(const Target& target) {
    const int bits = target.bits();
    if (bits <= 8) return VK_FORMAT_R8_UINT;
    if (bits <= 16) return VK_FORMAT_R16_UINT;
    if (bits <= 32) return VK_FORMAT_R32_UINT;
    if (bits <= 64) return VK_FORMAT_R32G32_UINT;
    return VK_FORMAT_R32G32B32A32_UINT;
}

std::vector<uint32_t> texelsToWords(const std::vector<uint8_t>& bytes, size_t pixels) {
    const size_t texel = pixels ? bytes.size() / pixels : 0;
    if (texel == 0 || bytes.size() != texel * pixels || (texel < 4 && texel != 1 && texel != 2) || (texel >= 4 && texel % 4))
        throw std::logic_error("texelsToWords: " + std::to_string(bytes.size()) + " bytes for " + std::to_string(pixels) +
                               " texels");
    if (texel >= 4) {
        std::vector<uint32_t> words(bytes.size() / 4);
        std::memcpy(words.data(), bytes.data(), words.size() * 4);
        return words;
    }
    std::vector<uint32_t> words(pixels);
    for (size_t i = 0; i < pixels; ++i)
        words[i] = texel == 1 ? uint32_t(bytes[i]) : uint32_t(bytes[2 * i]) | uint32_t(bytes[2 * i + 1]) << 8;
    return words;
}

VkFormat vkFormatFromName(const std::string& name) {
    static const std::vector<std::pair<const char*, VkFormat>> table = {
        {"R8_UNORM", VK_FORMAT_R8_UNORM},
        {"R8G8_UNORM", VK_FORMAT_R8G8_UNORM},
        {"R8G8B8A8_UNORM", VK_FORMAT_R8G8B8A8_UNORM},
        {"R8G8B8A8_SRGB", VK_FORMAT_R8G8B8A8_SRGB},
        {"R8G8B8A8_SNORM", VK_FORMAT_R8G8B8A8_SNORM},
        {"B8G8R8A8_UNORM", VK_FORMAT_B8G8R8A8_UNORM},
        {"B8G8R8A8_SRGB", VK_FORMAT_B8G8R8A8_SRGB},
        {"A8B8G8R8_UNORM_PACK32", VK_FORMAT_A8B8G8R8_UNORM_PACK32},
        {"A8B8G8R8_SRGB_PACK32", VK_FORMAT_A8B8G8R8_SRGB_PACK32},
        {"R8_UINT", VK_FORMAT_R8_UINT},
        {"R8G8_UINT", VK_FORMAT_R8G8_UINT},
        {"R8G8B8A8_UINT", VK_FORMAT_R8G8B8A8_UINT},
        {"A2B10G10R10_UNORM_PACK32", VK_FORMAT_A2B10G10R10_UNORM_PACK32},
        {"A2R10G10B10_UNORM_PACK32", VK_FORMAT_A2R10G10B10_UNORM_PACK32},
        {"A2B10G10R10_UINT_PACK32", VK_FORMAT_A2B10G10R10_UINT_PACK32},
        {"B10G11R11_UFLOAT_PACK32", VK_FORMAT_B10G11R11_UFLOAT_PACK32},
        {"R16_UNORM", VK_FORMAT_R16_UNORM},
        {"R16G16_UNORM", VK_FORMAT_R16G16_UNORM},
        {"R16G16B16A16_UNORM", VK_FORMAT_R16G16B16A16_UNORM},
        {"R16_SFLOAT", VK_FORMAT_R16_SFLOAT},
        {"R16G16_SFLOAT", VK_FORMAT_R16G16_SFLOAT},
        {"R16G16B16A16_SFLOAT", VK_FORMAT_R16G16B16A16_SFLOAT},
        {"R16_UINT", VK_FORMAT_R16_UINT},
        {"R16G16_UINT", VK_FORMAT_R16G16_UINT},
        {"R16G16B16A16_UINT", VK_FORMAT_R16G16B16A16_UINT},
        {"R32_SFLOAT", VK_FORMAT_R32_SFLOAT},
        {"R32G32_SFLOAT", VK_FORMAT_R32G32_SFLOAT},
        {"R32G32B32A32_SFLOAT", VK_FORMAT_R32G32B32A32_SFLOAT},
        {"R32_UINT", VK_FORMAT_R32_UINT},
        {"R32G32_UINT", VK_FORMAT_R32G32_UINT},
        {"R32G32B32A32_UINT", VK_FORMAT_R32G32B32A32_UINT},
        {"D16_UNORM", VK_FORMAT_D16_UNORM},
        {"X8_D24_UNORM_PACK32", VK_FORMAT_X8_D24_UNORM_PACK32},
        {"D24_UNORM_S8_UINT", VK_FORMAT_D24_UNORM_S8_UINT},
        {"D32_SFLOAT", VK_FORMAT_D32_SFLOAT},
        {"D32_SFLOAT_S8_UINT", VK_FORMAT_D32_SFLOAT_S8_UINT},
    };
    for (const auto& [n, f] : table)
        if (name == n) return f;
    return VK_FORMAT_UNDEFINED;
}

std::vector<MaterialSlot> materialPassSlots(const Layout& layout) {
    std::vector<MaterialSlot> slots;
    int next = 0;
    for (const Fallback& fb : layout.fallbacks) {
        if (fb.kind != FallbackKind::MaterialPass) continue;
        const int n = attributeInfo(fb.attribute).components;
        slots.push_back({fb.attribute, n, next});
        next += n;
    }
    return slots;
}

int materialTargetCount(const Layout& layout) {
    int floats = 0;
    for (const MaterialSlot& s : materialPassSlots(layout)) floats += s.components;
    return (floats + 3) / 4;
}

std::vector<Attribute> fallbackInputs(FallbackKind kind) {
    using A = Attribute;
    switch (kind) {
        case FallbackKind::FromMetallic: return {A::BaseColor, A::Metallic};
        case FallbackKind::Ue4: return {A::BaseColor, A::Metallic, A::Specular};
        case FallbackKind::FromBaseColor: return {A::BaseColor, A::Metallic};
        case FallbackKind::FromDiffuseSpecular: return {A::DiffuseColor, A::Metallic, A::SpecularColor};
        case FallbackKind::FromSpecularColor: return {A::SpecularColor};
        case FallbackKind::FromRoughness: return {A::Roughness};
        default: return {};
    }
}

std::vector<const Fallback*> orderedFallbacks(const Layout& layout) {
    std::set<Attribute> pending;
    for (const Fallback& f : layout.fallbacks) pending.insert(f.attribute);
    std::vector<const Fallback*> out;
    std::vector<bool> done(layout.fallbacks.size(), false);
    for (size_t round = 0; round <= 2 * layout.fallbacks.size(); ++round) {
        bool progress = false;
        for (size_t i = 0; i < layout.fallbacks.size(); ++i) {
            if (done[i]) continue;
            bool ready = true;
            for (Attribute a : fallbackInputs(layout.fallbacks[i].kind)) ready &= pending.count(a) == 0;
            if (!ready) continue;
            done[i] = true;
            progress = true;
            pending.erase(layout.fallbacks[i].attribute);
            out.push_back(&layout.fallbacks[i]);
        }
        if (progress) continue;
        // Stuck on fallbacks that derive from each other: allowed only between attributes stored
        // under some models, where every model stores one of them (validation: HDRP's fresnel0
        // under its standard feature, its metallic under anisotropy). The first of them in file
        // order goes first; on a pixel of a model storing it, its fallback is skipped.
        for (size_t i = 0; i < layout.fallbacks.size(); ++i) {
            if (done[i] || !layout.storesConditionally(layout.fallbacks[i].attribute)) continue;
            done[i] = true;
            pending.erase(layout.fallbacks[i].attribute);
            out.push_back(&layout.fallbacks[i]);
            break;
        }
    }
    if (out.size() != layout.fallbacks.size())
        throw std::logic_error("layout " + layout.name + ": fallbacks depend on each other in a cycle");
    return out;
}

}  // namespace gbl
