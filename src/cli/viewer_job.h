#pragma once
// The job file of the Khronos glTF Sample Viewer renderer (tools/gltf-viewer/README.md, "The job
// file"): the camera, punctual lights and exposure a `gbufferlab render` used, so that the viewer
// renders the same frame (issue 45's cross-check, scripts/crosscheck.sh), and the reference's
// coverage mask in the format that tool writes its own.
#include <cstdint>
#include <string>
#include <vector>

#include "image.h"
#include "scene.h"

namespace gbl {

struct ViewerJob {
    std::string gltf;         // absolute path of the model
    uint32_t width = 0, height = 0;
    Camera camera;            // the one rendered (framed for width / height where the scene has none)
    float exposure = 1.0f;
    bool ibl = false;         // false: "ibl": null (punctual lights only)
    std::string environment;  // absolute path of the .hdr (ibl only)
    std::string output;       // the viewer's .pfm, relative to the job file's folder
};

// The job's JSON text: lights from `scene` (world space, KHR_lights_punctual units, as the
// lighting pass reads them), the camera's camera-to-world matrix column-major.
std::string viewerJobJson(const ViewerJob& job, const Scene& scene);

// A binary PGM (P5, maxval 255, rows top to bottom) of the HDR image's alpha: 255 where the
// lighting pass shaded geometry (alpha 1), 0 where it drew the environment (alpha 0) or where
// `excluded` (one byte a pixel, or empty) is non-zero.
void writeCoverageMask(const std::string& path, const Image& hdr, const std::vector<uint8_t>& excluded = {});

}  // namespace gbl
