#include "report_html_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "report_html.h"

namespace gbl {
namespace {

// ---- The plot ------------------------------------------------------------------------------------

const char* kSeriesColors[] = {"#1f5fa8", "#c0392b", "#218c4b", "#7b3fa0", "#d9730d", "#6b4f3a", "#0f8a8a"};

struct Axis {
    double lo = 0, hi = 1, step = 0.2;
    int decimals = 1;
};

// Ticks at 1, 2, 2.5 or 5 x 10^k, about `count` of them over [lo, hi].
Axis niceAxis(double lo, double hi, int count, bool fromZero) {
    if (fromZero) lo = std::min(lo, 0.0);
    if (!(hi > lo)) hi = lo + (lo == 0 ? 1.0 : std::abs(lo) * 0.1);
    const double raw = (hi - lo) / count;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    double step = magnitude;
    for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (m * magnitude >= raw) {
            step = m * magnitude;
            break;
        }
    Axis a;
    a.step = step;
    a.lo = std::floor(lo / step + 1e-9) * step;
    a.hi = std::ceil(hi / step - 1e-9) * step;
    if (a.hi <= a.lo) a.hi = a.lo + step;
    const double fractional = step / std::pow(10.0, std::floor(std::log10(step)));
    a.decimals = std::max(0, -int(std::floor(std::log10(step))) + (fractional == 2.5 ? 1 : 0));
    return a;
}

struct Box {
    double x0, y0, x1, y1;
    bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};



}  // namespace

void writePlot(std::string& out, const ReportModel& model, const PlotSpec& spec, bool hidden) {

    // Series: one per IBL mode, in the run info's order, then any others the runs name.
    std::vector<std::string> modes = model.run.iblModes;
    for (const RunReport& r : model.runs)
        if (std::find(modes.begin(), modes.end(), r.iblMode) == modes.end()) modes.push_back(r.iblMode);
    struct Point {
        double x, y;
        const RunReport* run;
    };
    std::vector<std::vector<Point>> series(modes.size());
    double xMax = 0, yMin = INFINITY, yMax = -INFINITY;
    bool anyInfinite = false;
    bool skippedLighting = false;
    for (const RunReport& r : model.runs) {
        if (r.status != RunStatus::Ok || !r.image) continue;
        // Errors against ground truth, not against the float reference: not a point of this plot
        // (and never on a layout's Pareto front). The IBL figure and the table show them.
        if (r.isLightingComparison()) {
            skippedLighting = true;
            continue;
        }
        const double y = *r.image.*spec.field;
        if (std::isnan(y)) continue;
        const size_t s = size_t(std::find(modes.begin(), modes.end(), r.iblMode) - modes.begin());
        series[s].push_back({double(r.bytesPerPixel.total), y, &r});
        xMax = std::max(xMax, double(r.bytesPerPixel.total));
        if (std::isinf(y)) {
            anyInfinite = true;
        } else {
            yMin = std::min(yMin, y);
            yMax = std::max(yMax, y);
        }
    }
    out += std::string("<figure class=\"plot\" id=\"plot-") + spec.id + "\"" + (hidden ? " hidden" : "") + ">\n";
    const double W = 900, H = 460, left = 70, right = 150, top = anyInfinite ? 46 : 24, bottom = 52;
    const double plotW = W - left - right, plotH = H - top - bottom;
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + formatFixed(W, 0) + " " + formatFixed(H, 0) +
           "\" role=\"img\" aria-label=\"" + htmlEscape(spec.yLabel) + " against bytes per pixel\" "
           "font-family=\"system-ui, 'DejaVu Sans', Arial, sans-serif\" font-size=\"12\">\n";
    size_t pointCount = 0;
    for (const auto& s : series) pointCount += s.size();
    if (pointCount == 0) {
        out += "<text x=\"" + formatFixed(W / 2, 0) + "\" y=\"" + formatFixed(H / 2, 0) +
               "\" text-anchor=\"middle\" fill=\"#5b6672\">No measured runs to plot.</text>\n</svg>\n</figure>\n";
        return;
    }
    if (yMin > yMax) yMin = 0, yMax = 1;  // every value infinite
    const Axis xa = niceAxis(0, xMax * 1.05, 6, true);
    const Axis ya = niceAxis(spec.yFromZero ? 0 : yMin - (yMax - yMin) * 0.05, yMax + (yMax - yMin) * 0.05, 5,
                             spec.yFromZero);
    const auto px = [&](double x) { return left + (x - xa.lo) / (xa.hi - xa.lo) * plotW; };
    const auto py = [&](double y) {
        if (std::isinf(y)) return y > 0 ? top - 22 : top + plotH;  // +inf: the "∞" lane above the axes
        return top + plotH - (y - ya.lo) / (ya.hi - ya.lo) * plotH;
    };
    const auto f1 = [](double v) { return formatFixed(v, 1); };
    // Grid and ticks.
    out += "<g stroke=\"#e3e7eb\" stroke-width=\"1\">\n";
    for (double x = xa.lo; x <= xa.hi + xa.step * 1e-6; x += xa.step)
        out += "<line x1=\"" + f1(px(x)) + "\" y1=\"" + f1(top) + "\" x2=\"" + f1(px(x)) + "\" y2=\"" +
               f1(top + plotH) + "\"/>\n";
    for (double y = ya.lo; y <= ya.hi + ya.step * 1e-6; y += ya.step)
        out += "<line x1=\"" + f1(left) + "\" y1=\"" + f1(py(y)) + "\" x2=\"" + f1(left + plotW) + "\" y2=\"" +
               f1(py(y)) + "\"/>\n";
    out += "</g>\n<rect x=\"" + f1(left) + "\" y=\"" + f1(top) + "\" width=\"" + f1(plotW) + "\" height=\"" + f1(plotH) +
           "\" fill=\"none\" stroke=\"#9aa5b1\"/>\n<g fill=\"#5b6672\">\n";
    for (double x = xa.lo; x <= xa.hi + xa.step * 1e-6; x += xa.step)
        out += "<text x=\"" + f1(px(x)) + "\" y=\"" + f1(top + plotH + 16) + "\" text-anchor=\"middle\">" +
               formatFixed(x, xa.decimals) + "</text>\n";
    for (double y = ya.lo; y <= ya.hi + ya.step * 1e-6; y += ya.step)
        out += "<text x=\"" + f1(left - 6) + "\" y=\"" + f1(py(y) + 4) + "\" text-anchor=\"end\">" +
               formatFixed(y, ya.decimals) + "</text>\n";
    if (anyInfinite)
        out += "<text x=\"" + f1(left - 6) + "\" y=\"" + f1(py(INFINITY) + 5) + "\" text-anchor=\"end\" font-size=\"15\">" +
               kInfinity + "</text>\n<line x1=\"" + f1(left) + "\" y1=\"" + f1(py(INFINITY)) + "\" x2=\"" +
               f1(left + plotW) + "\" y2=\"" + f1(py(INFINITY)) + "\" stroke=\"#e3e7eb\" stroke-dasharray=\"3 3\"/>\n";
    out += "<text x=\"" + f1(left + plotW / 2) + "\" y=\"" + f1(H - 10) +
           "\" text-anchor=\"middle\" fill=\"#1d232b\">G-buffer bytes per pixel (targets + depth + light buffers)</text>\n";
    out += "<text transform=\"translate(16 " + f1(top + plotH / 2) + ") rotate(-90)\" text-anchor=\"middle\" "
           "fill=\"#1d232b\">" + htmlEscape(spec.yLabel) + "</text>\n</g>\n";
    // Pareto fronts, then points, then labels (placed to avoid each other and the points).
    std::vector<Box> taken;
    for (size_t s = 0; s < series.size(); ++s) {
        std::vector<std::pair<double, double>> xy;
        for (const Point& p : series[s]) xy.push_back({p.x, p.y});
        const std::vector<size_t> front = paretoFront(xy, spec.higherIsBetter);
        if (front.size() >= 2) {
            std::string points;
            for (size_t i : front) points += f1(px(series[s][i].x)) + "," + f1(py(series[s][i].y)) + " ";
            points.pop_back();
            out += std::string("<polyline class=\"pareto\" fill=\"none\" stroke=\"") + kSeriesColors[s % 7] +
                   "\" stroke-width=\"2\" stroke-opacity=\"0.75\" points=\"" + points + "\"/>\n";
        }
        for (const Point& p : series[s]) taken.push_back({px(p.x) - 5, py(p.y) - 5, px(p.x) + 5, py(p.y) + 5});
    }
    for (size_t s = 0; s < series.size(); ++s) {
        const char* color = kSeriesColors[s % 7];
        for (const Point& p : series[s]) {
            const std::string tip = p.run->layout + " (" + p.run->iblMode + "): " + formatFixed(p.x, 0) + " B/px, " +
                                    spec.yLabel + " " + spec.format(p.y);
            out += "<circle cx=\"" + f1(px(p.x)) + "\" cy=\"" + f1(py(p.y)) + "\" r=\"4.5\" fill=\"" + color +
                   "\" stroke=\"#fff\" stroke-width=\"1\"><title>" + htmlEscape(tip) + "</title></circle>\n";
        }
    }
    out += "<g font-size=\"11\" fill=\"#1d232b\">\n";
    for (size_t s = 0; s < series.size(); ++s)
        for (const Point& p : series[s]) {
            const double cx = px(p.x), cy = py(p.y);
            const double w = 6.4 * double(p.run->layout.size()) + 2, h = 13;
            struct Candidate {
                double x, y;  // text anchor (start) and baseline
            };
            const Candidate candidates[] = {{cx + 7, cy + 4},      {cx + 7, cy - 7},      {cx + 7, cy + 15},
                                            {cx - 7 - w, cy + 4},  {cx - w / 2, cy - 9},  {cx - w / 2, cy + 18},
                                            {cx - 7 - w, cy - 7},  {cx - 7 - w, cy + 15}, {cx + 7, cy - 18},
                                            {cx + 7, cy + 26}};
            const Candidate* chosen = &candidates[0];
            for (const Candidate& c : candidates) {
                const Box b{c.x, c.y - h + 3, c.x + w, c.y + 3};
                const bool inside = b.x0 >= 2 && b.x1 <= W - 2 && b.y0 >= 2 && b.y1 <= H - bottom + 14;
                if (inside && std::none_of(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(b); })) {
                    chosen = &c;
                    break;
                }
            }
            taken.push_back({chosen->x, chosen->y - h + 3, chosen->x + w, chosen->y + 3});
            out += "<text x=\"" + f1(chosen->x) + "\" y=\"" + f1(chosen->y) + "\">" + htmlEscape(p.run->layout) +
                   "</text>\n";
        }
    out += "</g>\n</svg>\n<div class=\"legend\">";
    for (size_t s = 0; s < series.size(); ++s) {
        if (series[s].empty()) continue;
        out += std::string("<span><svg width=\"12\" height=\"12\" viewBox=\"0 0 12 12\"><circle cx=\"6\" cy=\"6\" "
                           "r=\"4.5\" fill=\"") +
               kSeriesColors[s % 7] + "\"/></svg>layouts, IBL " + htmlEscape(modes[s]) + "</span>";
    }
    out += std::string("<span><svg width=\"26\" height=\"12\" viewBox=\"0 0 26 12\"><line x1=\"1\" y1=\"6\" x2=\"25\" "
                       "y2=\"6\" stroke=\"#5b6672\" stroke-width=\"2\"/></svg>Pareto front, per IBL mode (no layout is "
                       "both smaller and ") +
           (spec.higherIsBetter ? "higher" : "lower") + ")</span>";
    if (anyInfinite) out += std::string("<span>") + kInfinity + ": identical to the reference</span>";
    if (skippedLighting)
        out += "<span>the lighting comparisons (reference (&lt;mode&gt; vs ground-truth)) are not plotted: their "
               "errors are against ground truth</span>";
    out += "</div>\n</figure>\n";
}

}  // namespace gbl
