#include "report_html_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "budget_verdict.h"
#include "plot_labels.h"
#include "report_html.h"
namespace gbl {
namespace {

const char* kSeriesColors[] = {"#1f5fa8", "#c0392b", "#218c4b", "#7b3fa0", "#d9730d", "#6b4f3a", "#0f8a8a"};
constexpr double kLabelFont = 11;
constexpr double kMarkerHalf = 5;  // a marker's box, around its centre

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

// A logarithmic axis from the largest 1, 2 or 5 x 10^k at or below `lo` to the smallest at or
// above `hi`, with a tick at each of them in between.
struct LogAxis {
    double lo = 1e-3, hi = 1;
    std::vector<double> ticks;
};

LogAxis logAxis(double lo, double hi) {
    if (!(lo > 0)) lo = hi > 0 ? hi / 10 : 1e-3;
    if (!(hi > lo)) hi = lo * 10;
    const auto nice = [](int k, int i) { return double(i == 0 ? 1 : i == 1 ? 2 : 5) * std::pow(10.0, k); };
    LogAxis a;
    a.lo = a.hi = 0;
    for (int k = int(std::floor(std::log10(lo))) - 1; k <= int(std::ceil(std::log10(hi))) + 1; ++k)
        for (int i = 0; i < 3; ++i) {
            const double t = nice(k, i);
            if (t <= lo * (1 + 1e-9)) a.lo = t;
            if (t >= hi * (1 - 1e-9) && a.hi == 0) a.hi = t;
        }
    for (int k = int(std::floor(std::log10(a.lo))); k <= int(std::ceil(std::log10(a.hi))); ++k)
        for (int i = 0; i < 3; ++i) {
            const double t = nice(k, i);
            if (t >= a.lo * (1 - 1e-9) && t <= a.hi * (1 + 1e-9)) a.ticks.push_back(t);
        }
    return a;
}

struct Point {
    double x = 0;        // the table's bytes per pixel
    double counted = 0;  // the verdict's counted bytes (differs for a visibility buffer)
    double y = 0;
    bool visibility = false;
    size_t series = 0;
    size_t run = 0;  // index into model.runs
};

// A label to place: the text, the marker it names and the run it links to.
struct LabelText {
    std::string text;
    double anchorX, anchorY;
    size_t run;
    size_t point;  // the marker's data-pt
};

struct Front {
    size_t series;
    bool visibility;
    std::vector<std::pair<double, double>> points;  // in the picture, by increasing bytes
};

std::string f1(double v) { return formatFixed(v, 1); }

// The runs a plot shows, one point each (a run's metric, against its bytes), and what its axes
// must hold.
struct PlotPoints {
    std::vector<std::string> modes;  // the series: one per IBL mode
    std::vector<Point> points;
    double xMax = 0, yMin = INFINITY, yMax = -INFINITY;
    bool anyInfinite = false, anyZero = false, skippedLighting = false, anyVisibility = false;
};

PlotPoints collectPoints(const ReportModel& model, const PlotSpec& spec) {
    PlotPoints c;
    // Series: one per IBL mode, in the run info's order, then any others the runs name.
    c.modes = model.run.iblModes;
    for (const RunReport& r : model.runs)
        if (std::find(c.modes.begin(), c.modes.end(), r.iblMode) == c.modes.end()) c.modes.push_back(r.iblMode);
    for (size_t i = 0; i < model.runs.size(); ++i) {
        const RunReport& r = model.runs[i];
        if (r.status != RunStatus::Ok || !r.image) continue;
        // Errors against ground truth, not against the float reference: not a point of this plot
        // (and never on a layout's Pareto front). The IBL figure and the table show them.
        if (r.isLightingComparison()) {
            c.skippedLighting = true;
            continue;
        }
        if (spec.singleFrame && (!r.singleFrame || !r.singleFrame->image)) continue;
        const double y = spec.singleFrame ? *r.singleFrame->image.*spec.field : *r.image.*spec.field;
        if (std::isnan(y)) continue;
        Point p;
        p.x = r.bytesPerPixel.total;
        p.visibility = r.isVisibilityBuffer();
        p.counted = p.visibility ? verdictCountedBytes(r) : p.x;
        if (*spec.xClass) {  // effective bytes (report_bandwidth.h): the visibility buffer's fetch share kept
            const ClassTraffic* e = r.effective ? r.effective->find(spec.xClass) : nullptr;
            if (!e) continue;
            p.counted = e->bytesPerPixel + (p.counted - p.x);
            p.x = e->bytesPerPixel;
        }
        p.y = y;
        p.series = size_t(std::find(c.modes.begin(), c.modes.end(), r.iblMode) - c.modes.begin());
        p.run = i;
        c.points.push_back(p);
        c.anyVisibility = c.anyVisibility || p.visibility;
        c.xMax = std::max({c.xMax, p.x, p.counted});
        if (std::isinf(y)) {
            c.anyInfinite = true;
        } else if (spec.logY && y <= 0) {
            c.anyZero = true;
        } else {
            c.yMin = std::min(c.yMin, y);
            c.yMax = std::max(c.yMax, y);
        }
    }
    return c;
}

// The picture's frame: the plot area in the SVG's units, the axes and their ticks, and where a
// value lands.
struct PlotFrame {
    const PlotSpec& spec;
    double W = 1080, left = 74, right = 18;
    double topLane = 0, zeroLane = 0, top = 0, plotH = 440, plotW = 0;
    double axisBottom = 0, xTickY = 0, xTitleY = 0;
    std::string scaleName;
    Axis xa, ya;
    LogAxis la;
    std::vector<double> yTicks;

