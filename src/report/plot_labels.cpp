#include "plot_labels.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <optional>
#include <tuple>
#include <utility>

namespace gbl {
namespace {

constexpr double kGap = 2;       // kept clear around every marker and line
constexpr double kWordGap = 6;   // between labels side by side: less reads as one name
// From a marker's centre to a label set beside it: past the marker's half size (5), the gap kept
// around it and the rounding of the occupancy grid to whole units.
constexpr double kBeside = 8;
constexpr double kGridStep = 3;  // the search for a free spot: fine enough to find gaps one line tall
constexpr double kNearReach = 160;  // how far a label goes for a leader that crosses nothing
constexpr int kLeaderTries = 600;   // free spots tried for a clear leader before the nearest is taken

// DejaVu Sans advance widths of ' ' .. '~', in font units (2048 per em), from its hmtx table.
constexpr int kAdvance[95] = {
    651,  821,  942,  1716, 1303, 1946, 1597, 563,  799,  799,  1024, 1716, 651,  739,  651,  690,
    1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 690,  690,  1716, 1716, 1716, 1087,
    2048, 1401, 1405, 1430, 1577, 1294, 1178, 1587, 1540, 604,  604,  1343, 1141, 1767, 1532, 1612,
    1235, 1612, 1423, 1300, 1251, 1499, 1401, 2025, 1403, 1251, 1403, 799,  690,  799,  1716, 1024,
    1024, 1255, 1300, 1126, 1300, 1260, 721,  1300, 1298, 569,  569,  1186, 569,  1995, 1298, 1253,
    1300, 1300, 842,  1067, 803,  1298, 1212, 1675, 1212, 1212, 1075, 1303, 690,  1303, 1716};

PlotBox padded(const PlotBox& b, double by) { return {b.x0 - by, b.y0 - by, b.x1 + by, b.y1 + by}; }

double distanceTo(const PlotBox& b, double x, double y) {
    return std::hypot(std::max({b.x0 - x, 0.0, x - b.x1}), std::max({b.y0 - y, 0.0, y - b.y1}));
}

// Whether the segment (ax, ay)-(bx, by) passes through `box` (Liang-Barsky clipping).
bool segmentHits(double ax, double ay, double bx, double by, const PlotBox& box) {
    double t0 = 0, t1 = 1;
    const double dx = bx - ax, dy = by - ay;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {ax - box.x0, box.x1 - ax, ay - box.y0, box.y1 - ay};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0) {
            if (q[i] < 0) return false;
            continue;
        }
        const double t = q[i] / p[i];
        if (p[i] < 0) t0 = std::max(t0, t);
        else t1 = std::min(t1, t);
        if (t0 > t1) return false;
    }
    return true;
}

using Segment = PlotLine;

bool segmentsCross(const Segment& s, const Segment& t) {
    const auto side = [](double ax, double ay, double bx, double by, double px, double py) {
        const double c = (bx - ax) * (py - ay) - (by - ay) * (px - ax);
        return (c > 0) - (c < 0);
    };
    return side(s.x0, s.y0, s.x1, s.y1, t.x0, t.y0) * side(s.x0, s.y0, s.x1, s.y1, t.x1, t.y1) < 0 &&
           side(t.x0, t.y0, t.x1, t.y1, s.x0, s.y0) * side(t.x0, t.y0, t.x1, t.y1, s.x1, s.y1) < 0;
}

// What is taken, one cell per unit of the picture, with each row's running sums so that whether a
// box is free costs two look-ups per row whatever the number of labels (a report of 80 runs has 80
// labels per plot, each trying thousands of spots); a mark refreshes only the rows it touched.
// Cells are marked and queried outward to whole units, so a box found free overlaps nothing marked.
class Occupancy {
public:
    explicit Occupancy(const PlotBox& area)
        : x0_(int(std::floor(area.x0)) - 1), y0_(int(std::floor(area.y0)) - 1),
          w_(int(std::ceil(area.x1)) - x0_ + 2), h_(int(std::ceil(area.y1)) - y0_ + 2),
          cells_(size_t(w_) * size_t(h_), 0), sums_(size_t(w_ + 1) * size_t(h_), 0) {}

