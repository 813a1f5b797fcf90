// Material conversion: glTF 2.0's metallic-roughness material and the KHR_materials_* extensions
// gbufferlab shades (specular, ior, emissive_strength, clearcoat, sheen, anisotropy), each
// texture with its texCoord set (0 or 1) and KHR_texture_transform. The JSON's types and ranges
// were checked before (scene_gltf_json_check.cpp: a clearcoatFactor of 1.5 is refused there, at its
// place); here the values are read as the extensions' READMEs define them.
#include "scene_gltf_materials.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "scene_gltf_textures.h"

namespace gbl {
namespace {

float finiteOr(double value, float fallback) {
    return std::isfinite(value) ? static_cast<float>(value) : fallback;
}

float unitInterval(double value, float fallback) { return std::clamp(finiteOr(value, fallback), 0.0f, 1.0f); }

template <int N>
glm::vec<N, float> vectorOr(const std::vector<double>& values, const glm::vec<N, float>& fallback) {
    if (values.size() != N) return fallback;
    glm::vec<N, float> out;
    for (int i = 0; i < N; ++i) out[i] = finiteOr(values[static_cast<size_t>(i)], fallback[i]);
    return out;
}

// The extension's JSON helpers: tinygltf::Value asserts on the wrong type, so check first.
double numberOr(const tinygltf::Value& object, const char* key, double fallback) {
    if (!object.IsObject() || !object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

int textureIndexOf(const tinygltf::Value& object, const char* key) {
    if (!object.IsObject() || !object.Has(key)) return -1;
    const tinygltf::Value& info = object.Get(key);
    if (!info.IsObject() || !info.Has("index") || !info.Get("index").IsNumber()) return -1;
    return info.Get("index").GetNumberAsInt();
}

glm::vec3 vec3Or(const tinygltf::Value& object, const char* key, const glm::vec3& fallback) {
    if (!object.IsObject() || !object.Has(key)) return fallback;
    const tinygltf::Value& array = object.Get(key);
    if (!array.IsArray() || array.ArrayLen() != 3) return fallback;
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        const tinygltf::Value& v = array.Get(i);
        out[i] = v.IsNumber() ? finiteOr(v.GetNumberAsDouble(), fallback[i]) : fallback[i];
    }
    return out;
}

glm::vec2 vec2Or(const tinygltf::Value& object, const char* key, const glm::vec2& fallback) {
    if (!object.IsObject() || !object.Has(key)) return fallback;
    const tinygltf::Value& array = object.Get(key);
    if (!array.IsArray() || array.ArrayLen() != 2) return fallback;
    glm::vec2 out;
    for (int i = 0; i < 2; ++i) {
        const tinygltf::Value& v = array.Get(i);
        out[i] = v.IsNumber() ? finiteOr(v.GetNumberAsDouble(), fallback[i]) : fallback[i];
    }
    return out;
}

// KHR_texture_transform of a textureInfo's `extensions`, and the set it samples: the
// extension's texCoord "Overrides the textureInfo texCoord value if supplied".
TextureTransform textureTransformOf(const tinygltf::ExtensionMap& extensions, int texCoord) {
    TextureTransform t;
    t.texCoord = texCoord;
    const auto it = extensions.find("KHR_texture_transform");
    if (it == extensions.end()) return t;
    const tinygltf::Value& ext = it->second;
    t.offset = vec2Or(ext, "offset", glm::vec2(0.0f));
    t.rotation = finiteOr(numberOr(ext, "rotation", 0.0), 0.0f);
    t.scale = vec2Or(ext, "scale", glm::vec2(1.0f));
    if (ext.IsObject() && ext.Has("texCoord") && ext.Get("texCoord").IsNumber())
        t.texCoord = ext.Get("texCoord").GetNumberAsInt();
    return t;
}

// An extension's textureInfo (a JSON object): its texture, texCoord, KHR_texture_transform and,
// for a normalTextureInfo, scale.
struct ExtensionTexture {
    int index = -1;
    TextureTransform transform;
    float scale = 1.0f;
};
ExtensionTexture extensionTexture(const tinygltf::Value& object, const char* key) {
    ExtensionTexture t;
    if (!object.IsObject() || !object.Has(key)) return t;
    const tinygltf::Value& info = object.Get(key);
    if (!info.IsObject()) return t;
    t.index = textureIndexOf(object, key);
    const int texCoord = info.Has("texCoord") && info.Get("texCoord").IsNumber() ? info.Get("texCoord").GetNumberAsInt() : 0;
    tinygltf::ExtensionMap extensions;
    if (info.Has("extensions") && info.Get("extensions").IsObject()) {
        const tinygltf::Value& e = info.Get("extensions");
        for (const std::string& name : e.Keys()) extensions[name] = e.Get(name);
    }
    t.transform = textureTransformOf(extensions, texCoord);
    t.scale = finiteOr(numberOr(info, "scale", 1.0), 1.0f);
    return t;
}

// The set a slot samples must be one gbufferlab loads (scene.h Vertex: uv, uv1).
void checkTexCoordSet(const GltfContext& ctx, const std::string& where, const TextureTransform& t) {
    if (t.texCoord != 0 && t.texCoord != 1)
        ctx.fail(where, "texCoord " + std::to_string(t.texCoord) + " names TEXCOORD_" + std::to_string(t.texCoord) +
                            ", and gbufferlab reads TEXCOORD_0 and TEXCOORD_1 only",
                 "use texture coordinate set 0 or 1");
}

Material convertMaterial(const GltfContext& ctx, size_t index, TextureTable& textures) {
    const tinygltf::Material& src = ctx.model.materials[index];
    const std::string where = describeItem("material", index, src.name);
    const auto& pbr = src.pbrMetallicRoughness;
    Material m;
    m.name = src.name.empty() ? "material " + std::to_string(index) : src.name;
    m.baseColorFactor = glm::clamp(vectorOr<4>(pbr.baseColorFactor, glm::vec4(1.0f)), 0.0f, 1.0f);
    m.metallicFactor = unitInterval(pbr.metallicFactor, 1.0f);
    m.roughnessFactor = unitInterval(pbr.roughnessFactor, 1.0f);
    // Emissive exceeds 1 only through KHR_materials_emissive_strength (emissiveStrength below).
    m.emissiveFactor = glm::clamp(vectorOr<3>(src.emissiveFactor, glm::vec3(0.0f)), 0.0f, 1.0f);
    m.normalScale = finiteOr(src.normalTexture.scale, 1.0f);
    m.occlusionStrength = unitInterval(src.occlusionTexture.strength, 1.0f);
    m.doubleSided = src.doubleSided;
    // alphaMode MASK cuts out; BLEND has no place in a G-buffer (engines draw it forward after
    // lighting), so it renders opaque here, as OPAQUE does.
    m.alphaMask = src.alphaMode == "MASK";
    m.alphaBlend = src.alphaMode == "BLEND";
    m.alphaCutoff = finiteOr(src.alphaCutoff, 0.5f);

    // Colour data is sRGB-encoded per the glTF spec; everything else is linear.
    auto slot = [&](TextureSlot k) -> TextureTransform& { return m.uvTransforms[size_t(k)]; };
    auto core = [&](TextureSlot k, int texCoord, const tinygltf::ExtensionMap& extensions, const std::string& at) {
        slot(k) = textureTransformOf(extensions, texCoord);
        checkTexCoordSet(ctx, where + " " + at, slot(k));
    };
    m.baseColorTexture = textures.get(pbr.baseColorTexture.index, true, where + " baseColorTexture");
    core(TextureSlot::BaseColor, pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions, "baseColorTexture");
    m.metallicRoughnessTexture =
        textures.get(pbr.metallicRoughnessTexture.index, false, where + " metallicRoughnessTexture");
    core(TextureSlot::MetallicRoughness, pbr.metallicRoughnessTexture.texCoord, pbr.metallicRoughnessTexture.extensions,
         "metallicRoughnessTexture");
    m.normalTexture = textures.get(src.normalTexture.index, false, where + " normalTexture");
    core(TextureSlot::Normal, src.normalTexture.texCoord, src.normalTexture.extensions, "normalTexture");
    m.occlusionTexture = textures.get(src.occlusionTexture.index, false, where + " occlusionTexture");
    core(TextureSlot::Occlusion, src.occlusionTexture.texCoord, src.occlusionTexture.extensions, "occlusionTexture");
    m.emissiveTexture = textures.get(src.emissiveTexture.index, true, where + " emissiveTexture");
    core(TextureSlot::Emissive, src.emissiveTexture.texCoord, src.emissiveTexture.extensions, "emissiveTexture");

    // An extension's texture: its index in Scene::textures, its slot's set and transform.
    auto extension = [&](const tinygltf::Value& ext, const char* extName, const char* key, TextureSlot k, bool srgb) {
        const ExtensionTexture t = extensionTexture(ext, key);
        const std::string at = where + " " + extName + " " + key;
        slot(k) = t.transform;
        if (t.index >= 0) checkTexCoordSet(ctx, at, t.transform);
        return std::make_pair(textures.get(t.index, srgb, at), t.scale);
    };
    auto find = [&](const char* name) -> const tinygltf::Value* {
        const auto it = src.extensions.find(name);
        return it == src.extensions.end() ? nullptr : &it->second;
    };

    if (const tinygltf::Value* ext = find("KHR_materials_specular")) {
        m.specularFactor = std::clamp(finiteOr(numberOr(*ext, "specularFactor", 1.0), 1.0f), 0.0f, 1.0f);
        // Colour factors above 1 are allowed by the extension (F0 = min(0.04 * colour, 1)).
        m.specularColorFactor = glm::max(vec3Or(*ext, "specularColorFactor", glm::vec3(1.0f)), 0.0f);
        m.specularTexture = extension(*ext, "KHR_materials_specular", "specularTexture", TextureSlot::Specular, false).first;
        m.specularColorTexture =
            extension(*ext, "KHR_materials_specular", "specularColorTexture", TextureSlot::SpecularColor, true).first;
    }
    // KHR_materials_ior: "Valid values for ior are numbers greater than or equal to one. As a special
    // case, a value of zero is allowed" (the JSON check refused the rest).
    if (const tinygltf::Value* ext = find("KHR_materials_ior")) m.ior = finiteOr(numberOr(*ext, "ior", 1.5), 1.5f);
    // KHR_materials_emissive_strength: a non-negative multiplier of the emissive factor.
    if (const tinygltf::Value* ext = find("KHR_materials_emissive_strength"))
        m.emissiveStrength = std::max(finiteOr(numberOr(*ext, "emissiveStrength", 1.0), 1.0f), 0.0f);
    // KHR_materials_clearcoat: factors default to 0 (a clearcoatFactor of 0 disables the layer);
    // "If the clearcoatTexture or clearcoatRoughnessTexture is not given, respective texture
    // components are assumed to have a value of 1.0. All clearcoat textures contain RGB components
    // in linear space."
    if (const tinygltf::Value* ext = find("KHR_materials_clearcoat")) {
        m.clearcoatFactor = unitInterval(numberOr(*ext, "clearcoatFactor", 0.0), 0.0f);
        m.clearcoatRoughnessFactor = unitInterval(numberOr(*ext, "clearcoatRoughnessFactor", 0.0), 0.0f);
        m.clearcoatTexture = extension(*ext, "KHR_materials_clearcoat", "clearcoatTexture", TextureSlot::Clearcoat, false).first;
        m.clearcoatRoughnessTexture =
            extension(*ext, "KHR_materials_clearcoat", "clearcoatRoughnessTexture", TextureSlot::ClearcoatRoughness, false).first;
        std::tie(m.clearcoatNormalTexture, m.clearcoatNormalScale) =
            extension(*ext, "KHR_materials_clearcoat", "clearcoatNormalTexture", TextureSlot::ClearcoatNormal, false);
    }
    // KHR_materials_sheen: "The sheen color is in sRGB transfer function"; roughness in alpha.
    if (const tinygltf::Value* ext = find("KHR_materials_sheen")) {
        m.sheenColorFactor = glm::clamp(vec3Or(*ext, "sheenColorFactor", glm::vec3(0.0f)), 0.0f, 1.0f);
        m.sheenRoughnessFactor = unitInterval(numberOr(*ext, "sheenRoughnessFactor", 0.0), 0.0f);
        m.sheenColorTexture = extension(*ext, "KHR_materials_sheen", "sheenColorTexture", TextureSlot::SheenColor, true).first;
        m.sheenRoughnessTexture =
            extension(*ext, "KHR_materials_sheen", "sheenRoughnessTexture", TextureSlot::SheenRoughness, false).first;
    }
    // KHR_materials_anisotropy: strength in [0, 1], rotation in radians, texture linear.
    if (const tinygltf::Value* ext = find("KHR_materials_anisotropy")) {
        m.anisotropyStrength = unitInterval(numberOr(*ext, "anisotropyStrength", 0.0), 0.0f);
        m.anisotropyRotation = finiteOr(numberOr(*ext, "anisotropyRotation", 0.0), 0.0f);
        m.anisotropyTexture = extension(*ext, "KHR_materials_anisotropy", "anisotropyTexture", TextureSlot::Anisotropy, false).first;
    }
    // Transmissive and volumetric materials: deferred engines draw them forward (their G-buffer
    // cannot hold what is behind them), so their pixels are masked out of the metrics, not shaded
    // as if opaque in silence. A transmissionFactor of 0 transmits nothing: opaque.
    if (const tinygltf::Value* ext = find("KHR_materials_transmission")) {
        if (numberOr(*ext, "transmissionFactor", 0.0) > 0.0 || textureIndexOf(*ext, "transmissionTexture") >= 0)
            m.forward = "KHR_materials_transmission";
    }
    if (m.forward.empty() && find("KHR_materials_volume")) m.forward = "KHR_materials_volume";
    return m;
}

}  // namespace

Material defaultGltfMaterial() {
    Material m;
    m.name = "default material";  // Material's own defaults are glTF's
    return m;
}

void loadMaterials(const GltfContext& ctx, Scene& scene) {
    TextureTable textures(ctx, scene.textures);
    for (size_t i = 0; i < ctx.model.materials.size(); ++i)
        scene.materials.push_back(convertMaterial(ctx, i, textures));
}

}  // namespace gbl