    double px(double x) const { return left + (x - xa.lo) / (xa.hi - xa.lo) * plotW; }
    double py(double y) const {
        if (std::isinf(y)) return y > 0 ? top - topLane / 2 : axisBottom;  // +inf: the "∞" lane above the axes
        if (!spec.logY) return axisBottom - (y - ya.lo) / (ya.hi - ya.lo) * plotH;
        if (y <= 0) return axisBottom + zeroLane / 2 + 2;  // the "0" lane under a log axis
        return axisBottom - (std::log10(y) - std::log10(la.lo)) / (std::log10(la.hi) - std::log10(la.lo)) * plotH;
    }
    std::string yTickText(double y) const { return spec.logY ? formatSignificant(y, 1) : formatFixed(y, ya.decimals); }
};

// The lanes (infinite values above the axes, zeros under a log axis) and sizes; the axes only when
// there are points.
PlotFrame planFrame(const PlotPoints& c, const PlotSpec& spec) {
    PlotFrame f{spec};
    f.topLane = c.anyInfinite ? 26 : 0;
    f.zeroLane = c.anyZero ? 24 : 0;
    f.top = 16 + f.topLane;
    f.plotW = f.W - f.left - f.right;
    f.axisBottom = f.top + f.plotH;
    f.xTickY = f.axisBottom + f.zeroLane + 16;
    f.xTitleY = f.xTickY + 22;
    f.scaleName = spec.logY ? " (log scale)" : "";
    return f;
}

void planAxes(PlotFrame& f, PlotPoints& c, const PlotSpec& spec) {
    if (c.yMin > c.yMax) c.yMin = spec.logY ? 1e-3 : 0, c.yMax = 1;  // every value infinite (or zero)
    f.xa = niceAxis(0, c.xMax * 1.05, 8, true);
    f.ya = niceAxis(spec.yFromZero ? 0 : c.yMin - (c.yMax - c.yMin) * 0.05, c.yMax + (c.yMax - c.yMin) * 0.05, 6,
                    spec.yFromZero);
    f.la = logAxis(c.yMin, c.yMax);
    if (spec.logY) f.yTicks = f.la.ticks;
    else
        for (double y = f.ya.lo; y <= f.ya.hi + f.ya.step * 1e-6; y += f.ya.step) f.yTicks.push_back(y);
}

// Pareto fronts: per IBL mode and per pipeline kind. `lines` gains what the labels must not cover:
// the fronts, and the connectors of visibility buffers' two markers.
std::vector<Front> paretoFronts(const PlotPoints& c, const PlotFrame& f, const PlotSpec& spec,
                                std::vector<PlotLine>& lines) {
    std::vector<Front> fronts;
    for (size_t s = 0; s < c.modes.size(); ++s)
        for (bool visibility : {false, true}) {
            std::vector<const Point*> group;
            std::vector<std::pair<double, double>> xy;
            for (const Point& p : c.points)
                if (p.series == s && p.visibility == visibility) {
                    group.push_back(&p);
                    xy.push_back({p.counted, p.y});
                }
            const std::vector<size_t> front = paretoFront(xy, spec.higherIsBetter);
            if (front.size() < 2) continue;
            Front line{s, visibility, {}};
            for (size_t i : front) line.points.push_back({f.px(group[i]->counted), f.py(group[i]->y)});
            for (size_t i = 1; i < line.points.size(); ++i)
                lines.push_back({line.points[i - 1].first, line.points[i - 1].second, line.points[i].first,
                                 line.points[i].second});
            fronts.push_back(std::move(line));
        }
    for (const Point& p : c.points)
        if (p.visibility) lines.push_back({f.px(p.x), f.py(p.y), f.px(p.counted), f.py(p.y)});
    return fronts;
}

// The labels, placed: texts[order[j]] goes in placed[j]; `height` is the picture's, grown for
// labels that found no room in the plot.
struct PlotLabels {
    std::vector<LabelText> texts;
    std::vector<size_t> order;
    std::vector<PlacedLabel> placed;
    double height = 0;
};

PlotLabels placePointLabels(const ReportModel& model, const PlotPoints& c, const PlotFrame& f,
                            const std::vector<PlotLine>& lines) {
    PlotLabels labels;
    std::vector<LabelText>& texts = labels.texts;
    std::vector<PlotBox> markers;
    for (size_t k = 0; k < c.points.size(); ++k) {
        const Point& p = c.points[k];
        const RunReport& r = model.runs[p.run];
        texts.push_back({r.layout, f.px(p.x), f.py(p.y), p.run, k});
        markers.push_back({f.px(p.x) - kMarkerHalf, f.py(p.y) - kMarkerHalf, f.px(p.x) + kMarkerHalf,
                           f.py(p.y) + kMarkerHalf});
        if (p.visibility) {
            texts.push_back({r.layout + " + fetches", f.px(p.counted), f.py(p.y), p.run, k});
            markers.push_back({f.px(p.counted) - kMarkerHalf, f.py(p.y) - kMarkerHalf, f.px(p.counted) + kMarkerHalf,
                               f.py(p.y) + kMarkerHalf});
        }
    }
    // Isolated markers first: they keep their labels beside them, and the crowded ones take the
    // space that is left, with leader lines.
    std::vector<size_t>& order = labels.order;
    order.resize(texts.size());
    std::vector<int> neighbours(texts.size(), 0);
    for (size_t i = 0; i < texts.size(); ++i) {
        order[i] = i;
        for (const LabelText& t : texts)
            neighbours[i] += std::hypot(t.anchorX - texts[i].anchorX, t.anchorY - texts[i].anchorY) < 60;
    }
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        if (neighbours[a] != neighbours[b]) return neighbours[a] < neighbours[b];
        if (texts[a].anchorX != texts[b].anchorX) return texts[a].anchorX < texts[b].anchorX;
        return texts[a].anchorY < texts[b].anchorY;
    });
    std::vector<LabelRequest> requests;
    for (size_t i : order)
        requests.push_back({texts[i].anchorX, texts[i].anchorY, labelTextWidth(texts[i].text, kLabelFont),
                            kLabelFont * (kLabelAscent + kLabelDescent)});
    const PlotBox area{f.left + 2, f.top - f.topLane + 2, f.left + f.plotW - 2, f.axisBottom + f.zeroLane};
    labels.placed = placeLabels(requests, markers, lines, area);
    // A label with no room in the plot went under it: move that column below the axis title.
    labels.height = f.xTitleY + 12;
    const double overflowShift = f.xTitleY + 12 - area.y1;
    for (PlacedLabel& l : labels.placed)
        if (l.box.y0 >= area.y1) {
            l.box.y0 += overflowShift, l.box.y1 += overflowShift, l.leaderY += overflowShift;
            labels.height = std::max(labels.height, l.box.y1 + 6);
        }
    return labels;
}

