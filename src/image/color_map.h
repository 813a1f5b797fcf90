#pragma once
// Heat maps: a perceptually uniform colour map (viridis-like) and a readable legend.
//
// The 256-entry table is generated at first use from ten key colours of viridis (van der Walt &
// Smith's matplotlib map, at t = i/9), interpolated linearly in CIELAB (D65) between key
// points, so L* rises monotonically and near-uniformly; entries are sRGB-encoded 8-bit,
// rounded with floor(255 x + 0.5). Entry 0 is (68, 1, 84), entry 255 is (253, 231, 37).
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "image.h"

namespace gbl {

struct Rgb8 {
    uint8_t r = 0, g = 0, b = 0;
};

// The table, index 0 = low.
const std::array<Rgb8, 256>& viridisTable();

// Maps channel 0 of `scalar` to RGB 8-bit: t = (v - lo) / (hi - lo) clamped to [0,1], entry
// floor(255 t + 0.5). When hi <= lo, values > lo map to the top entry and the rest to entry 0.
// NaN maps to mid grey (128, 128, 128), so it is not mistaken for a value.
Image8 applyColorMap(const Image& scalar, float lo, float hi);

// ---- Text: a built-in 5x7 bitmap font -----------------------------------------------------------
// Glyphs: 0-9, A-Z (lower case letters draw as upper case, except an 'e' after a digit or '.',
// which draws as a lower case exponent 'e'),
// . , - + : ( ) / % = _ ? space, and the degree sign (UTF-8 "\u00b0"). Other characters draw as '?'.
// Each glyph is 5x7 on a 6-pixel advance, scaled by an integer factor.

int textWidth(std::string_view utf8, int scale = 1);
int textHeight(int scale = 1);  // 7 * scale
// Draws onto a 3- or 4-channel image (alpha set to 255), clipped to the image.
void drawText(Image8& image, int x, int y, std::string_view utf8, Rgb8 color, int scale = 1);
void fillRect(Image8& image, int x, int y, int w, int h, Rgb8 color);

// Compact tick label: printf "%.3g" (so 0.25, 1.5e-05, 120), "-0" written as "0".
std::string formatTickValue(double v);

// ---- Legend ---------------------------------------------------------------------------------------

struct LegendStyle {
    int ticks = 5;         // labelled ticks from lo to hi inclusive (>= 2)
    int textScale = 0;     // glyph scale; 0 = automatic (1 below 400 px of map height, else 2)
    Rgb8 background{24, 24, 24};
    Rgb8 foreground{235, 235, 235};
};

// Width in pixels of the legend that drawLegend draws for these values.
int legendWidth(float lo, float hi, const LegendStyle& style, int mapHeight);
// Draws the legend: a vertical colour bar (hi at the top, lo at the bottom) with tick marks and
// labels to its right, into the rectangle [x, x + legendWidth) x [y, y + height) of `image`.
void drawLegend(Image8& image, int x, int y, int height, float lo, float hi, const LegendStyle& style);

// An annotated picture: `map` under a title band and, when `legend`, the lo..hi legend on its
// right. The map's pixel (x, y) is the picture's (x, y + titleBandHeight(map.height)).
Image8 titledPicture(const Image8& map, std::string_view title, bool legend, float lo, float hi,
                     const LegendStyle& style = {});
// The height of the title band titledPicture puts above a map of this height.
int titleBandHeight(int mapHeight, const LegendStyle& style = {});

// A readable heat-map picture: the colour-mapped scalar image, a title line above it, and the
// legend on the right with lo and hi (and the ticks between) labelled.
Image8 heatMapWithLegend(const Image& scalar, float lo, float hi, std::string_view title,
                         const LegendStyle& style = {});

}  // namespace gbl
