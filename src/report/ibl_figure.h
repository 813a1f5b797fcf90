#pragma once
// The seed's comparison figure, reproduced: one row per IBL mode (ground truth, split sum with the
// pdf in the shader, split sum with pre-filtering n = v = r, UE4 mobile EnvBRDFApprox, Black Ops 2),
// one column per material ball (the metals, then the dielectrics, roughness rising left to right),
// cropped from each mode's reference render; under each row, its caption: the row's error against
// ground truth per material class (for ground truth, its own estimated noise).
//
// Geometry (so a reader, or a test, can find every tile): a title band of kIblFigureTitleHeight,
// then per row: tiles of tileSize x tileSize at y = rowTop, x = kIblFigureMargin + column *
// (tileSize + kIblFigureTileGap) (+ kIblFigureGroupGap before the first dielectric column), then the
// caption band of captionBandHeight(): text at (kIblFigureMargin, rowTop + tileSize + kIblFigureCaptionPad),
// scale kIblFigureTextScale, colour kIblFigureText, on kIblFigureBackground.
#include <optional>
#include <string>
#include <vector>

#include "color_map.h"
#include "image.h"
#include "report_model.h"

namespace gbl {

constexpr int kIblFigureMargin = 8;
constexpr int kIblFigureTileGap = 2;
constexpr int kIblFigureGroupGap = 12;
constexpr int kIblFigureTextScale = 1;
constexpr int kIblFigureCaptionPad = 4;
constexpr int kIblFigureTitleHeight = 7 * kIblFigureTextScale + 2 * kIblFigureCaptionPad;
constexpr Rgb8 kIblFigureBackground{24, 24, 24};
constexpr Rgb8 kIblFigureText{235, 235, 235};
// What a tile shows outside its ball (the scene around the grid is masked out, as in the seed's figure).
constexpr Rgb8 kIblFigureTileBackdrop{56, 56, 56};
inline int iblFigureCaptionBandHeight() { return 7 * kIblFigureTextScale + 2 * kIblFigureCaptionPad; }

// A material ball in the renders: a square crop, top-left (x, y), side `size` pixels.
struct FigureBall {
    int x = 0, y = 0, size = 0;
    // size x size, row-major over the crop: 1 where the ball covers the crop pixel's centre (the
    // camera ray through it hits the sphere); tile pixels from a 0 show kIblFigureTileBackdrop.
    // Empty: no mask.
    std::vector<unsigned char> mask;
    bool metal = false;
    std::string label;  // "metal r=0.05"
};

struct IblFigureLayout {
    int tileSize = 0;
    int columns = 0, rows = 0;
    int metalColumns = 0;  // the first metalColumns columns are metals
    int width = 0, height = 0;
    int tileX(int column) const;
    int rowTop(int row) const;
};
// Tile side: the largest crop, upscaled by an integer factor to at least 64 pixels.
IblFigureLayout iblFigureLayout(const std::vector<FigureBall>& balls, int rows);

// The caption printed under a row (upper case ASCII the bitmap font draws), from its numbers:
//   "GROUND-TRUTH: NOISE METAL 0.138%, DIELECTRIC 0.004%"
//   "SPLIT-SUM: ERROR METAL 27.277%, DIELECTRIC 1.331%"
std::string iblFigureCaption(const IblFigureRow& row);

// renders[r]: row r's tone-mapped 8-bit render (3 or 4 channels); balls in column order (metals
// first); captions[r] under row r. Crops outside a render are filled with the background.
Image8 composeIblFigure(const std::vector<Image8>& renders, const std::vector<FigureBall>& balls,
                        const std::vector<std::string>& captions, const std::string& title);

}  // namespace gbl