// The SVG's opening, the grid, the ticks, the lanes and the axis titles.
void writeAxes(std::string& out, const PlotPoints& c, const PlotFrame& f, double H) {
    const PlotSpec& spec = f.spec;
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + formatFixed(f.W, 0) + " " + formatFixed(H, 0) +
           "\" role=\"img\" aria-label=\"" + htmlEscape(spec.yLabel) + f.scaleName + " against bytes per pixel\" "
           "font-family=\"system-ui, 'DejaVu Sans', Arial, sans-serif\" font-size=\"12\">\n";
    // Grid and ticks.
    out += "<g stroke=\"#e3e7eb\" stroke-width=\"1\">\n";
    for (double x = f.xa.lo; x <= f.xa.hi + f.xa.step * 1e-6; x += f.xa.step)
        out += "<line x1=\"" + f1(f.px(x)) + "\" y1=\"" + f1(f.top) + "\" x2=\"" + f1(f.px(x)) + "\" y2=\"" +
               f1(f.axisBottom) + "\"/>\n";
    for (double y : f.yTicks)
        out += "<line x1=\"" + f1(f.left) + "\" y1=\"" + f1(f.py(y)) + "\" x2=\"" + f1(f.left + f.plotW) + "\" y2=\"" +
               f1(f.py(y)) + "\"/>\n";
    out += "</g>\n<rect x=\"" + f1(f.left) + "\" y=\"" + f1(f.top) + "\" width=\"" + f1(f.plotW) + "\" height=\"" +
           f1(f.plotH) + "\" fill=\"none\" stroke=\"#9aa5b1\"/>\n<g fill=\"#5b6672\">\n";
    for (double x = f.xa.lo; x <= f.xa.hi + f.xa.step * 1e-6; x += f.xa.step)
        out += "<text x=\"" + f1(f.px(x)) + "\" y=\"" + f1(f.xTickY) + "\" text-anchor=\"middle\">" +
               formatFixed(x, f.xa.decimals) + "</text>\n";
    for (double y : f.yTicks)
        out += "<text x=\"" + f1(f.left - 6) + "\" y=\"" + f1(f.py(y) + 4) + "\" text-anchor=\"end\">" + f.yTickText(y) +
               "</text>\n";
    if (c.anyInfinite)
        out += "<text x=\"" + f1(f.left - 6) + "\" y=\"" + f1(f.py(INFINITY) + 5) +
               "\" text-anchor=\"end\" font-size=\"15\">" + kInfinity + "</text>\n<line x1=\"" + f1(f.left) +
               "\" y1=\"" + f1(f.py(INFINITY)) + "\" x2=\"" + f1(f.left + f.plotW) + "\" y2=\"" + f1(f.py(INFINITY)) +
               "\" stroke=\"#e3e7eb\" stroke-dasharray=\"3 3\"/>\n";
    if (c.anyZero)
        out += "<text x=\"" + f1(f.left - 6) + "\" y=\"" + f1(f.py(0) + 4) + "\" text-anchor=\"end\">0</text>\n<line x1=\"" +
               f1(f.left) + "\" y1=\"" + f1(f.py(0)) + "\" x2=\"" + f1(f.left + f.plotW) + "\" y2=\"" + f1(f.py(0)) +
               "\" stroke=\"#e3e7eb\" stroke-dasharray=\"3 3\"/>\n";
    out += "<text x=\"" + f1(f.left + f.plotW / 2) + "\" y=\"" + f1(f.xTitleY) +
           "\" text-anchor=\"middle\" fill=\"#1d232b\">" +
           std::string(*spec.xClass ? std::string("Effective bytes per pixel (") + spec.xClass + "): targets as stored + depth + light buffers"
                                    : std::string("Bytes per pixel: targets + depth + light buffers")) +
           (c.anyVisibility ? "; a visibility buffer also at what the verdict counts (hollow diamond)" : "") +
           "</text>\n";
    out += "<text transform=\"translate(16 " + f1(f.top + f.plotH / 2) + ") rotate(-90)\" text-anchor=\"middle\" "
           "fill=\"#1d232b\">" + htmlEscape(spec.yLabel) + f.scaleName + "</text>\n</g>\n";
}

