#include "search_reference.h"

#include <algorithm>

#include "layout_catalog.h"
#include "wiring_codegen.h"

namespace gbl {

namespace {

glm::vec3 pixel3(const Image& img, size_t i) {
    return {img.pixels[i * size_t(img.channels)], img.pixels[i * size_t(img.channels) + 1],
            img.pixels[i * size_t(img.channels) + 2]};
}

}  // namespace

SearchReference renderSearchReference(Renderer& renderer, const std::vector<Camera>& cameras, uint32_t width,
                                      uint32_t height) {
    const Layout reference = loadLayout("reference");
    const GBufferWiring wiring = generateWiring(reference);
    SearchReference out;
    for (const Camera& camera : cameras) {
        RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.specularIbl = IblMode::SplitSum;  // the mode the CPU re-shade models
        settings.decodeSurfaces = true;
        settings.readTargetWords = false;
        settings.camera = camera;
        RenderOutput r = renderer.render(wiring, settings);
        const SurfaceImages& s = r.surfaces;
        search::EvalView v;
        v.shade.width = int(width);
        v.shade.height = int(height);
        v.shade.cameraPosition = camera.position;
        v.shade.covered = s.coverage;
        v.shade.background = r.hdr;
        v.depth = r.depth;
        const CameraMatrices m = computeCameraMatrices(camera, float(width) / float(height), reference.depth.reversedZ);
        v.view = m.view;
        v.invViewProj = m.invViewProj;
        const size_t n = size_t(width) * height;
        v.reference.resize(n);
        for (size_t i = 0; i < n; ++i) {
            Surface& p = v.reference[i];
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
        out.gpuHdr.push_back(std::move(r.hdr));
        out.views.push_back(std::move(v));
    }
    return out;
}

}  // namespace gbl
