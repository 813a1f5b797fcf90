#include "image_diff.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "error.h"
#include "image_io.h"
#include "metrics.h"

namespace gbl {

namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

const char* kindName(DiffKind k) { return k == DiffKind::Ldr ? "8-bit sRGB (PNG/JPEG)" : "HDR float (EXR/HDR)"; }

}  // namespace

DiffInput readDiffInput(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (!std::filesystem::exists(path)) throwUserError(path + ": no such file");
    DiffInput in;
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") {
        const Image8 img = readImage8(path);
        in.kind = DiffKind::Ldr;
        in.fileChannels = img.channels;
        const int colour = img.channels >= 3 ? 3 : 1;  // grey(+alpha) -> 1, RGB(A) -> 3
        in.image = Image(img.width, img.height, colour);
        for (size_t p = 0; p < in.image.pixelCount(); ++p)
            for (int c = 0; c < colour; ++c)
                in.image.pixels[p * colour + c] = float(img.pixels[p * img.channels + c]) / 255.0f;
        return in;
    }
    if (ext == ".exr") {
        const std::vector<std::string> names = readExrChannelNames(path);
        in.kind = DiffKind::Hdr;
        in.fileChannels = int(names.size());
        const bool rgb = std::count(names.begin(), names.end(), "R") && std::count(names.begin(), names.end(), "G") &&
                         std::count(names.begin(), names.end(), "B");
        const bool grey = !rgb && std::count(names.begin(), names.end(), "Y") &&
                          !std::count(names.begin(), names.end(), "RY");
        if (grey) {
            in.image = readExrChannels(path, {"Y"});
        } else {
            in.image = readExr(path);  // names the file when it has neither R,G,B nor Y
        }
        return in;
    }
    if (ext == ".hdr") {
        in.kind = DiffKind::Hdr;
        in.image = readHdr(path);
        in.fileChannels = 3;
        return in;
    }
    throwUserError(path + ": unknown image type '" + ext + "'; give a .png, .jpg, .exr or .hdr file");
}

DiffResult diffImages(const DiffInput& reference, const DiffInput& test, const std::string& referencePath,
                      const std::string& testPath, const DiffOptions& options) {
    if (reference.kind != test.kind)
        throwUserError(testPath + ": is " + kindName(test.kind) + " but the reference " + referencePath + " is " +
                       kindName(reference.kind) + "; compare like with like (PNG with PNG, EXR with EXR)");
    const Image& r = reference.image;
    const Image& t = test.image;
    if (r.width != t.width || r.height != t.height)
        throwUserError(testPath + ": is " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                       " but the reference " + referencePath + " is " + std::to_string(r.width) + "x" +
                       std::to_string(r.height) + "; give images of the same size");
    if (reference.fileChannels != test.fileChannels || r.channels != t.channels)
        throwUserError(testPath + ": has " + std::to_string(test.fileChannels) + " channels but the reference " +
                       referencePath + " has " + std::to_string(reference.fileChannels) +
                       "; give images with the same channels");
    if (reference.kind == DiffKind::Hdr &&
        (options.startExposure.has_value() != options.stopExposure.has_value()))
        throwUserError("gbufferlab diff: give both --start-exposure and --stop-exposure, or neither");

    DiffResult out;
    out.kind = reference.kind;
    out.width = r.width;
    out.height = r.height;
    out.channels = r.channels;
    const PsnrPeak peak = reference.kind == DiffKind::Ldr ? PsnrPeak::One : PsnrPeak::ReferenceMax;
    const ImageErrorStats e = imageErrorStats(r, t, nullptr, peak);
    out.rmse = e.rmse;
    out.psnrDb = e.psnr;
    out.peak = e.peak;
    out.maxAbs = e.maxAbs;
    if (reference.kind == DiffKind::Ldr) {
        out.flipMap = flipLdr(r, t, options.pixelsPerDegree);
    } else {
        FlipExposureRange range{0.0f, 0.0f, 0};  // count 0: from the reference
        if (options.startExposure || options.numExposures) {
            range = flipExposureRange(r);
            if (options.startExposure) {
                range.start = *options.startExposure;
                range.stop = *options.stopExposure;
                if (!(range.stop >= range.start))
                    throwUserError("gbufferlab diff: --stop-exposure " + std::to_string(range.stop) +
                                   " is below --start-exposure " + std::to_string(range.start));
            }
            // NVIDIA's tool: N = max(2, ceil(stop - start)) unless given.
            range.count = options.numExposures ? *options.numExposures
                                               : std::max(2, int(std::ceil(range.stop - range.start)));
        }
        HdrFlipResult h = flipHdr(r, t, options.pixelsPerDegree, range);
        out.flipMap = std::move(h.flip);
        out.exposures = h.range;
    }
    out.flip = flipStats(out.flipMap);
    return out;
}

}  // namespace gbl
