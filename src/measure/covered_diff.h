#pragma once
// Two renders of one frame by two renderers, compared where both drew geometry: issue 45's
// cross-check of the float reference against the Khronos glTF Sample Viewer
// (scripts/crosscheck.sh, docs/crosscheck.md). Background pixels are left out: the two renderers
// clear to different colours, and a silhouette pixel one covers and the other does not is counted
// (onlyReference / onlyTest), not measured.
//
// Over the N covered pixels, colour channels c of reference r and test t (linear):
//   meanLuminance   mean over covered pixels of the reference's luminance Y (Rec. 709 weights)
//   meanTestLuminance  the same of the test
//   rmse            sqrt(sum (t - r)^2 / 3N)
//   relativeRmse    rmse / meanLuminance  (the error as a fraction of the image's mean level)
//   maxAbs          max |t - r|
//   maxRelative     max over covered pixels of max_c |t - r| / max(Y_r, 0.01 meanLuminance): the
//                   worst pixel against its own level (the floor keeps black pixels finite)
//   beyond          covered pixels whose max_c |t - r| > tolerance max(Y_r, 0.01 meanLuminance)
//   flip            HDR-FLIP (flip.h) of the two images with the uncovered pixels set to 0 in
//                   both, its mean and max over the covered pixels only.
#include <cstdint>
#include <string>
#include <vector>

#include "flip.h"
#include "image.h"

namespace gbl {

// A binary PGM (P5, maxval 255, rows top to bottom) as a 0/1 mask, width x height; a file of
// another size or kind is a UserError naming it.
std::vector<uint8_t> readCoverageMask(const std::string& path, int width, int height);

struct CoveredDiff {
    size_t covered = 0, onlyReference = 0, onlyTest = 0, beyond = 0;
    double tolerance = 0.0;
    double meanTestLuminance = 0.0;  // the test's, over the same pixels: a uniform scale shows here
    double meanLuminance = 0.0, rmse = 0.0, relativeRmse = 0.0, maxAbs = 0.0, maxRelative = 0.0;
    int worstX = -1, worstY = -1;  // the maxRelative pixel
    FlipStats flip;
    Image error;     // per pixel max_c |t - r| / max(Y_r, 0.01 meanLuminance) (0 where uncovered)
    Image flipMap;   // FLIP, 0 where uncovered
    std::vector<uint8_t> beyondMask;  // 1 where beyond
};

// The relative RMSE of the two images' means over box x box blocks that both masks cover whole:
// what is left of the difference once detail finer than the block is averaged away. A texture
// filtering difference (another mip, another filter footprint) moves a pixel about its
// neighbourhood's mean and shrinks under the average; a shading difference (a BRDF term, a light
// unit, a colour-space step) does not. Also returns the blocks counted.
double boxedRelativeRmse(const Image& reference, const Image& test, const std::vector<uint8_t>& referenceMask,
                         const std::vector<uint8_t>& testMask, int box, size_t* blocks = nullptr);

// reference, test: 3 or 4 channels (alpha ignored), the same size; masks 0/1 of that size.
CoveredDiff coveredDiff(const Image& reference, const Image& test, const std::vector<uint8_t>& referenceMask,
                        const std::vector<uint8_t>& testMask, double tolerance);

}  // namespace gbl
