#include "tile_memory.h"

#include "bandwidth.h"

namespace gbl {

const std::vector<TileFamily>& tileFamilies() {
    static const std::vector<TileFamily> families = {
        {"apple-a7", "Apple A7 (GPU family 1)", 16, 4, true,
         "Apple, Understanding Color-Renderable Pixel Format Sizes, Table 1: A7, four targets, 128 bits per pixel"},
        {"apple-a8-a10", "Apple A8, A9, A10 (GPU families 2, 3)", 32, 8, true,
         "Apple, Understanding Color-Renderable Pixel Format Sizes, Table 1: A8-A10, eight targets, 256 bits per pixel"},
        {"apple-a11", "Apple A11 (GPU family 4)", 64, 8, true,
         "Apple, Understanding Color-Renderable Pixel Format Sizes, Table 1: A11, eight targets, 512 bits per pixel"},
        {"mali-t760+", "Arm Mali since T760 (full-rate tile storage)", 16, 0, false,
         "Arm community forum, Multiple render targets and tilebuffer (answer 28891): at most 128 bits per pixel for "
         "the best tile pipelining; more works, more slowly"},
    };
    return families;
}

std::vector<TileFit> tileFits(const Layout& layout, int litOutputBytesPerPixel) {
    int bytes = litOutputBytesPerPixel, targets = 1;
    if (layout.pipeline == Pipeline::VisibilityBuffer) {
        bytes += layout.ids.bytes();
        targets += 1;
    } else {
        for (const Target& t : layout.targets) bytes += t.bytes();
        targets += int(layout.targets.size());
    }
    if (layout.pipeline == Pipeline::DeferredLighting) {
        bytes += lightBufferBytesPerPixel(layout);
        targets += int(layout.lightBuffers.size());
    }
    std::vector<TileFit> fits;
    for (const TileFamily& f : tileFamilies()) {
        TileFit fit;
        fit.family = f.id;
        fit.colourBytesPerPixel = bytes;
        fit.colourTargets = targets;
        fit.limitBytesPerPixel = f.colourBytesPerPixel;
        fit.fits = bytes <= f.colourBytesPerPixel && (f.maxColourTargets == 0 || targets <= f.maxColourTargets);
        if (!fit.fits) fit.overflow = f.hardLimit ? "spill" : "slower";
        fits.push_back(fit);
    }
    return fits;
}

}  // namespace gbl
