#include "view_content.h"

#include <cstdio>

#include "tone_map.h"

namespace gbl {

std::string nothingToMeasure(const Image& referenceHdr, float exposure) {
    const size_t n = referenceHdr.pixelCount();
    if (n == 0) return "the view has no pixels";
    if (referenceHdr.channels == 4) {
        bool covered = false;
        for (size_t i = 0; i < n && !covered; ++i) covered = referenceHdr.pixels[i * 4 + 3] >= 0.5f;
        if (!covered) return "the camera sees no geometry (coverage 0), only the environment, which every layout draws alike";
    }
    const Image8 ldr = toneMapToSrgb8(referenceHdr, exposure);
    const int colour = ldr.channels >= 3 ? 3 : 1;
    bool black = false, white = false;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < colour; ++c) {
            const unsigned char v = ldr.pixels[i * size_t(ldr.channels) + size_t(c)];
            if (v != 0 && v != 255) return "";
            (v == 0 ? black : white) = true;
        }
    char at[64];
    std::snprintf(at, sizeof at, "%g", double(exposure));
    const std::string what = black && white ? "only black and white (every value clipped)" : black ? "all black" : "all white";
    return "the reference tone-maps to " + what + " at exposure " + at +
           ", where no layout's error can show (check the exposure and the environment's brightness)";
}

}  // namespace gbl