void writeFronts(std::string& out, const std::vector<Front>& fronts) {
    for (const Front& f : fronts) {
        std::string line;
        for (const auto& [x, y] : f.points) line += f1(x) + "," + f1(y) + " ";
        line.pop_back();
        out += std::string("<polyline class=\"pareto\" data-kind=\"") + (f.visibility ? "visibility" : "gbuffer") +
               "\" fill=\"none\" stroke=\"" + kSeriesColors[f.series % 7] + "\" stroke-width=\"2\" stroke-opacity=\"0.75\"" +
               (f.visibility ? " stroke-dasharray=\"7 4\"" : "") + " points=\"" + line + "\"/>\n";
    }
}

// Markers: each a link to its run's section, named on hover by the page's script (and its title).
void writeMarkers(std::string& out, const ReportModel& model, const std::vector<std::string>& runIds,
                  const PlotPoints& c, const PlotFrame& f) {
    const PlotSpec& spec = f.spec;
    for (size_t k = 0; k < c.points.size(); ++k) {
        const Point& p = c.points[k];
        const RunReport& r = model.runs[p.run];
        const char* color = kSeriesColors[p.series % 7];
        const std::string cx = f1(f.px(p.x)), cy = f1(f.py(p.y)), id = runIds[p.run];
        const std::string info = r.layout + " (IBL " + r.iblMode + "): " + formatFixed(p.x, 0) + " B/px, " +
                                 spec.yLabel + " " + spec.format(p.y);
        const std::string link = "<a class=\"pt\" href=\"#" + id + "\" data-pt=\"" + std::to_string(k) + "\" data-info=\"";
        if (!p.visibility) {
            out += link + htmlEscape(info) + "\"><circle cx=\"" + cx + "\" cy=\"" + cy + "\" r=\"4.5\" fill=\"" + color +
                   "\" stroke=\"#fff\" stroke-width=\"1\"><title>" + htmlEscape(info) + "</title></circle></a>\n";
            continue;
        }
        const std::string counted = r.layout + " (IBL " + r.iblMode + ") counted with half its modelled vertex "
                                    "fetches (no cache reuse): " + formatSignificant(p.counted, 3) + " B/px, " +
                                    spec.yLabel + " " + spec.format(p.y);
        const auto shape = [&](bool hollow) {
            const double cxv = f.px(hollow ? p.counted : p.x), cyv = f.py(p.y);
            return "<polygon points=\"" + f1(cxv) + "," + f1(cyv - 5.5) + " " + f1(cxv + 5.5) + "," + f1(cyv) + " " +
                   f1(cxv) + "," + f1(cyv + 5.5) + " " + f1(cxv - 5.5) + "," + f1(cyv) + "\" fill=\"" +
                   (hollow ? "#fff" : color) + "\" stroke=\"" + (hollow ? color : "#fff") + "\" stroke-width=\"" +
                   (hollow ? "2" : "1") + "\">";
        };
        out += "<line class=\"fetches\" x1=\"" + f1(f.px(p.x) + 6) + "\" y1=\"" + cy + "\" x2=\"" +
               f1(f.px(p.counted) - 6) + "\" y2=\"" + cy + "\" stroke=\"" + color +
               "\" stroke-width=\"1.5\" stroke-dasharray=\"4 3\"/>\n";
        out += link + htmlEscape(info + " of ids and depth") + "\">" + shape(false) + "<title>" +
               htmlEscape(info + " of ids and depth") + "</title></polygon></a>\n";
        out += link + htmlEscape(counted) + "\">" + shape(true) + "<title>" + htmlEscape(counted) +
               "</title></polygon></a>\n";
    }
}

