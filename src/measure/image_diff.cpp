#include "image_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "error.h"
#include "image_io.h"
#include "pfm_io.h"
#include "metrics.h"

namespace gbl {

namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

std::string shortNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

const char* kindName(DiffKind k) { return k == DiffKind::Ldr ? "sRGB (PNG/JPEG)" : "HDR float (EXR/HDR/PFM)"; }

}  // namespace

DiffInput readDiffInput(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (!std::filesystem::exists(path)) throwUserError(path + ": no such file");
    DiffInput in;
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") {
        // At the file's precision: a 16-bit PNG read as 8 bits would lose its low bytes, and two
        // files that differ only there would compare as identical.
        const UnormImage file = readImageUnorm(path);
        const Image& img = file.image;
        in.kind = DiffKind::Ldr;
        in.fileChannels = img.channels;
        in.bitsPerSample = file.bitsPerSample;
        const int colour = img.channels >= 3 ? 3 : 1;  // grey(+alpha) -> 1, RGB(A) -> 3
        in.image = Image(img.width, img.height, colour);
        for (size_t p = 0; p < in.image.pixelCount(); ++p)
            for (int c = 0; c < colour; ++c) in.image.pixels[p * colour + c] = img.pixels[p * img.channels + c];
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
    // A PFM (tools/gltf-viewer's output, the Sample Viewer's frame) is linear float like EXR.
    if (ext == ".pfm") {
        in.kind = DiffKind::Hdr;
        in.image = readPfm(path);
        in.fileChannels = in.image.channels;
        in.formatHasNoAlpha = true;
        return in;
    }
    throwUserError(path + ": unknown image type '" + ext + "'; give a .png, .jpg, .exr, .hdr or .pfm file");
}

std::string diffPrecision(const DiffInput& reference, const DiffInput& test) {
    if (reference.kind == DiffKind::Hdr) return "float";
    if (reference.bitsPerSample == test.bitsPerSample) return std::to_string(reference.bitsPerSample) + "-bit";
    return std::to_string(reference.bitsPerSample) + "-bit reference, " + std::to_string(test.bitsPerSample) +
           "-bit test";
}

double diffMemoryBytes(const ImageFileInfo& reference, const ImageFileInfo& test) {
    const double pixels = std::max(double(reference.width) * double(reference.height),
                                   double(test.width) * double(test.height));
    const int colour = std::max(reference.channels, test.channels) >= 3 ? 3 : 1;
    const double perPixel = (reference.hdr || test.hdr ? 104.0 : 84.0) + 8.0 * colour;
    return pixels * perPixel * 1.1 + double(64 << 20);
}

void requireFinite(const Image& image, const std::string& path) {
    size_t count = 0, first = 0;
    for (size_t i = 0; i < image.pixels.size(); ++i)
        if (!std::isfinite(image.pixels[i]) && count++ == 0) first = i;
    if (count == 0) return;
    const size_t ch = size_t(std::max(image.channels, 1));
    const size_t pixel = first / ch;
    const int x = int(pixel % size_t(image.width)), y = int(pixel / size_t(image.width));
    static const char* rgb[] = {"R", "G", "B", "A"};
    const std::string channel = image.channels == 1 ? "Y" : rgb[std::min<size_t>(first % ch, 3)];
    const float v = image.pixels[first];
    throwUserError(path + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " + channel +
                   " is " + (std::isnan(v) ? "NaN" : v > 0 ? "+inf" : "-inf") + " (" + std::to_string(count) +
                   " non-finite value" + (count == 1 ? "" : "s") + " in all); diff measures finite images only: "
                   "replace them in the file (e.g. with 0) or compare a crop without them");
}

DiffResult diffImages(const DiffInput& reference, const DiffInput& test, const std::string& referencePath,
                      const std::string& testPath, const DiffOptions& options) {
    if (reference.kind != test.kind)
        throwUserError(testPath + ": is " + kindName(test.kind) + " but the reference " + referencePath + " is " +
                       kindName(reference.kind) + "; compare like with like (PNG with PNG, EXR with EXR or PFM)");
    const Image& r = reference.image;
    const Image& t = test.image;
    if (r.width != t.width || r.height != t.height)
        throwUserError(testPath + ": is " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                       " but the reference " + referencePath + " is " + std::to_string(r.width) + "x" +
                       std::to_string(r.height) + "; give images of the same size");
    const bool alphaCounts = !reference.formatHasNoAlpha && !test.formatHasNoAlpha;
    if ((alphaCounts && reference.fileChannels != test.fileChannels) || r.channels != t.channels)
        throwUserError(testPath + ": has " + std::to_string(test.fileChannels) + " channels but the reference " +
                       referencePath + " has " + std::to_string(reference.fileChannels) +
                       "; give images with the same channels");
    if (reference.kind == DiffKind::Hdr &&
        (options.startExposure.has_value() != options.stopExposure.has_value()))
        throwUserError("gbufferlab diff: give both --start-exposure and --stop-exposure, or neither");
    requireFinite(r, referencePath);
    requireFinite(t, testPath);

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
            // NVIDIA's tool: N = max(2, ceil(stop - start)) unless given; counted in double, as
            // hand-given exposures can span more stops than an int holds.
            const double span = std::ceil(double(range.stop) - double(range.start));
            if (!options.numExposures && !(span <= double(kMaxFlipExposures)))
                throwUserError("gbufferlab diff: --start-exposure " + shortNumber(range.start) + " to --stop-exposure " +
                               shortNumber(range.stop) + " spans " + shortNumber(span) +
                               " stops, one HDR-FLIP exposure each, more than " + std::to_string(kMaxFlipExposures) +
                               "; narrow the range or give --num-exposures N");
            range.count = options.numExposures ? *options.numExposures : std::max(2, int(span));
        }
        HdrFlipResult h = flipHdr(r, t, options.pixelsPerDegree, range);
        out.flipMap = std::move(h.flip);
        out.exposures = h.range;
    }
    out.flip = flipStats(out.flipMap);
    return out;
}

}  // namespace gbl
