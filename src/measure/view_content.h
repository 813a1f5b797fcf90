#pragma once
// A view with nothing to measure. Every metric of compare compares a layout with the reference
// over what the view shows; when it shows nothing a layout can change, each layout's image equals
// the reference's and reads as PSNR inf, FLIP 0: a perfect score that nothing measured. Such a
// view is left out of every mean and rank, and said so (compare.md, "Views with nothing to
// measure").
#include <string>

#include "image.h"

namespace gbl {

// Why the view whose reference render is `referenceHdr` (RGBA, A = coverage) has nothing to
// measure at `exposure`, or "" when it has something:
//   - no pixel is covered by geometry (coverage 0: the camera sees only the environment, which
//     every layout draws alike);
//   - the tone-mapped 8-bit reference holds no value between black and white: every colour sample
//     is 0 or 255 (an exposure, or an environment, that clips the whole view), where no layout's
//     error can show.
// The sentence names the cause and the exposure, e.g. "the reference tone-maps to all black at
// exposure 1e-30".
std::string nothingToMeasure(const Image& referenceHdr, float exposure);

}  // namespace gbl
