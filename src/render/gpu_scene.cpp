#include "gpu_scene.h"

#include <algorithm>
#include <cmath>

#include "srgb_texels.h"
#include "texture_mip_cache.h"

namespace gbl {

namespace {

// KHR_materials_ior's dielectric F0, ((ior - 1) / (ior + 1))^2 (0.04 at 1.5, rounded from double:
// the float 0.04 the shaders wrote before the extension); ior 0, the specular-glossiness
// compatibility mode, is an infinite ior: F0 = 1.
float dielectricF0OfIor(float ior) {
    if (ior == 0.0f) return 1.0f;
    const double r = (double(ior) - 1.0) / (double(ior) + 1.0);
    return float(r * r);
}

// The identity transform of a slot sampling TEXCOORD_0: what a scene without transforms reads.
void packUvTransforms(const Material& m, gpu::GpuMaterial& g) {
    for (size_t k = 0; k < kTextureSlotCount; ++k) {
        const TextureTransform& t = m.uvTransforms[k];
        const glm::mat2 a = t.matrix();
        g.uvTransforms[2 * k] = glm::vec4(a[0][0], a[0][1], a[1][0], a[1][1]);
        g.uvTransforms[2 * k + 1] = glm::vec4(t.offset, float(t.texCoord), t.transforms() ? 1.0f : 0.0f);
    }
}

}  // namespace

std::array<int, kMaterialTextureSlotCount> materialSlotTextures(const gpu::GpuMaterial& m) {
    return {m.textures0.x, m.textures0.y, m.textures0.z, m.textures0.w, m.textures1.x, m.textures1.y, m.textures1.z,
            m.textures1.w, m.textures2.x, m.textures2.y, m.textures2.z, m.textures2.w, m.textures3.x};
}

SceneShaderFeatures sceneShaderFeatures(const Scene& scene) {
    SceneShaderFeatures f;
    for (const Material& m : scene.materials) {
        f.layers |= m.layers();
        for (const TextureTransform& t : m.uvTransforms) f.uvTransforms = f.uvTransforms || t.transforms() || t.texCoord != 0;
    }
    return f;
}

std::vector<gpu::GpuMaterial> packMaterials(const Scene& scene) {
    std::vector<gpu::GpuMaterial> out;
    for (const Material& m : scene.materials) {
        gpu::GpuMaterial g{};
        g.baseColorFactor = m.baseColorFactor;
        // emissiveStrength 1 leaves the factor's bits as they were.
        g.emissiveNormalScale = glm::vec4(m.emissiveFactor * m.emissiveStrength, m.normalScale);
        g.specularColorSpecular = glm::vec4(m.specularColorFactor, m.specularFactor);
        g.metallicRoughnessOcclusion =
            glm::vec4(m.metallicFactor, m.roughnessFactor, m.occlusionStrength, m.doubleSided ? 1.0f : 0.0f);
        g.textures0 = glm::ivec4(m.baseColorTexture, m.metallicRoughnessTexture, m.normalTexture, m.occlusionTexture);
        g.textures1 = glm::ivec4(m.emissiveTexture, m.specularTexture, m.specularColorTexture, m.clearcoatTexture);
        g.alphaMaskCutoff = glm::vec4(m.alphaMask ? 1.0f : 0.0f, m.alphaCutoff, dielectricF0OfIor(m.ior), float(m.layers()));
        g.clearcoat = glm::vec4(m.clearcoatFactor, m.clearcoatRoughnessFactor, m.clearcoatNormalScale, 0.0f);
        g.sheen = glm::vec4(m.sheenColorFactor, m.sheenRoughnessFactor);
        g.anisotropy = glm::vec4(m.anisotropyStrength, std::cos(m.anisotropyRotation), std::sin(m.anisotropyRotation), 0.0f);
        g.textures2 = glm::ivec4(m.clearcoatRoughnessTexture, m.clearcoatNormalTexture, m.sheenColorTexture,
                                 m.sheenRoughnessTexture);
        g.textures3 = glm::ivec4(m.anisotropyTexture, kNoTexture, kNoTexture, kNoTexture);
        packUvTransforms(m, g);
        out.push_back(g);
    }
    if (out.empty()) {
        gpu::GpuMaterial g{};
        g.baseColorFactor = glm::vec4(1.0f);
        g.emissiveNormalScale = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
        g.specularColorSpecular = glm::vec4(1.0f);
        g.metallicRoughnessOcclusion = glm::vec4(0.0f, 0.5f, 1.0f, 0.0f);
        g.textures0 = g.textures1 = g.textures2 = g.textures3 = glm::ivec4(kNoTexture);
        g.alphaMaskCutoff = glm::vec4(0.0f, 0.5f, dielectricF0OfIor(1.5f), 0.0f);
        packUvTransforms(Material{}, g);
        out.push_back(g);
    }
    return out;
}

MaterialTextureSlots materialTextureSlots(const std::vector<gpu::GpuMaterial>& materials, uint32_t textureCount) {
    MaterialTextureSlots slots;
    for (const gpu::GpuMaterial& m : materials) {
        const std::array<int, kMaterialTextureSlotCount> indices = materialSlotTextures(m);
        for (size_t k = 0; k < kMaterialTextureSlotCount; ++k)
            if (indices[k] >= 0 && uint32_t(indices[k]) < textureCount) slots[k].push_back(uint32_t(indices[k]));
    }
    for (std::vector<uint32_t>& s : slots) {
        std::sort(s.begin(), s.end());
        s.erase(std::unique(s.begin(), s.end()), s.end());
    }
    return slots;
}

std::vector<gpu::GpuLight> packLights(const Scene& scene) {
    std::vector<gpu::GpuLight> out;
    for (const Light& l : scene.lights) {
        gpu::GpuLight g{};
        g.positionType = glm::vec4(l.position, float(int(l.type)));
        g.directionRange = glm::vec4(glm::normalize(l.direction), l.range);
        g.colorIntensity = glm::vec4(l.color, l.intensity);
        // KHR_lights_punctual's smooth cone attenuation (its README, "Inner and Outer Cone Angles"):
        // scale = 1 / max(0.001, cos(inner) - cos(outer)), offset = -cos(outer) * scale.
        const float scale = 1.0f / std::max(0.001f, std::cos(l.innerConeAngle) - std::cos(l.outerConeAngle));
        g.spotCone = glm::vec4(scale, -std::cos(l.outerConeAngle) * scale, 0.0f, 0.0f);
        out.push_back(g);
    }
    return out;
}

GpuScene uploadScene(const VulkanContext& ctx, const Scene& scene) {
    GpuScene g;
    for (const Material& m : scene.materials) g.materialStencilValues.push_back(m.stencilValues);
    const SceneShaderFeatures features = sceneShaderFeatures(scene);
    g.layers = features.layers;
    g.uvTransforms = features.uvTransforms;
    g.vertices = createBufferWithData(ctx, scene.vertices.data(), scene.vertices.size() * sizeof(Vertex),
                                      VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    g.indices = createBufferWithData(ctx, scene.indices.data(), scene.indices.size() * sizeof(uint32_t),
                                     VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const auto materials = packMaterials(scene);
    g.materials = createBufferWithData(ctx, materials.data(), materials.size() * sizeof(gpu::GpuMaterial),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    auto lights = packLights(scene);
    g.lightCount = uint32_t(lights.size());
    if (lights.empty()) lights.push_back(gpu::GpuLight{});
    g.lights = createBufferWithData(ctx, lights.data(), lights.size() * sizeof(gpu::GpuLight),
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

    auto addTexture = [&](int w, int h, const uint8_t* rgba, bool srgb) {
        ImageDesc d;
        // sRGB texels decoded exactly on the host (srgb_texels.h: lavapipe's _SRGB decode is up to
        // 2.6 % off), as half floats.
        d.format = srgb ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R8G8B8A8_UNORM;
        d.width = uint32_t(w);
        d.height = uint32_t(h);
        d.mipLevels = mipCountFor(d.width, d.height);
        d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        GpuImage img = createImage(ctx, d);
        if (srgb) {
            const std::vector<uint16_t> linear = decodeSrgbTexels(rgba, size_t(w) * size_t(h));
            uploadTextureWithMips(ctx, img, reinterpret_cast<const uint8_t*>(linear.data()));
        } else {
            uploadTextureWithMips(ctx, img, rgba);  // blits, or on a CPU device their stored result
        }
        g.textures.push_back(img);
    };
    for (const Texture& t : scene.textures) addTexture(t.width, t.height, t.rgba.data(), t.srgb);
    if (g.textures.empty()) {
        const uint8_t white[4] = {255, 255, 255, 255};
        addTexture(1, 1, white, false);
    }
    g.texturesBySlot = materialTextureSlots(materials, uint32_t(g.textures.size()));
    // Trilinear, no anisotropy: identical for every layout, and anisotropy is an optional feature.
    const bool nearest = scene.textureBaseLevelOnly && scene.textureNearest;
    g.textureSampler = createSampler(ctx, nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR,
                                     VK_SAMPLER_ADDRESS_MODE_REPEAT,
                                     VK_SAMPLER_ADDRESS_MODE_REPEAT, 1.0f,
                                     scene.textureBaseLevelOnly ? 0.0f : VK_LOD_CLAMP_NONE);

    for (const Draw& d : scene.draws) {
        gpu::DrawConstants c{};
        c.model = d.model;
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(d.model)));
        for (int col = 0; col < 3; ++col) c.normalMatrix[col] = glm::vec4(normalMatrix[col], 0.0f);
        c.material = glm::ivec4(std::clamp(d.material, 0, int(materials.size()) - 1), int(g.draws.size()),
                                int(d.firstIndex), d.vertexOffset);
        g.draws.push_back(c);
        g.drawRanges.push_back(d);
    }
    if (g.draws.empty()) g.draws.push_back(gpu::DrawConstants{});  // the binding is never empty
    g.drawTable = createBufferWithData(ctx, g.draws.data(), g.draws.size() * sizeof(gpu::DrawConstants),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (scene.draws.empty()) g.draws.clear();
    return g;
}

void destroyGpuScene(const VulkanContext& ctx, GpuScene& g) {
    destroyBuffer(ctx, g.vertices);
    destroyBuffer(ctx, g.indices);
    destroyBuffer(ctx, g.materials);
    destroyBuffer(ctx, g.lights);
    destroyBuffer(ctx, g.drawTable);
    for (auto& t : g.textures) destroyImage(ctx, t);
    g.textures.clear();
    if (g.textureSampler) vkDestroySampler(ctx.device, g.textureSampler, nullptr);
    g.textureSampler = VK_NULL_HANDLE;
}

}  // namespace gbl