    void mark(const PlotBox& b) {
        const auto [i0, j0, i1, j1] = cellsOf(b);
        for (int j = j0; j < j1; ++j)
            for (int i = i0; i < i1; ++i) cells_[size_t(j) * size_t(w_) + size_t(i)] = 1;
        if (j1 > j0) staleBegin_ = std::min(staleBegin_, j0), staleEnd_ = std::max(staleEnd_, j1);
    }
    // Every cell within `pad` of the line.
    void mark(const PlotLine& l, double pad) {
        const double length = std::hypot(l.x1 - l.x0, l.y1 - l.y0);
        const int steps = int(std::ceil(length / 0.5)) + 1;
        for (int k = 0; k <= steps; ++k) {
            const double t = double(k) / steps, x = l.x0 + (l.x1 - l.x0) * t, y = l.y0 + (l.y1 - l.y0) * t;
            mark(PlotBox{x - pad, y - pad, x + pad, y + pad});
        }
    }
    bool free(const PlotBox& b) {
        refresh();
        const auto [i0, j0, i1, j1] = cellsOf(b);
        for (int j = j0; j < j1; ++j) {
            const int32_t* row = &sums_[size_t(j) * size_t(w_ + 1)];
            if (row[i1] != row[i0]) return false;
        }
        return true;
    }

private:
    std::array<int, 4> cellsOf(const PlotBox& b) const {
        const auto clampX = [&](double v) { return std::clamp(int(v), 0, w_); };
        const auto clampY = [&](double v) { return std::clamp(int(v), 0, h_); };
        return {clampX(std::floor(b.x0) - x0_), clampY(std::floor(b.y0) - y0_), clampX(std::ceil(b.x1) - x0_),
                clampY(std::ceil(b.y1) - y0_)};
    }
    void refresh() {
        for (int j = staleBegin_; j < staleEnd_; ++j) {
            int32_t* row = &sums_[size_t(j) * size_t(w_ + 1)];
            for (int i = 0; i < w_; ++i) row[i + 1] = row[i] + cells_[size_t(j) * size_t(w_) + size_t(i)];
        }
        staleBegin_ = h_, staleEnd_ = 0;
    }
    int x0_, y0_, w_, h_;
    std::vector<uint8_t> cells_;
    std::vector<int32_t> sums_;  // per row: sums_[j][i] = taken cells left of column i
    int staleBegin_ = 0, staleEnd_ = h_;
};

struct Placer {
    const std::vector<PlotBox>& markers;
    Occupancy taken;
    std::vector<PlotBox> boxes;
    std::vector<Segment> leaders;

    Placer(const std::vector<PlotBox>& m, const std::vector<PlotLine>& lines, const PlotBox& area)
        : markers(m), taken(area) {
        for (const PlotBox& b : markers) taken.mark(padded(b, kGap));
        for (const PlotLine& l : lines) taken.mark(l, kGap);
    }
    bool free(const PlotBox& b) { return taken.free(b); }
    // A label without a leader names the marker nearest to it: no other marker may be as close.
    bool unambiguous(const PlotBox& b, const LabelRequest& own) const {
        const double mine = distanceTo(b, own.anchorX, own.anchorY);
        for (const PlotBox& m : markers) {
            const double cx = (m.x0 + m.x1) / 2, cy = (m.y0 + m.y1) / 2;
            if (std::hypot(cx - own.anchorX, cy - own.anchorY) < 1.0) continue;  // its own (or one on top of it)
            if (distanceTo(b, cx, cy) <= mine) return false;
        }
        return true;
    }
    // A leader that passes near no other marker and crosses no label or leader: it reads unambiguously.
    bool clearLeader(const Segment& s, const LabelRequest& own) const {
        for (const PlotBox& m : markers) {
            const bool mine = own.anchorX >= m.x0 && own.anchorX <= m.x1 && own.anchorY >= m.y0 && own.anchorY <= m.y1;
            if (!mine && segmentHits(s.x0, s.y0, s.x1, s.y1, padded(m, kGap + 2))) return false;
        }
        for (const PlotBox& o : boxes)
            if (segmentHits(s.x0, s.y0, s.x1, s.y1, o)) return false;
        for (const Segment& t : leaders)
            if (segmentsCross(s, t)) return false;
        return true;
    }
    void take(PlacedLabel& out, const PlotBox& b, const LabelRequest& r, bool leader) {
        out.box = b;
        out.leader = leader;
        out.leaderX = std::clamp(r.anchorX, b.x0, b.x1);
        out.leaderY = std::clamp(r.anchorY, b.y0, b.y1);
        boxes.push_back(b);
        taken.mark(PlotBox{b.x0 - kWordGap, b.y0 - kGap, b.x1 + kWordGap, b.y1 + kGap});
        if (leader) {
            leaders.push_back({r.anchorX, r.anchorY, out.leaderX, out.leaderY});
            taken.mark(leaders.back(), kGap);
        }
    }
};

}  // namespace

