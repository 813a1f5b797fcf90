#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "color_difference.h"
#include "color_map.h"

namespace {

using gbl::Image;
using gbl::Image8;
using gbl::Rgb8;

bool same(Rgb8 a, Rgb8 b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

Rgb8 pixel(const Image8& im, int x, int y) {
    const unsigned char* p = &im.pixels[(size_t(y) * size_t(im.width) + size_t(x)) * size_t(im.channels)];
    return {p[0], p[1], p[2]};
}

double lstar(Rgb8 c) {
    return gbl::linearSrgbToLab(gbl::srgbDecode(c.r / 255.0), gbl::srgbDecode(c.g / 255.0), gbl::srgbDecode(c.b / 255.0))
        .L;
}

TEST(ColorMap, EndpointsAndKeyColours) {
    const auto& t = gbl::viridisTable();
    EXPECT_TRUE(same(t[0], {68, 1, 84}));
    EXPECT_TRUE(same(t[255], {253, 231, 37}));
    // Entries 85 and 170 sit exactly on key colours 3 and 6 (t = 1/3, 2/3): within 1 step.
    const Rgb8 k3{49, 104, 142}, k6{53, 183, 121};
    EXPECT_LE(std::abs(t[85].r - k3.r) + std::abs(t[85].g - k3.g) + std::abs(t[85].b - k3.b), 2);
    EXPECT_LE(std::abs(t[170].r - k6.r) + std::abs(t[170].g - k6.g) + std::abs(t[170].b - k6.b), 2);
}

TEST(ColorMap, LightnessRisesMonotonically) {
    const auto& t = gbl::viridisTable();
    // L* strictly increases along the map (up to the 8-bit rounding of each entry, well below
    // the ~0.3 L* step between neighbours) and spans dark to light.
    for (int i = 1; i < 256; ++i) EXPECT_GT(lstar(t[size_t(i)]), lstar(t[size_t(i - 1)]) - 0.05) << i;
    for (int i = 8; i < 256; i += 8) EXPECT_GT(lstar(t[size_t(i)]), lstar(t[size_t(i - 8)]) + 1.0) << i;
    EXPECT_LT(lstar(t[0]), 20.0);
    EXPECT_GT(lstar(t[255]), 88.0);
}

TEST(ColorMap, ApplyMapsRangeClampsAndMarksNan) {
    Image s(6, 1, 1);
    s.pixels = {0.0f, 1.0f, -5.0f, 9.0f, 0.5f, std::nanf("")};
    const Image8 m = gbl::applyColorMap(s, 0.0f, 1.0f);
    ASSERT_EQ(m.width, 6);
    ASSERT_EQ(m.channels, 3);
    const auto& t = gbl::viridisTable();
    EXPECT_TRUE(same(pixel(m, 0, 0), t[0]));
    EXPECT_TRUE(same(pixel(m, 1, 0), t[255]));
    EXPECT_TRUE(same(pixel(m, 2, 0), t[0]));
    EXPECT_TRUE(same(pixel(m, 3, 0), t[255]));
    EXPECT_TRUE(same(pixel(m, 4, 0), t[128]));  // floor(127.5 + 0.5)
    EXPECT_TRUE(same(pixel(m, 5, 0), {128, 128, 128}));
    // Degenerate range: above lo -> top, else bottom.
    const Image8 d = gbl::applyColorMap(s, 0.5f, 0.5f);
    EXPECT_TRUE(same(pixel(d, 1, 0), t[255]));
    EXPECT_TRUE(same(pixel(d, 4, 0), t[0]));
}

TEST(ColorMap, FontDrawsGlyphPixels) {
    Image8 im;
    im.width = 20;
    im.height = 9;
    im.channels = 3;
    im.pixels.assign(20 * 9 * 3, 0);
    gbl::drawText(im, 1, 1, "1", {255, 255, 255});
    // '1' = "..#.." / ".##.." / "..#.." x4 / ".###.": column 2 inked in every row.
    for (int row = 0; row < 7; ++row) EXPECT_EQ(pixel(im, 1 + 2, 1 + row).r, 255) << row;
    EXPECT_EQ(pixel(im, 1 + 0, 1 + 0).r, 0);
    EXPECT_EQ(pixel(im, 1 + 1, 1 + 1).r, 255);
    EXPECT_EQ(pixel(im, 1 + 3, 1 + 6).r, 255);
    EXPECT_EQ(pixel(im, 1 + 4, 1 + 6).r, 0);
    EXPECT_EQ(gbl::textWidth("1", 1), 5);
    EXPECT_EQ(gbl::textWidth("12", 2), 22);
    EXPECT_EQ(gbl::textWidth("\xc2\xb0", 1), 5);  // degree sign is one glyph
    // Every label character has its own glyph (not the '?' fallback); unknown ones fall back.
    auto render = [](const std::string& s) {
        Image8 r;
        r.width = 6;
        r.height = 7;
        r.channels = 3;
        r.pixels.assign(6 * 7 * 3, 0);
        gbl::drawText(r, 0, 0, s, {255, 255, 255});
        return r.pixels;
    };
    const auto q = render("?");
    for (const std::string c : {"0", "5", "9", ".", "-", "+", "e", "\xc2\xb0", "F", "L", "I", "P", "(", ")"})
        EXPECT_NE(render(c), q) << c;
    EXPECT_EQ(render("~"), q);
    EXPECT_EQ(render("f"), render("F"));  // lower case draws as upper case...
    EXPECT_EQ(render("e"), render("E"));
    // ...except an exponent e (after a digit or '.'): compare the second glyph of "1e" / "1E".
    auto second = [](const std::string& s) {
        Image8 r;
        r.width = 12;
        r.height = 7;
        r.channels = 3;
        r.pixels.assign(12 * 7 * 3, 0);
        gbl::drawText(r, 0, 0, s, {255, 255, 255});
        std::vector<unsigned char> g;
        for (int y = 0; y < 7; ++y)
            for (int x = 6; x < 11; ++x) g.push_back(pixel(r, x, y).r);
        return g;
    };
    EXPECT_NE(second("1e"), second("1E"));
    EXPECT_EQ(second("Re"), second("RE"));
}

TEST(ColorMap, TickFormat) {
    EXPECT_EQ(gbl::formatTickValue(0.25), "0.25");
    EXPECT_EQ(gbl::formatTickValue(1.5e-5), "1.5e-05");
    EXPECT_EQ(gbl::formatTickValue(120.0), "120");
    EXPECT_EQ(gbl::formatTickValue(-0.0), "0");
    EXPECT_EQ(gbl::formatTickValue(-2.5), "-2.5");
}

TEST(ColorMap, HeatMapWithLegendLayout) {
    // A horizontal ramp 0..1, 200 x 120.
    Image s(200, 120, 1);
    for (int y = 0; y < 120; ++y)
        for (int x = 0; x < 200; ++x) s.at(x, y, 0) = x / 199.0f;
    gbl::LegendStyle style;
    const Image8 out = gbl::heatMapWithLegend(s, 0.0f, 1.0f, "FLIP", style);
    const int scale = 1;  // auto: map height < 400
    const int titleH = 7 * scale + 6 * scale;
    const int legendW = gbl::legendWidth(0.0f, 1.0f, style, 120);
    EXPECT_EQ(out.width, 200 + legendW);
    EXPECT_EQ(out.height, titleH + 120);
    EXPECT_EQ(out.channels, 3);
    const auto& t = gbl::viridisTable();
    // The map sits below the title, unchanged.
    EXPECT_TRUE(same(pixel(out, 0, titleH), t[0]));
    EXPECT_TRUE(same(pixel(out, 199, titleH + 60), t[255]));
    // The title is drawn (foreground pixels in the title strip).
    int ink = 0;
    for (int y = 0; y < titleH; ++y)
        for (int x = 0; x < 60; ++x) ink += same(pixel(out, x, y), style.foreground);
    EXPECT_GT(ink, 20);
    // The bar: hi colour at the top, lo colour at the bottom, in the bar's columns.
    const int barStart = 200 + 4 * scale, barX = barStart + 6 * scale;  // barX: mid bar, clear of notches
    const int top = titleH + 4 * scale + 3, bottom = titleH + 120 - 1 - 4 * scale - 3;
    EXPECT_TRUE(same(pixel(out, barX, top), t[255]));
    EXPECT_TRUE(same(pixel(out, barX, bottom), t[0]));
    // Labels: the lo label "0" is drawn centred on the bottom tick, the hi label "1" on the top.
    const int labelX = 200 + 4 * scale + 12 * scale + 3 * scale;
    // Tick notches in the bar's right edge at the ends.
    EXPECT_TRUE(same(pixel(out, barStart + 11 * scale, top), style.foreground));
    EXPECT_TRUE(same(pixel(out, barStart + 11 * scale, bottom), style.foreground));
    int loInk = 0, hiInk = 0;
    for (int y = bottom - 3; y <= bottom + 3; ++y)
        for (int x = labelX; x < labelX + 5; ++x) loInk += same(pixel(out, x, y), style.foreground);
    for (int y = top - 3; y <= top + 3; ++y)
        for (int x = labelX; x < labelX + 5; ++x) hiInk += same(pixel(out, x, y), style.foreground);
    EXPECT_GT(loInk, 8);   // '0' has 18 ink pixels
    EXPECT_GT(hiInk, 8);   // '1' has 12
    // Large maps use 2x text; a tiny map still gets a legend tall enough for its labels.
    const Image8 big = gbl::heatMapWithLegend(Image(10, 500, 1, 0.5f), 0.0f, 2.0f, "N", style);
    EXPECT_EQ(big.height, 500 + 7 * 2 + 6 * 2);
    const Image8 tiny = gbl::heatMapWithLegend(Image(3, 2, 1, 0.5f), 0.0f, 2.0f, "DEG \xc2\xb0", style);
    EXPECT_GE(tiny.height, 2 * 7 + 16);
}

}  // namespace