// Leader lines under the labels, then the labels, each pinned to the width it was placed with.
void writeLabels(std::string& out, const std::vector<std::string>& runIds, const PlotLabels& labels) {
    out += "<g stroke=\"#8a949e\" stroke-width=\"0.8\">\n";
    for (size_t j = 0; j < labels.order.size(); ++j) {
        const PlacedLabel& l = labels.placed[j];
        if (!l.leader) continue;
        const LabelText& t = labels.texts[labels.order[j]];
        const double dx = l.leaderX - t.anchorX, dy = l.leaderY - t.anchorY, d = std::hypot(dx, dy);
        if (d <= kMarkerHalf + 1) continue;
        out += "<line class=\"leader\" x1=\"" + f1(t.anchorX + dx / d * (kMarkerHalf + 1)) + "\" y1=\"" +
               f1(t.anchorY + dy / d * (kMarkerHalf + 1)) + "\" x2=\"" + f1(l.leaderX) + "\" y2=\"" + f1(l.leaderY) +
               "\"/>\n";
    }
    out += "</g>\n<g font-size=\"11\" fill=\"#1d232b\">\n";
    for (size_t j = 0; j < labels.order.size(); ++j) {
        const PlacedLabel& l = labels.placed[j];
        const LabelText& t = labels.texts[labels.order[j]];
        out += "<a href=\"#" + runIds[t.run] + "\"><text class=\"label\" data-pt=\"" + std::to_string(t.point) +
               "\" x=\"" + formatFixed(l.box.x0, 2) + "\" y=\"" + formatFixed(l.box.y0 + kLabelFont * kLabelAscent, 2) +
               "\" textLength=\"" + formatFixed(l.box.x1 - l.box.x0, 2) + "\">" + htmlEscape(t.text) + "</text></a>\n";
    }
    out += "</g>\n</svg>\n";
}

