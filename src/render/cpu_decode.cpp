#include "cpu_decode.h"

#include <algorithm>
#include <cmath>

#include "layout.h"
#include "normal_space.h"
#include "parallel_for.h"

namespace gbl {

namespace {

// Rows a thread decodes at once: the band's Surfaces (88 bytes per pixel, 168 KiB at 1920 wide)
// stay in its cache between the codec writing them and the planes reading them.
constexpr int kRowsPerBand = 1;

// decode_pass.comp.glsl's view depth, in the same float steps: from the depth value and the
// projection alone (see there why not through world space).
float viewDepthAt(const gpu::FrameConstants& frame, float depth) {
    const glm::mat4& p = frame.proj;
    return (depth * p[3][3] - p[3][2]) / (depth * p[2][3] - p[2][2]);
}

}  // namespace

SurfaceImages decodeSurfacesOnCpu(const CpuCodec& codec, CpuGBuffer& words, const std::vector<float>& depth,
                                  const gpu::FrameConstants& frame, int normalSpace, VkFormat depthFormat,
                                  bool storesDepth, bool layers) {
    const int w = words.width, h = words.height;
    const size_t pixels = size_t(w) * size_t(h);
    const float clearDepth = frame.shading.y;
    words.covered.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) words.covered[i] = depth[i] != clearDepth;

    SurfaceImages s;
    s.normal = Image(w, h, 3);
    s.baseColor = Image(w, h, 3);
    s.diffuseColor = Image(w, h, 3);
    s.specularColor = Image(w, h, 3);
    s.emissive = Image(w, h, 3);
    s.roughness = Image(w, h, 1);
    s.metallic = Image(w, h, 1);
    s.occlusion = Image(w, h, 1);
    s.viewDepth = Image(w, h, 1);
    s.depth = Image(w, h, 1);
    std::copy(depth.begin(), depth.end(), s.depth.pixels.begin());
    s.coverage = words.covered;
    if (layers) s.allocateLayers(w, h);

    const StoredSpace space = StoredSpace(normalSpace);
    // The depth as the decode pass's texelFetch sees it. A 24-bit UNORM depth reads back here as
    // the correctly rounded v / (2^24 - 1) (renderer.cpp), but llvmpipe's sampler converts it as
    // float(v) times the rounded reciprocal (gallivm's unsigned-normalised-to-float for widths
    // beyond the float mantissa), an ulp off at times: near the far plane one ulp of depth is
    // tens of ulps of view depth. v is recovered exactly: the read-back value is within half an
    // ulp, under half a step of 1 / (2^24 - 1) in v.
    const bool unorm24 = depthFormat == VK_FORMAT_D24_UNORM_S8_UINT || depthFormat == VK_FORMAT_X8_D24_UNORM_PACK32;
    auto sampled = [&](float d) {
        if (!unorm24) return d;
        return float(std::nearbyint(double(d) * 16777215.0)) * (1.0f / 16777215.0f);
    };
    const glm::mat4 view = frame.view;
    const int bands = (h + kRowsPerBand - 1) / kRowsPerBand;
    parallelFor(bands, 0, [&](int64_t b0, int64_t b1) {
        std::vector<Surface> band(size_t(w) * kRowsPerBand);
        for (int64_t b = b0; b < b1; ++b) {
            const int y0 = int(b) * kRowsPerBand, y1 = std::min(h, y0 + kRowsPerBand);
            codec.decodeRows(words, y0, y1, band.data());
            for (int y = y0; y < y1; ++y)
                for (int x = 0; x < w; ++x) {
                    const size_t i = size_t(y) * size_t(w) + size_t(x);
                    if (!words.covered[i]) continue;  // the planes' zeros, as the decode pass writes
                    const Surface& d = band[size_t(y - y0) * size_t(w) + size_t(x)];
                    const glm::vec3 n = directionFromStored(d.normal, space, view);
                    const glm::vec3* rgb[5] = {&n, &d.baseColor, &d.diffuseColor, &d.specularColor, &d.emissive};
                    Image* planes[5] = {&s.normal, &s.baseColor, &s.diffuseColor, &s.specularColor, &s.emissive};
                    for (int p = 0; p < 5; ++p)
                        for (int c = 0; c < 3; ++c) planes[p]->pixels[i * 3 + size_t(c)] = (*rgb[p])[c];
                    s.roughness.pixels[i] = d.roughness;
                    s.metallic.pixels[i] = d.metallic;
                    s.occlusion.pixels[i] = d.occlusion;
                    // A layout's stored window depth is the one its lighting reads (decode_pass).
                    s.viewDepth.pixels[i] = viewDepthAt(frame, storesDepth ? d.position.z : sampled(depth[i]));
                    if (!layers) continue;
                    // decode_pass.comp.glsl's layer vec4s (gblSurfaceFromStored turns both directions).
                    const glm::vec3 coatN = directionFromStored(d.coatNormal, space, view);
                    const glm::vec3 tangent = directionFromStored(d.anisotropyDirection, space, view);
                    for (int c = 0; c < 3; ++c) {
                        s.coatNormal.pixels[i * 3 + size_t(c)] = coatN[c];
                        s.sheenColor.pixels[i * 3 + size_t(c)] = d.sheenColor[c];
                        s.anisotropyDirection.pixels[i * 3 + size_t(c)] = tangent[c];
                    }
                    s.coat.pixels[i] = d.coat;
                    s.coatRoughness.pixels[i] = d.coatRoughness;
                    s.sheenRoughness.pixels[i] = d.sheenRoughness;
                    s.anisotropyStrength.pixels[i] = d.anisotropyStrength;
                }
        }
    });
    return s;
}

}  // namespace gbl
