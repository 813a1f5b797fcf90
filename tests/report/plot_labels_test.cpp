// Label placement for the report's plot: on a crowd like a real report's (many layouts within a
// few bytes and a decade of error), no label overlaps another label or any marker, all stay in
// the plot or covers a line (a front), a lone point keeps its label beside it, leaders end on their label's box, and the
// result depends on nothing but the input.
#include <gtest/gtest.h>

#include <cmath>

#include "plot_labels.h"

namespace gbl {
namespace {

constexpr double kHeight = 11 * (kLabelAscent + kLabelDescent);

struct Scene {
    std::vector<LabelRequest> labels;
    std::vector<PlotBox> markers;
    std::vector<PlotLine> lines;
};

void addPoint(Scene& s, double x, double y, const std::string& name) {
    s.labels.push_back({x, y, labelTextWidth(name, 11), kHeight});
    s.markers.push_back({x - 5, y - 5, x + 5, y + 5});
}

// 18 points in an 80 x 200 band (the G-buffer layouts between 16 and 25 B/px), two apart.
Scene crowd() {
    Scene s;
    for (int i = 0; i < 18; ++i)
        addPoint(s, 200 + (i * 37) % 80, 180 + (i * 53) % 200, "crysis2-slim-x360-" + std::to_string(i));
    addPoint(s, 120, 420, "visibility-32");
    addPoint(s, 700, 40, "outlier");
    s.lines = {{120, 420, 900, 420}, {200, 180, 279, 380}, {279, 380, 600, 300}};  // a connector, a front
    return s;
}

// Whether the line passes through the box: sampled every 0.25 px, finer than any gap kept.
bool lineHits(const PlotLine& l, const PlotBox& b) {
    const int steps = int(std::hypot(l.x1 - l.x0, l.y1 - l.y0) * 4) + 1;
    for (int i = 0; i <= steps; ++i) {
        const double t = double(i) / steps, x = l.x0 + (l.x1 - l.x0) * t, y = l.y0 + (l.y1 - l.y0) * t;
        if (x > b.x0 && x < b.x1 && y > b.y0 && y < b.y1) return true;
    }
    return false;
}

bool segmentsCross(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy) {
    const auto side = [](double px, double py, double qx, double qy, double rx, double ry) {
        const double c = (qx - px) * (ry - py) - (qy - py) * (rx - px);
        return (c > 0) - (c < 0);
    };
    return side(ax, ay, bx, by, cx, cy) * side(ax, ay, bx, by, dx, dy) < 0 &&
           side(cx, cy, dx, dy, ax, ay) * side(cx, cy, dx, dy, bx, by) < 0;
}

TEST(PlotLabels, ACrowdGetsLabelsThatOverlapNothing) {
    const Scene s = crowd();
    const PlotBox area{76, 18, 1060, 456};
    const auto placed = placeLabels(s.labels, s.markers, s.lines, area);
    ASSERT_EQ(placed.size(), s.labels.size());
    int leaders = 0;
    for (size_t i = 0; i < placed.size(); ++i) {
        SCOPED_TRACE(i);
        const PlotBox& b = placed[i].box;
        EXPECT_TRUE(area.contains(b)) << b.x0 << "," << b.y0 << " " << b.x1 << "," << b.y1;
        EXPECT_NEAR(b.x1 - b.x0, s.labels[i].width, 1e-9);
        EXPECT_NEAR(b.y1 - b.y0, kHeight, 1e-9);
        for (size_t j = 0; j < placed.size(); ++j) {
            if (j == i) continue;
            EXPECT_FALSE(b.intersects(placed[j].box)) << "labels " << i << " and " << j;
        }
        for (const PlotBox& m : s.markers) EXPECT_FALSE(b.intersects(m)) << "a label covers a marker";
        for (const PlotLine& l : s.lines) EXPECT_FALSE(lineHits(l, b)) << "a label covers a line";
        if (placed[i].leader) {
            ++leaders;
            // The leader ends on the box, at its point nearest the marker.
            EXPECT_GE(placed[i].leaderX, b.x0);
            EXPECT_LE(placed[i].leaderX, b.x1);
            EXPECT_GE(placed[i].leaderY, b.y0);
            EXPECT_LE(placed[i].leaderY, b.y1);
        }
    }
    // 18 labels about 110 px wide cannot all sit beside markers 20 px apart: some need leaders,
    // and no two leaders cross.
    EXPECT_GT(leaders, 0);
    for (size_t i = 0; i < placed.size(); ++i)
        for (size_t j = i + 1; j < placed.size(); ++j)
            if (placed[i].leader && placed[j].leader) {
                EXPECT_FALSE(segmentsCross(s.labels[i].anchorX, s.labels[i].anchorY, placed[i].leaderX,
                                           placed[i].leaderY, s.labels[j].anchorX, s.labels[j].anchorY,
                                           placed[j].leaderX, placed[j].leaderY))
                    << "leaders " << i << " and " << j;
            }
}

TEST(PlotLabels, ALonePointKeepsItsLabelBesideIt) {
    const Scene s = crowd();
    const auto placed = placeLabels(s.labels, s.markers, s.lines, {76, 18, 1060, 456});
    const PlacedLabel& outlier = placed.back();
    EXPECT_FALSE(outlier.leader);
    const double dx = std::max({outlier.box.x0 - 700, 0.0, 700 - outlier.box.x1});
    const double dy = std::max({outlier.box.y0 - 40, 0.0, 40 - outlier.box.y1});
    EXPECT_LT(std::hypot(dx, dy), 12.0);
}

// Two markers 35 units apart on one line (a visibility buffer's and its neighbour's): the first
// label cannot go right (the second marker is there) nor above or below on the right, where it
// would be as near the second marker as its own, so it goes left.
TEST(PlotLabels, ALabelWithoutLeaderIsNearerItsMarkerThanAnyOther) {
    Scene s;
    addPoint(s, 200, 300, "visibility-32");
    addPoint(s, 235, 300, "visibility-64");
    s.lines = {{206, 300, 900, 300}};
    const auto placed = placeLabels(s.labels, s.markers, s.lines, {76, 18, 1060, 456});
    for (size_t i = 0; i < 2; ++i) {
        SCOPED_TRACE(i);
        ASSERT_FALSE(placed[i].leader);
        const PlotBox& b = placed[i].box;
        const auto distance = [&](const LabelRequest& r) {
            return std::hypot(std::max({b.x0 - r.anchorX, 0.0, r.anchorX - b.x1}),
                              std::max({b.y0 - r.anchorY, 0.0, r.anchorY - b.y1}));
        };
        EXPECT_LT(distance(s.labels[i]), distance(s.labels[1 - i]));
    }
    EXPECT_LE(placed[0].box.x1, 200.0);  // left of its marker
}

TEST(PlotLabels, SameInputSamePlacement) {
    const Scene s = crowd();
    const auto a = placeLabels(s.labels, s.markers, s.lines, {76, 18, 1060, 456});
    const auto b = placeLabels(s.labels, s.markers, s.lines, {76, 18, 1060, 456});
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].box.x0, b[i].box.x0);
        EXPECT_EQ(a[i].box.y0, b[i].box.y0);
        EXPECT_EQ(a[i].leader, b[i].leader);
    }
}

