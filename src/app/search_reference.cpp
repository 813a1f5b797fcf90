#include "search_reference.h"

#include <algorithm>
#include <optional>
#include <regex>

#include "cpu_codec.h"
#include "file_io.h"
#include "layout_catalog.h"
#include "wiring_codegen.h"

namespace gbl {

namespace {

glm::vec3 pixel3(const Image& img, size_t i) {
    return {img.pixels[i * size_t(img.channels)], img.pixels[i * size_t(img.channels) + 1],
            img.pixels[i * size_t(img.channels) + 2]};
}

std::vector<Surface> surfacesOf(const SurfaceImages& s, size_t n) {
    std::vector<Surface> out(n);
    for (size_t i = 0; i < n; ++i) {
        Surface& p = out[i];
        p.normal = pixel3(s.normal, i);
        p.baseColor = pixel3(s.baseColor, i);
        p.diffuseColor = pixel3(s.diffuseColor, i);
        p.specularColor = pixel3(s.specularColor, i);
        p.roughness = s.roughness.pixels[i];
        p.metallic = s.metallic.pixels[i];
        p.occlusion = s.occlusion.pixels[i];
        p.emissive = pixel3(s.emissive, i);
        // UE4's scalar specular is not in the decoded images: recovered from F0 where the
        // surface is a dielectric (F0 = 0.08 specular), UE4's default 0.5 elsewhere.
        const float f0 = (p.specularColor.x + p.specularColor.y + p.specularColor.z) / 3.0f;
        p.specular = p.metallic < 0.5f ? std::clamp(f0 / 0.08f, 0.0f, 1.0f) : 0.5f;
    }
    return out;
}

// The reference layout with only its [depth] format and direction changed.
Layout referenceWithDepth(const Layout& reference, const DepthKey& key) {
    std::string text = readTextFile(reference.sourceFile);
    text = std::regex_replace(text, std::regex("\n\\[depth\\]\n((?:#[^\n]*\n)*)format = \"[A-Z0-9_]+\"\nreversed_z = (true|false)"),
                              "\n[depth]\n$1format = \"" + key.format + "\"\nreversed_z = " +
                                  (key.reversedZ ? "true" : "false"));
    const Layout l = parseLayout(text, reference.sourceFile);
    if (l.depth.format != key.format || l.depth.reversedZ != key.reversedZ)
        throw std::logic_error("search: could not set the reference's depth to " + key.format);
    return l;
}

RenderSettings referenceSettings(uint32_t width, uint32_t height, const Camera& camera, bool layers) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.specularIbl = IblMode::SplitSum;  // the mode the CPU re-shade models
    settings.decodeSurfaces = true;
    settings.readTargetWords = layers;  // the layers are not in the decoded images: from the words
    settings.camera = camera;
    return settings;
}

// The material layers of the reference's Surfaces (not among the decoded images, which hold the
// attributes compare measures): its float32 words decoded by the CPU codec, exact.
void addLayers(const CpuCodec& codec, const RenderOutput& r, uint32_t width, uint32_t height,
               std::vector<Surface>& surfaces) {
    CpuGBuffer words;
    words.width = int(width);
    words.height = int(height);
    words.targetWords = r.targetWords;
    std::vector<Surface> decoded;
    codec.decode(words, decoded);
    for (size_t i = 0; i < surfaces.size() && i < decoded.size(); ++i) {
        const Surface& d = decoded[i];
        Surface& s = surfaces[i];
        s.coat = d.coat;
        s.coatRoughness = d.coatRoughness;
        s.coatNormal = d.coatNormal;
        s.sheenColor = d.sheenColor;
        s.sheenRoughness = d.sheenRoughness;
        s.anisotropyStrength = d.anisotropyStrength;
        s.anisotropyDirection = d.anisotropyDirection;
    }
}

}  // namespace

SearchReference renderSearchReference(Renderer& renderer, const std::vector<Camera>& cameras, uint32_t width,
                                      uint32_t height, const std::vector<DepthKey>& variants) {
    const Layout reference = loadReferenceLayout(renderer.sceneLayers());
    const GBufferWiring wiring = generateWiring(reference);
    std::vector<std::pair<DepthKey, GBufferWiring>> variantWirings;
    for (const DepthKey& key : variants)
        if (!(key.format == reference.depth.format && key.reversedZ == reference.depth.reversedZ))
            variantWirings.emplace_back(key, generateWiring(referenceWithDepth(reference, key)));
    SearchReference out;
    const size_t n = size_t(width) * height;
    // A scene with layers: the re-shade lights them, so the reference's Surfaces carry them.
    const bool layers = renderer.sceneLayers() != 0;
    std::optional<CpuCodec> codec;
    if (layers) codec.emplace(reference);
    for (const Camera& camera : cameras) {
        RenderOutput r = renderer.render(wiring, referenceSettings(width, height, camera, layers));
        const SurfaceImages& s = r.surfaces;
        search::EvalView v;
        v.shade.width = int(width);
        v.shade.height = int(height);
        v.shade.cameraPosition = camera.position;
        v.shade.covered = s.coverage;
        v.shade.background = r.hdr;
        v.depth = r.depth;
        v.depthReversedZ = reference.depth.reversedZ;
        const CameraMatrices m = computeCameraMatrices(camera, float(width) / float(height), reference.depth.reversedZ);
        v.view = m.view;
        v.invViewProj = m.invViewProj;
        v.reference = surfacesOf(s, n);
        if (codec) addLayers(*codec, r, width, height, v.reference);
        for (const auto& [key, variantWiring] : variantWirings) {
            RenderOutput rv = renderer.render(variantWiring, referenceSettings(width, height, camera, layers));
            search::DepthVariant d;
            d.format = key.format;
            d.reversedZ = key.reversedZ;
            d.surfaces = surfacesOf(rv.surfaces, n);
            if (codec) addLayers(*codec, rv, width, height, d.surfaces);
            d.covered = rv.surfaces.coverage;
            d.depth = std::move(rv.depth);
            d.invViewProj = computeCameraMatrices(camera, float(width) / float(height), key.reversedZ).invViewProj;
            v.depthVariants.push_back(std::move(d));
        }
        out.gpuHdr.push_back(std::move(r.hdr));
        out.views.push_back(std::move(v));
    }
    return out;
}

}  // namespace gbl
