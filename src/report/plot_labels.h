#pragma once
// Where the plot's point labels go: every label beside its marker when there is room, else at the
// nearest free spot with a leader line back to the marker; no two labels and no label and marker
// overlap. Deterministic (same input, same picture) and measured in the SVG's own units, so the
// page needs no script to read. Internal to the report library (report_html_plot.cpp).
#include <string>
#include <vector>

namespace gbl {

struct PlotBox {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool intersects(const PlotBox& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
    bool contains(const PlotBox& o) const { return o.x0 >= x0 && o.x1 <= x1 && o.y0 >= y0 && o.y1 <= y1; }
};

struct PlotLine {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct LabelRequest {
    double anchorX = 0, anchorY = 0;  // the marker's centre
    double width = 0, height = 0;     // the text's box
};

struct PlacedLabel {
    PlotBox box;
    bool leader = false;         // drawn with a line from the marker to the box
    double leaderX = 0, leaderY = 0;  // the line's end: the box's point nearest the marker
};

// Places `labels` in order (earlier ones get the nearer spots) inside `area`, clear of `markers`,
// of the `lines` already drawn (fronts, connectors) and of each other's boxes and leader lines.
// A label that finds no room inside `area` goes below it, in a column of its own: the caller
// grows the picture to the boxes it gets back.
std::vector<PlacedLabel> placeLabels(const std::vector<LabelRequest>& labels, const std::vector<PlotBox>& markers,
                                     const std::vector<PlotLine>& lines, const PlotBox& area);

// The advance width of `text` in DejaVu Sans at `fontSize` (its hmtx table, ASCII; 1 em for any
// other byte of UTF-8, an upper bound for Latin text). The plot pins each label to this width
// (SVG textLength), so the box placed here is the box a browser draws whatever font it picks.
double labelTextWidth(const std::string& text, double fontSize);
// DejaVu Sans' ascent and descent, as fractions of the font size (a label's box above and below
// its baseline).
inline constexpr double kLabelAscent = 1901.0 / 2048.0;
inline constexpr double kLabelDescent = 483.0 / 2048.0;

}  // namespace gbl
