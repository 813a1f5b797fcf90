// Material conversion. Only texCoord set 0 is loaded (Vertex has one uv); a texture that asks
// for another set is sampled with set 0, which is right for the common case of a single set.
#include "scene_gltf_materials.h"

#include <algorithm>
#include <cmath>

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

Material convertMaterial(const GltfContext& ctx, size_t index, TextureTable& textures) {
    const tinygltf::Material& src = ctx.model.materials[index];
    const std::string where = describeItem("material", index, src.name);
    const auto& pbr = src.pbrMetallicRoughness;
    Material m;
    m.name = src.name.empty() ? "material " + std::to_string(index) : src.name;
    m.baseColorFactor = glm::clamp(vectorOr<4>(pbr.baseColorFactor, glm::vec4(1.0f)), 0.0f, 1.0f);
    m.metallicFactor = unitInterval(pbr.metallicFactor, 1.0f);
    m.roughnessFactor = unitInterval(pbr.roughnessFactor, 1.0f);
    // Emissive may exceed 1 only through KHR_materials_emissive_strength, which is not read.
    m.emissiveFactor = glm::clamp(vectorOr<3>(src.emissiveFactor, glm::vec3(0.0f)), 0.0f, 1.0f);
    m.normalScale = finiteOr(src.normalTexture.scale, 1.0f);
    m.occlusionStrength = unitInterval(src.occlusionTexture.strength, 1.0f);
    m.doubleSided = src.doubleSided;
    // alphaMode MASK cuts out; BLEND has no place in a G-buffer (engines draw it forward after
    // lighting), so it renders opaque here, as OPAQUE does.
    m.alphaMask = src.alphaMode == "MASK";
    m.alphaCutoff = finiteOr(src.alphaCutoff, 0.5f);

    // Colour data is sRGB-encoded per the glTF spec; everything else is linear.
    m.baseColorTexture = textures.get(pbr.baseColorTexture.index, true, where + " baseColorTexture");
    m.metallicRoughnessTexture =
        textures.get(pbr.metallicRoughnessTexture.index, false, where + " metallicRoughnessTexture");
    m.normalTexture = textures.get(src.normalTexture.index, false, where + " normalTexture");
    m.occlusionTexture = textures.get(src.occlusionTexture.index, false, where + " occlusionTexture");
    m.emissiveTexture = textures.get(src.emissiveTexture.index, true, where + " emissiveTexture");

    if (const auto it = src.extensions.find("KHR_materials_specular"); it != src.extensions.end()) {
        const tinygltf::Value& ext = it->second;
        m.specularFactor = std::clamp(finiteOr(numberOr(ext, "specularFactor", 1.0), 1.0f), 0.0f, 1.0f);
        // Colour factors above 1 are allowed by the extension (F0 = min(0.04 * colour, 1)).
        m.specularColorFactor = glm::max(vec3Or(ext, "specularColorFactor", glm::vec3(1.0f)), 0.0f);
        m.specularTexture = textures.get(textureIndexOf(ext, "specularTexture"), false,
                                         where + " KHR_materials_specular specularTexture");
        m.specularColorTexture = textures.get(textureIndexOf(ext, "specularColorTexture"), true,
                                              where + " KHR_materials_specular specularColorTexture");
    }
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
