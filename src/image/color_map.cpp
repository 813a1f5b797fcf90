#include "color_map.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "color_difference.h"

namespace gbl {
namespace {

// Viridis key colours at t = i/9, i = 0..9 (sRGB, 8-bit).
constexpr Rgb8 kViridisKeys[10] = {{68, 1, 84},    {72, 40, 120},  {62, 74, 137},  {49, 104, 142},
                                   {38, 130, 142}, {31, 158, 137}, {53, 183, 121}, {109, 205, 89},
                                   {180, 222, 44}, {253, 231, 37}};

uint8_t toByte(double encoded) {
    return uint8_t(std::floor(std::clamp(encoded, 0.0, 1.0) * 255.0 + 0.5));
}

std::array<Rgb8, 256> buildViridis() {
    Lab keys[10];
    for (int i = 0; i < 10; ++i) {
        const Rgb8 k = kViridisKeys[i];
        keys[i] = linearSrgbToLab(srgbDecode(k.r / 255.0), srgbDecode(k.g / 255.0), srgbDecode(k.b / 255.0));
    }
    std::array<Rgb8, 256> table{};
    for (int i = 0; i < 256; ++i) {
        const double t = i / 255.0 * 9.0;
        const int seg = std::min(8, int(t));
        const double f = t - seg;
        const Lab& a = keys[seg];
        const Lab& b = keys[seg + 1];
        const Lab lab{a.L + f * (b.L - a.L), a.a + f * (b.a - a.a), a.b + f * (b.b - a.b)};
        double r, g, bl;
        xyzToLinearSrgb(labToXyz(lab), r, g, bl);
        table[size_t(i)] = {toByte(srgbEncode(std::max(0.0, r))), toByte(srgbEncode(std::max(0.0, g))),
                            toByte(srgbEncode(std::max(0.0, bl)))};
    }
    return table;
}

// ---- 5x7 font: each glyph is 7 rows of 5 columns, '#' = ink -----------------------------------------

struct Glyph {
    const char* key;  // UTF-8 of the character
    const char* rows[7];
};

// clang-format off
constexpr Glyph kFont[] = {
    {"0", {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
    {"1", {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {"2", {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
    {"3", {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."}},
    {"4", {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
    {"5", {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
    {"6", {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
    {"7", {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
    {"8", {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
    {"9", {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
    {"A", {".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {"B", {"####.", "#...#", "#...#", "####.", "#...#", "#...#", "####."}},
    {"C", {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."}},
    {"D", {"###..", "#..#.", "#...#", "#...#", "#...#", "#..#.", "###.."}},
    {"E", {"#####", "#....", "#....", "####.", "#....", "#....", "#####"}},
    {"F", {"#####", "#....", "#....", "####.", "#....", "#....", "#...."}},
    {"G", {".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".####"}},
    {"H", {"#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {"I", {".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {"J", {"..###", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."}},
    {"K", {"#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"}},
    {"L", {"#....", "#....", "#....", "#....", "#....", "#....", "#####"}},
    {"M", {"#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"}},
    {"N", {"#...#", "#...#", "##..#", "#.#.#", "#..##", "#...#", "#...#"}},
    {"O", {".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {"P", {"####.", "#...#", "#...#", "####.", "#....", "#....", "#...."}},
    {"Q", {".###.", "#...#", "#...#", "#...#", "#.#.#", "#..#.", ".##.#"}},
    {"R", {"####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"}},
    {"S", {".####", "#....", "#....", ".###.", "....#", "....#", "####."}},
    {"T", {"#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."}},
    {"U", {"#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {"V", {"#...#", "#...#", "#...#", "#...#", "#...#", ".#.#.", "..#.."}},
    {"W", {"#...#", "#...#", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#."}},
    {"X", {"#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#"}},
    {"Y", {"#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#.."}},
    {"Z", {"#####", "....#", "...#.", "..#..", ".#...", "#....", "#####"}},
    {"e", {".....", ".....", ".###.", "#...#", "#####", "#....", ".###."}},
    {".", {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
    {",", {".....", ".....", ".....", ".....", ".##..", "..#..", ".#..."}},
    {"-", {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
    {"+", {".....", "..#..", "..#..", "#####", "..#..", "..#..", "....."}},
    {":", {".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."}},
    {"(", {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."}},
    {")", {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."}},
    {"/", {".....", "....#", "...#.", "..#..", ".#...", "#....", "....."}},
    {"%", {"##...", "##..#", "...#.", "..#..", ".#...", "#..##", "...##"}},
    {"=", {".....", ".....", "#####", ".....", "#####", ".....", "....."}},
    {"_", {".....", ".....", ".....", ".....", ".....", ".....", "#####"}},
    {"?", {".###.", "#...#", "....#", "...#.", "..#..", ".....", "..#.."}},
    {" ", {".....", ".....", ".....", ".....", ".....", ".....", "....."}},
    {"\xc2\xb0", {".##..", "#..#.", "#..#.", ".##..", ".....", ".....", "....."}},
};
// clang-format on

const Glyph* findGlyph(std::string_view key) {
    for (const Glyph& g : kFont)
        if (key == g.key) return &g;
    return nullptr;
}

// Splits off the next character (a byte, or a UTF-8 sequence) and returns its glyph. Lower case
// letters draw as upper case, except an 'e' right after a digit or '.', which is an exponent.
const Glyph* nextGlyph(std::string_view text, size_t& pos) {
    const unsigned char c = static_cast<unsigned char>(text[pos]);
    const char prev = pos > 0 ? text[pos - 1] : ' ';
    const bool exponent = c == 'e' && ((prev >= '0' && prev <= '9') || prev == '.');
    size_t len = 1;
    if (c >= 0xC0 && c < 0xE0) len = 2;
    else if (c >= 0xE0 && c < 0xF0) len = 3;
    else if (c >= 0xF0) len = 4;
    len = std::min(len, text.size() - pos);
    std::string key(text.substr(pos, len));
    pos += len;
    if (len == 1 && c >= 'a' && c <= 'z' && !exponent) key[0] = char(c - 'a' + 'A');
    const Glyph* g = findGlyph(key);
    return g ? g : findGlyph("?");
}

void putPixel(Image8& im, int x, int y, Rgb8 c) {
    if (x < 0 || y < 0 || x >= im.width || y >= im.height) return;
    unsigned char* p = im.pixels.data() + (size_t(y) * size_t(im.width) + size_t(x)) * size_t(im.channels);
    if (im.channels >= 3) {
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
        if (im.channels >= 4) p[3] = 255;
    } else if (im.channels >= 1) {
        p[0] = uint8_t((int(c.r) + int(c.g) + int(c.b) + 1) / 3);
    }
}

int autoScale(const LegendStyle& s, int mapHeight) {
    if (s.textScale > 0) return s.textScale;
    return mapHeight < 400 ? 1 : 2;
}

std::vector<double> tickValues(float lo, float hi, int ticks) {
    const int n = std::max(2, ticks);
    std::vector<double> v(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) v[size_t(i)] = double(lo) + (double(hi) - double(lo)) * i / (n - 1);
    v.back() = hi;
    return v;
}

}  // namespace

const std::array<Rgb8, 256>& viridisTable() {
    static const std::array<Rgb8, 256> table = buildViridis();
    return table;
}

Image8 applyColorMap(const Image& scalar, float lo, float hi) {
    const auto& table = viridisTable();
    Image8 out;
    out.width = scalar.width;
    out.height = scalar.height;
    out.channels = 3;
    out.pixels.assign(scalar.pixelCount() * 3, 0);
    const double range = double(hi) - double(lo);
    for (size_t i = 0; i < scalar.pixelCount(); ++i) {
        const float v = scalar.channels > 0 ? scalar.pixels[i * size_t(scalar.channels)] : 0.0f;
        Rgb8 c{128, 128, 128};
        if (!std::isnan(v)) {
            double t;
            if (range > 0.0) t = std::clamp((double(v) - double(lo)) / range, 0.0, 1.0);
            else t = v > lo ? 1.0 : 0.0;
            c = table[size_t(std::floor(t * 255.0 + 0.5))];
        }
        out.pixels[i * 3 + 0] = c.r;
        out.pixels[i * 3 + 1] = c.g;
        out.pixels[i * 3 + 2] = c.b;
    }
    return out;
}

int textWidth(std::string_view text, int scale) {
    int count = 0;
    for (size_t pos = 0; pos < text.size();) {
        nextGlyph(text, pos);
        ++count;
    }
    return count == 0 ? 0 : (count * 6 - 1) * scale;
}

int textHeight(int scale) { return 7 * scale; }

void drawText(Image8& image, int x, int y, std::string_view text, Rgb8 color, int scale) {
    scale = std::max(1, scale);
    int penX = x;
    for (size_t pos = 0; pos < text.size();) {
        const Glyph* g = nextGlyph(text, pos);
        for (int row = 0; row < 7; ++row)
            for (int col = 0; col < 5; ++col)
                if (g->rows[row][col] == '#')
                    for (int sy = 0; sy < scale; ++sy)
                        for (int sx = 0; sx < scale; ++sx)
                            putPixel(image, penX + col * scale + sx, y + row * scale + sy, color);
        penX += 6 * scale;
    }
}

void fillRect(Image8& image, int x, int y, int w, int h, Rgb8 color) {
    for (int yy = std::max(0, y); yy < std::min(image.height, y + h); ++yy)
        for (int xx = std::max(0, x); xx < std::min(image.width, x + w); ++xx) putPixel(image, xx, yy, color);
}

std::string formatTickValue(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    std::string s = buf;
    if (s == "-0") s = "0";
    return s;
}

// Layout (s = text scale): pad 4s | bar 12s | gap 3s | labels | pad 4s. Tick marks are notches
// cut into the bar's right edge (not dashes beside it, which would read as minus signs).
int legendWidth(float lo, float hi, const LegendStyle& style, int mapHeight) {
    const int s = autoScale(style, mapHeight);
    int labelW = 0;
    for (double v : tickValues(lo, hi, style.ticks)) labelW = std::max(labelW, textWidth(formatTickValue(v), s));
    return 4 * s + 12 * s + 3 * s + labelW + 4 * s;
}

void drawLegend(Image8& image, int x, int y, int height, float lo, float hi, const LegendStyle& style) {
    const int s = autoScale(style, height);
    const int width = legendWidth(lo, hi, style, height);
    fillRect(image, x, y, width, height, style.background);
    const auto& table = viridisTable();
    // The bar spans [top, bottom], inset so the end labels (centred on their ticks) fit.
    const int top = y + 4 * s + textHeight(s) / 2;
    const int bottom = y + height - 1 - 4 * s - textHeight(s) / 2;
    if (bottom <= top) return;
    const int barX = x + 4 * s, barW = 12 * s;
    for (int yy = top; yy <= bottom; ++yy) {
        const double t = double(bottom - yy) / double(bottom - top);  // 1 at the top (hi)
        fillRect(image, barX, yy, barW, 1, table[size_t(std::floor(t * 255.0 + 0.5))]);
    }
    const std::vector<double> ticks = tickValues(lo, hi, style.ticks);
    for (size_t i = 0; i < ticks.size(); ++i) {
        const double t = double(i) / double(ticks.size() - 1);
        const int ty = bottom - int(std::lround(t * (bottom - top)));
        fillRect(image, barX + barW - 4 * s, ty - (s - 1) / 2, 4 * s, s, style.foreground);
        drawText(image, barX + barW + 3 * s, ty - textHeight(s) / 2, formatTickValue(ticks[i]), style.foreground, s);
    }
}

int titleBandHeight(int mapHeight, const LegendStyle& style) {
    const int s = autoScale(style, mapHeight);
    return textHeight(s) + 6 * s;
}

Image8 titledPicture(const Image8& map, std::string_view title, bool legend, float lo, float hi,
                     const LegendStyle& style) {
    const int s = autoScale(style, map.height);
    const int titleH = titleBandHeight(map.height, style);
    const int legendW = legend ? legendWidth(lo, hi, style, map.height) : 0;
    // Tall enough for the legend's end labels even when the map is tiny.
    const int bodyH = legend ? std::max(map.height, 2 * textHeight(s) + 16 * s) : map.height;
    Image8 out;
    out.width = std::max(map.width + legendW, textWidth(title, s) + 6 * s);
    out.height = titleH + bodyH;
    out.channels = 3;
    out.pixels.assign(size_t(out.width) * size_t(out.height) * 3, 0);
    fillRect(out, 0, 0, out.width, out.height, style.background);
    drawText(out, 3 * s, 3 * s, title, style.foreground, s);
    for (int y = 0; y < map.height; ++y)
        std::memcpy(out.pixels.data() + (size_t(titleH + y) * size_t(out.width)) * 3,
                    map.pixels.data() + size_t(y) * size_t(map.width) * 3, size_t(map.width) * 3);
    if (legend) drawLegend(out, map.width, titleH, bodyH, lo, hi, style);
    return out;
}

Image8 heatMapWithLegend(const Image& scalar, float lo, float hi, std::string_view title, const LegendStyle& style) {
    return titledPicture(applyColorMap(scalar, lo, hi), title, true, lo, hi, style);
}

}  // namespace gbl