// The readout line and the legend: the series shown, the fronts, the lanes.
void writeLegend(std::string& out, const PlotPoints& c, const PlotSpec& spec) {
    out += "<p class=\"plot-readout\" aria-live=\"polite\">Point at a marker to name it; click it (or its "
           "label) to open its section.</p>\n<div class=\"legend\">";
    for (size_t s = 0; s < c.modes.size(); ++s) {
        if (std::none_of(c.points.begin(), c.points.end(), [&](const Point& p) { return p.series == s; })) continue;
        out += std::string("<span><svg width=\"12\" height=\"12\" viewBox=\"0 0 12 12\"><circle cx=\"6\" cy=\"6\" "
                           "r=\"4.5\" fill=\"") +
               kSeriesColors[s % 7] + "\"/></svg>layouts, IBL " + htmlEscape(c.modes[s]) + "</span>";
    }
    const char* better = spec.higherIsBetter ? "higher" : "lower";
    out += std::string("<span><svg width=\"26\" height=\"12\" viewBox=\"0 0 26 12\"><line x1=\"1\" y1=\"6\" x2=\"25\" "
                       "y2=\"6\" stroke=\"#5b6672\" stroke-width=\"2\"/></svg>Pareto front of the G-buffer layouts "
                       "(deferred shading and deferred lighting), per IBL mode: no such layout is both smaller and ") +
           better + "</span>";
    if (c.anyVisibility)
        out += std::string("<span><svg width=\"26\" height=\"12\" viewBox=\"0 0 26 12\"><line x1=\"1\" y1=\"6\" x2=\"25\" "
                           "y2=\"6\" stroke=\"#5b6672\" stroke-width=\"2\" stroke-dasharray=\"7 4\"/></svg>Pareto front "
                           "of the visibility buffers, at their counted bytes</span><span><svg width=\"40\" height=\"12\" "
                           "viewBox=\"0 0 40 12\"><polygon points=\"6,0.5 11.5,6 6,11.5 0.5,6\" fill=\"#5b6672\"/>"
                           "<line x1=\"13\" y1=\"6\" x2=\"27\" y2=\"6\" stroke=\"#5b6672\" stroke-dasharray=\"4 3\"/>"
                           "<polygon points=\"34,1 39,6 34,11 29,6\" fill=\"#fff\" stroke=\"#5b6672\" stroke-width=\"2\"/>"
                           "</svg>visibility buffer: its ids and depth, then those plus half its resolve's modelled "
                           "vertex fetches (no cache reuse), the G-buffer size that moves as many bytes: what the "
                           "verdict counts</span>");
    if (c.anyInfinite) out += std::string("<span>") + kInfinity + ": identical to the reference</span>";
    if (c.anyZero) out += "<span>0 (under the log axis): identical to the reference</span>";
    if (c.skippedLighting)
        out += "<span>the lighting comparisons (reference (&lt;mode&gt; vs ground-truth)) are not plotted: their "
               "errors are against ground truth</span>";
    out += "</div>\n</figure>\n";
}

}  // namespace

void writePlot(std::string& out, const ReportModel& model, const std::vector<std::string>& runIds,
               const PlotSpec& spec, bool hidden) {
    PlotPoints points = collectPoints(model, spec);
    out += std::string("<figure class=\"plot\" id=\"plot-") + spec.id + "\"" + (hidden ? " hidden" : "") + ">\n";
    if (points.points.empty()) {
        out += "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 1080 200\" role=\"img\" aria-label=\"" +
               htmlEscape(spec.yLabel) + " against bytes per pixel\" font-family=\"system-ui, 'DejaVu Sans', Arial, "
               "sans-serif\" font-size=\"12\">\n<text x=\"540\" y=\"100\" text-anchor=\"middle\" fill=\"#5b6672\">"
               "No measured runs to plot.</text>\n</svg>\n</figure>\n";
        return;
    }
    PlotFrame frame = planFrame(points, spec);
    planAxes(frame, points, spec);
    std::vector<PlotLine> lines;  // what the labels must not cover: the fronts and the connectors
    const std::vector<Front> fronts = paretoFronts(points, frame, spec, lines);
    // The labels next: where they land decides the picture's height.
    const PlotLabels labels = placePointLabels(model, points, frame, lines);
    writeAxes(out, points, frame, labels.height);
    writeFronts(out, fronts);
    writeMarkers(out, model, runIds, points, frame);
    writeLabels(out, runIds, labels);
    writeLegend(out, points, spec);
}

}  // namespace gbl