TEST(PlotLabels, WhatFindsNoRoomGoesBelowTheAreaStillApart) {
    Scene s;
    for (int i = 0; i < 12; ++i) addPoint(s, 60 + 10 * i, 30, "a-long-layout-name-" + std::to_string(i));
    const PlotBox area{0, 0, 200, 60};  // room for a few labels only
    const auto placed = placeLabels(s.labels, s.markers, s.lines, area);
    int below = 0;
    for (size_t i = 0; i < placed.size(); ++i) {
        below += placed[i].box.y0 >= area.y1;
        EXPECT_TRUE(area.contains(placed[i].box) || placed[i].box.y0 >= area.y1) << i;
        for (size_t j = 0; j < i; ++j) EXPECT_FALSE(placed[i].box.intersects(placed[j].box)) << i << " " << j;
    }
    EXPECT_GT(below, 0);
}

TEST(PlotLabels, TextWidthIsDejaVuSansAdvances) {
    EXPECT_DOUBLE_EQ(labelTextWidth("m", 11), 1995.0 / 2048.0 * 11);
    EXPECT_DOUBLE_EQ(labelTextWidth("ue4", 11),
                     (1298.0 + 1260.0 + 1303.0) / 2048.0 * 11);
    // Outside ASCII: one em per character, whatever its UTF-8 length.
    EXPECT_DOUBLE_EQ(labelTextWidth("\xC3\xA9", 10), 10.0);
    EXPECT_DOUBLE_EQ(labelTextWidth("", 11), 0.0);
}

}  // namespace
}  // namespace gbl