std::vector<PlacedLabel> placeLabels(const std::vector<LabelRequest>& labels, const std::vector<PlotBox>& markers,
                                     const std::vector<PlotLine>& lines, const PlotBox& area) {
    Placer placer(markers, lines, area);
    std::vector<PlacedLabel> out(labels.size());
    std::vector<bool> done(labels.size(), false);
    // First every label that fits beside its marker, nearer to it than to any other, so the sparse
    // points keep their labels close.
    for (size_t i = 0; i < labels.size(); ++i) {
        const LabelRequest& r = labels[i];
        const double x = r.anchorX, y = r.anchorY, w = r.width, h = r.height, d = kBeside, o = kBeside / 2;
        const PlotBox beside[] = {
            {x + d, y - h / 2, x + d + w, y + h / 2}, {x + o, y - d - h, x + o + w, y - d},
            {x + o, y + d, x + o + w, y + d + h},     {x - d - w, y - h / 2, x - d, y + h / 2},
            {x - o - w, y - d - h, x - o, y - d},     {x - o - w, y + d, x - o, y + d + h},
            {x - w / 2, y - d - h, x + w / 2, y - d}, {x - w / 2, y + d, x + w / 2, y + d + h}};
        for (const PlotBox& b : beside)
            if (area.contains(b) && placer.free(b) && placer.unambiguous(b, r)) {
                placer.take(out[i], b, r, false);
                done[i] = true;
                break;
            }
    }
    // Then the rest at the nearest free spot, joined to their markers by a line.
    double overflowY = area.y1 + kGap;
    for (size_t i = 0; i < labels.size(); ++i) {
        if (done[i]) continue;
        const LabelRequest& r = labels[i];
        // Near spots first, farther ones for a clear leader, the whole area only when nothing near is
        // free: most labels land close by, and sorting few spots is what keeps this fast.
        std::optional<std::pair<double, PlotBox>> chosen, firstFree;
        for (const double reach : {kNearReach / 4, kNearReach, double(INFINITY)}) {
            std::vector<std::tuple<double, double, double>> spots;  // (squared distance, y0, x0)
            // The grid's columns and rows that can be within reach.
            const auto first = [&](double from, double lo) {
                return lo + std::max(0.0, std::ceil((from - lo) / kGridStep)) * kGridStep;
            };
            const double xBegin = first(r.anchorX - reach - r.width, area.x0);
            const double yBegin = first(r.anchorY - reach - r.height, area.y0);
            const double xEnd = std::min(area.x1 - r.width, r.anchorX + reach);
            const double yEnd = std::min(area.y1 - r.height, r.anchorY + reach);
            for (double y0 = yBegin; y0 <= yEnd; y0 += kGridStep)
                for (double x0 = xBegin; x0 <= xEnd; x0 += kGridStep) {
                    const double dx = std::max({x0 - r.anchorX, 0.0, r.anchorX - (x0 + r.width)});
                    const double dy = std::max({y0 - r.anchorY, 0.0, r.anchorY - (y0 + r.height)});
                    const double squared = dx * dx + dy * dy;
                    if (squared <= reach * reach) spots.emplace_back(squared, y0, x0);
                }
            std::sort(spots.begin(), spots.end());
            int tried = 0;
            for (const auto& [squared, y0, x0] : spots) {
                const double distance = std::sqrt(squared);
                const PlotBox b{x0, y0, x0 + r.width, y0 + r.height};
                if (!placer.free(b)) continue;
                if (!firstFree) firstFree = {distance, b};
                const Segment s{r.anchorX, r.anchorY, std::clamp(r.anchorX, b.x0, b.x1), std::clamp(r.anchorY, b.y0, b.y1)};
                if (placer.clearLeader(s, r)) {
                    chosen = {distance, b};
                    break;
                }
                if (++tried == kLeaderTries) break;
            }
            if (chosen || (firstFree && reach >= kNearReach)) break;
        }
        if (!chosen) chosen = firstFree;
        if (!chosen) {  // the area is full: a column below it
            chosen = {INFINITY, PlotBox{area.x0, overflowY, area.x0 + r.width, overflowY + r.height}};
            overflowY = chosen->second.y1 + kGap * 2;
        }
        const bool near = chosen->first <= kBeside + kGridStep && placer.unambiguous(chosen->second, r);
        placer.take(out[i], chosen->second, r, !near);
    }
    return out;
}

double labelTextWidth(const std::string& text, double fontSize) {
    double units = 0;
    for (unsigned char ch : text) {
        if (ch >= 32 && ch < 127) units += kAdvance[ch - 32];
        else if ((ch & 0xC0) != 0x80) units += 2048;  // a character outside ASCII (continuation bytes add nothing)
    }
    return units / 2048.0 * fontSize;
}

}  // namespace gbl
