#pragma once
// Zoomed crops of the worst regions of a run: the windows of an error map with the highest mean
// error, and their reference / test / heat-map crops as PNGs for the report.
#include <filesystem>
#include <string>
#include <vector>

#include "image.h"

namespace gbl {

struct Crop {
    int x = 0, y = 0;        // top-left corner, pixels
    int size = 0;            // width = height, pixels
    double meanError = 0.0;  // mean of the error map over the window
};

// The `count` non-overlapping cropSize x cropSize windows of channel 0 of `errorMap` with the
// highest mean error, highest first. Window sums come from a summed-area table (double); the
// windows are chosen greedily: the best window, then the best window that overlaps none chosen,
// and so on (ties: the first in row-major order). The crop size is clamped to the image; NaN
// counts as 0; windows with mean <= 0 are not returned (an error-free run has no crops).
std::vector<Crop> findWorstRegions(const Image& errorMap, int cropSize, int count);

struct CropFiles {
    std::string reference, test, heat;  // paths relative to dir
};

// The files writeCrops writes for crop i (known before they are written: compare queues them).
CropFiles cropFileNames(const std::string& prefix, size_t i);

// For each crop, <prefix>crop<i>_reference.png, _test.png and _heat.png: the crop of each picture
// upscaled `scale` times with nearest-neighbour (sharp pixels). The three images must have the
// size the crops were found on (heat: the colour-mapped error map, e.g. applyColorMap's).
std::vector<CropFiles> writeCrops(const std::filesystem::path& dir, const std::string& prefix,
                                  const std::vector<Crop>& crops, const Image8& reference, const Image8& test,
                                  const Image8& heat, int scale = 4);

// The crop of `image` at `crop`, upscaled `scale` times, nearest-neighbour.
Image8 cropUpscaled(const Image8& image, const Crop& crop, int scale);

}  // namespace gbl
