#include "ibl_figure.h"

#include <cmath>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace gbl {

int IblFigureLayout::tileX(int column) const {
    return kIblFigureMargin + column * (tileSize + kIblFigureTileGap) + (column >= metalColumns && metalColumns > 0 &&
                                                                         metalColumns < columns ? kIblFigureGroupGap : 0);
}

int IblFigureLayout::rowTop(int row) const {
    return kIblFigureTitleHeight + row * (tileSize + iblFigureCaptionBandHeight());
}

IblFigureLayout iblFigureLayout(const std::vector<FigureBall>& balls, int rows) {
    IblFigureLayout l;
    int largest = 1;
    for (const FigureBall& b : balls) largest = std::max(largest, b.size);
    const int scale = std::max(1, (64 + largest - 1) / largest);
    l.tileSize = largest * scale;
    l.columns = int(balls.size());
    l.rows = rows;
    l.metalColumns = int(std::count_if(balls.begin(), balls.end(), [](const FigureBall& b) { return b.metal; }));
    l.width = (l.columns > 0 ? l.tileX(l.columns - 1) + l.tileSize : 2 * kIblFigureMargin) + kIblFigureMargin;
    l.height = l.rowTop(rows) + kIblFigureMargin;
    return l;
}

namespace {
std::string percent(double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.3f%%", 100.0 * v);
    return buf;
}
std::string upper(std::string s) {
    for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
    return s;
}
}  // namespace

std::string iblFigureCaption(const IblFigureRow& row) {
    const bool noise = row.metalNoise || row.dielectricNoise;
    const std::optional<double> m = noise ? row.metalNoise : row.metalError;
    const std::optional<double> d = noise ? row.dielectricNoise : row.dielectricError;
    std::string text = upper(row.iblMode) + (noise ? ": NOISE" : ": ERROR");
    text += " METAL " + (m ? percent(*m) : std::string("-"));
    text += ", DIELECTRIC " + (d ? percent(*d) : std::string("-"));
    return text;
}

Image8 composeIblFigure(const std::vector<Image8>& renders, const std::vector<FigureBall>& balls,
                        const std::vector<std::string>& captions, const std::string& title) {
    if (captions.size() != renders.size()) throw std::invalid_argument("composeIblFigure: one caption per row");
    const IblFigureLayout l = iblFigureLayout(balls, int(renders.size()));
    Image8 out;
    out.width = l.width;
    out.height = l.height;
    out.channels = 3;
    out.pixels.assign(size_t(out.width) * out.height * 3, 0);
    fillRect(out, 0, 0, out.width, out.height, kIblFigureBackground);
    drawText(out, kIblFigureMargin, kIblFigureCaptionPad, upper(title), kIblFigureText, kIblFigureTextScale);
    for (int r = 0; r < l.rows; ++r) {
        const Image8& src = renders[size_t(r)];
        const int top = l.rowTop(r);
        for (int c = 0; c < l.columns; ++c) {
            const FigureBall& b = balls[size_t(c)];
            const int x0 = l.tileX(c);
            for (int ty = 0; ty < l.tileSize; ++ty)
                for (int tx = 0; tx < l.tileSize; ++tx) {
                    // Nearest: tile pixel -> crop pixel (the crop is centred in the tile).
                    const int sx = b.x + tx * b.size / l.tileSize, sy = b.y + ty * b.size / l.tileSize;
                    if (sx < 0 || sy < 0 || sx >= src.width || sy >= src.height) continue;
                    unsigned char* q = &out.pixels[(size_t(top + ty) * out.width + x0 + tx) * 3];
                    const int mx = sx - b.x, my = sy - b.y;
                    if (b.mask.size() == size_t(b.size) * size_t(b.size) && !b.mask[size_t(my) * size_t(b.size) + size_t(mx)]) {
                        q[0] = kIblFigureTileBackdrop.r;
                        q[1] = kIblFigureTileBackdrop.g;
                        q[2] = kIblFigureTileBackdrop.b;
                        continue;
                    }
                    const unsigned char* p = &src.pixels[(size_t(sy) * src.width + sx) * size_t(src.channels)];
                    q[0] = p[0];
                    q[1] = p[1];
                    q[2] = p[2];
                }
        }
        drawText(out, kIblFigureMargin, top + l.tileSize + kIblFigureCaptionPad, captions[size_t(r)], kIblFigureText,
                 kIblFigureTextScale);
    }
    return out;
}

}  // namespace gbl
