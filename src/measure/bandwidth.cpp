#include "bandwidth.h"

namespace gbl {

FrameTraffic computeFrameTraffic(const Layout& layout, uint32_t width, uint32_t height, int samples) {
    FrameTraffic f;
    f.width = width;
    f.height = height;
    f.samples = samples;
    const double pixels = double(width) * double(height);
    double targetBytes = 0;
    for (const Target& t : layout.targets) targetBytes += t.bytes();
    targetBytes += layout.ids.bytes();  // a visibility buffer's one target
    const double depthBytes = depthAttachmentBytes(layout);  // none where depth is in the ids
    const double perSample = pixels * samples;
    f.geometryWriteBytes = perSample * (targetBytes + depthBytes);
    f.lightingReadBytes = perSample * (targetBytes + depthBytes);
    if (layout.pipeline == Pipeline::DeferredLighting) {
        const double lightBytes = lightBufferBytesPerPixel(layout);
        // Light pass writes the light buffers; material pass reads them and re-tests depth.
        f.lightBufferBytes = perSample * (lightBytes + lightBytes + depthBytes);
    }
    if (layout.pipeline == Pipeline::VisibilityBuffer) {
        // With clusters the resolve also reads the cluster's (draw, first triangle) entry.
        f.vertexFetchBytes = pixels * (kVisibilityVertexBytes + (layout.ids.clusterTriangles ? kVisibilityClusterBytes : 0));
        f.textureFetchBytes = pixels * kVisibilityTextureBytes;
    }
    f.totalBytes = f.geometryWriteBytes + f.lightingReadBytes + f.lightBufferBytes + f.vertexFetchBytes;
    f.litOutputBytes = pixels * kLitOutputBytesPerPixel;  // resolved once, whatever the MSAA
    f.onChipExternalBytes = f.litOutputBytes;
    return f;
}

BandwidthReport computeBandwidth(const Layout& layout, uint32_t width, uint32_t height) {
    BandwidthReport r;
    for (const Target& t : layout.targets) {
        r.targets.push_back({t.name, t.format, t.bytes()});
        r.targetBytesPerPixel += t.bytes();
    }
    if (layout.pipeline == Pipeline::VisibilityBuffer) {
        r.targets.push_back({"ids", layout.ids.format, layout.ids.bytes()});
        r.targetBytesPerPixel += layout.ids.bytes();
        r.visibilityBuffer = true;
    }
    r.depthBytesPerPixel = depthAttachmentBytes(layout);
    r.lightBufferBytesPerPixel = lightBufferBytesPerPixel(layout);
    r.gbufferBytesPerPixel = r.targetBytesPerPixel + r.depthBytesPerPixel;
    r.deferredLighting = layout.pipeline == Pipeline::DeferredLighting;
    const std::pair<uint32_t, uint32_t> sizes[] = {{width, height}, {1920, 1080}, {3840, 2160}};
    for (const auto& [w, h] : sizes)
        for (int samples : {1, 2, 4}) r.frames.push_back(computeFrameTraffic(layout, w, h, samples));
    return r;
}

}  // namespace gbl
