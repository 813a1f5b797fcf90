#pragma once
// `gbufferlab diff`: one test image against one reference image, the way pbrt-v4's `imgtool diff`
// and NVIDIA's FLIP tool compare files.
//
// Inputs are read by extension and keep their kind:
//   .png / .jpg / .jpeg  LDR: sRGB-encoded, at the file's precision: 8 bits (v / 255) or, for a
//                        16-bit PNG, 16 bits (v / 65535); values in [0, 1]. A 16-bit pair is
//                        compared at 16 bits (never rounded to 8), an 8-bit file with a 16-bit
//                        one each at its own; DiffInput::bitsPerSample says which.
//   .exr / .hdr          HDR: linear RGB float (EXR: R,G,B or Y; A is not compared).
// Reference and test must be the same kind, width, height and channel count (else UserError
// naming the test file).
//
// Metrics, over every pixel and the colour channels (RGB; a grey image its one channel; alpha
// never):
//   rmse, max_abs        of test - reference, in the file's values (LDR: encoded / 255; HDR: linear).
//   psnr_db              10 log10(peak^2 / MSE); peak 1 for LDR, the reference's largest colour
//                        value for HDR (as report.json's psnr_linear_db); +inf when identical.
//   flip_*               LDR: LDR-FLIP of the two sRGB images [Andersson et al. 2020].
//                        HDR: HDR-FLIP [Andersson et al. 2021] over exposures start..stop (from the
//                        reference unless given), as NVIDIA's tool: --start-exposure,
//                        --stop-exposure, --num-exposures.
// The error map is the FLIP map.
//
// Non-finite pixels (NaN, +-inf: only an EXR can hold them) are refused, never dropped: a
// UserError names the file, the first such pixel in row order, its channel and value, and how
// many there are. A metric that skipped them would disagree with one that clamps them (FLIP
// reads NaN as 0), so no number is given for such a pair.
//
// Memory: diffMemoryBytes is the peak, from the headers alone; a pair beyond the budget
// (memory_budget.h) is refused before a pixel is decoded.
#include <optional>
#include <string>

#include "flip.h"
#include "image.h"
#include "image_io.h"

namespace gbl {

enum class DiffKind { Ldr, Hdr };

struct DiffInput {
    DiffKind kind = DiffKind::Ldr;
    Image image;        // LDR: sRGB-encoded [0,1]; HDR: linear. Colour channels only (1 or 3).
    int fileChannels = 0;  // channels in the file (alpha included), for the like-for-like check
    // The format stores no alpha (PFM: 1 or 3 channels). Its colour channels are then compared
    // with the other file's whatever alpha that one has: an RGBA EXR reference (compare's, alpha =
    // coverage) against the glTF Sample Viewer's RGB PFM (tools/gltf-viewer) is like for like.
    bool formatHasNoAlpha = false;
    int bitsPerSample = 0;  // LDR: 8 or 16, the precision its values keep; HDR: 0 (float)
};
// How precise the numbers of a pair are: "8-bit", "16-bit", "8-bit reference, 16-bit test" (LDR),
// "float" (HDR).
std::string diffPrecision(const DiffInput& reference, const DiffInput& test);

// Reads one input; bad files (unreadable, unknown extension) are a UserError naming the file.
DiffInput readDiffInput(const std::string& path);

// The peak memory of reading a pair of images of this size and kind and diffing them, in
// bytes. Per pixel, with c colour channels (1 or 3): the two float inputs 8c; LDR-FLIP's
// scratch planes 28, linear planes 12, the two prepared images 40 and the map 4 (LDR: 84 + 8c);
// HDR-FLIP's two sets of tone-mapped planes 24, scratch 28, prepared images 40, the running
// maximum 4 and the map and exposure map 8 (HDR: 104 + 8c). 10 % on top for the allocator and
// the filters' rows, and 64 MiB for the program. Measured (peak resident memory, /usr/bin/time -v,
// commit dff3d2c's diff): a 4096x4096 LDR pair 1737 MiB, estimated 1965; diff_bounds_cli_test
// holds a 2048x2048 pair below its estimate.
double diffMemoryBytes(const ImageFileInfo& reference, const ImageFileInfo& test);

// Throws a UserError naming `path`, the first non-finite value's pixel and channel, and their
// count, if the image holds any.
void requireFinite(const Image& image, const std::string& path);

struct DiffOptions {
    double pixelsPerDegree = flipPixelsPerDegree();
    std::optional<float> startExposure, stopExposure;  // HDR only
    std::optional<int> numExposures;                    // HDR only
};

struct DiffResult {
    DiffKind kind = DiffKind::Ldr;
    int width = 0, height = 0, channels = 0;
    double rmse = 0.0, psnrDb = 0.0, peak = 1.0, maxAbs = 0.0;
    FlipStats flip;
    FlipExposureRange exposures;  // HDR only
    Image flipMap;                // 1 channel [0, 1]
};

// Throws UserError (naming testPath) when the two differ in kind, size or channel count.
DiffResult diffImages(const DiffInput& reference, const DiffInput& test, const std::string& referencePath,
                      const std::string& testPath, const DiffOptions& options = {});

}  // namespace gbl
