// compare's band plan (compare_bands.h): the bands cover every row of the frame exactly once, in
// order; each band's images hold its rows and `halo` rows each side, clamped to the frame; bands
// start on multiples of 8 (the worst regions' tiles); and --band-rows is parsed with one clear error.
#include <gtest/gtest.h>

#include "compare_bands.h"
#include "compare_memory.h"
#include "error.h"
#include "gpu_evaluator.h"

namespace {

using gbl::compare::BandPlan;
using gbl::compare::planBands;

void expectCovers(const BandPlan& plan, uint32_t height, uint32_t bandRows, uint32_t halo) {
    uint32_t next = 0, maxRows = 0;
    for (const gbl::EvalBand& b : plan.bands) {
        EXPECT_EQ(b.firstRow, next);
        EXPECT_EQ(b.firstRow % 8, 0u);
        EXPECT_GT(b.rows, 0u);
        EXPECT_LE(b.rows, bandRows);
        // The images: the band and min(halo, rows to the frame's edge) rows each side.
        const uint32_t above = std::min(halo, b.firstRow);
        const uint32_t below = std::min(halo, height - (b.firstRow + b.rows));
        EXPECT_EQ(b.imageFirstRow, b.firstRow - above);
        EXPECT_EQ(b.imageRows, above + b.rows + below);
        EXPECT_LE(b.imageFirstRow + b.imageRows, height);
        maxRows = std::max(maxRows, b.imageRows);
        next = b.firstRow + b.rows;
    }
    EXPECT_EQ(next, height);
    EXPECT_EQ(plan.maxImageRows(), maxRows);
    EXPECT_LE(plan.maxImageRows(), bandRows + 2 * halo);
}

TEST(CompareBands, PlansCoverTheFrameOnce) {
    for (uint32_t height : {1u, 7u, 8u, 61u, 120u, 2160u})
        for (uint32_t rows : {8u, 24u, 128u, 4096u})
            for (uint32_t halo : {0u, 3u, 11u}) {
                SCOPED_TRACE(std::to_string(height) + " rows, bands of " + std::to_string(rows) + ", halo " +
                             std::to_string(halo));
                const BandPlan plan = planBands(height, rows, halo);
                EXPECT_TRUE(plan.banded());
                EXPECT_EQ(plan.bands.size(), (height + rows - 1) / rows);
                expectCovers(plan, height, rows, halo);
            }
    EXPECT_FALSE(planBands(2160, 0, 11).banded());
    EXPECT_TRUE(planBands(2160, 0, 11).bands.empty());
    EXPECT_THROW(planBands(2160, 12, 11), std::invalid_argument);
}

TEST(CompareBands, AutoBandsOnlyOnACpuDeviceAbove4Mpx) {
    using gbl::compare::autoBandRows;
    EXPECT_EQ(autoBandRows(true, 3840, 2160), gbl::compare::kAutoBandRows);
    EXPECT_EQ(autoBandRows(true, 2048, 2049), gbl::compare::kAutoBandRows);  // 4,196,352 pixels
    EXPECT_EQ(autoBandRows(true, 2048, 2048), 0u);                           // 2^22 exactly: whole
    EXPECT_EQ(autoBandRows(true, 1920, 1080), 0u);
    EXPECT_EQ(autoBandRows(false, 3840, 2160), 0u);  // a GPU's memory is not the host's
}

TEST(CompareBands, FlagValuesAndConflicts) {
    using gbl::compare::parseBandRowsFlag;
    EXPECT_FALSE(parseBandRowsFlag("auto", false, false).has_value());
    EXPECT_EQ(parseBandRowsFlag("0", true, true).value(), 0u);  // whole frames go with anything
    EXPECT_EQ(parseBandRowsFlag("64", false, false).value(), 64u);
    for (const char* bad : {"12", "-8", "x", "", "64k", "99999999"})
        EXPECT_THROW(parseBandRowsFlag(bad, false, false), gbl::UserError) << bad;
    EXPECT_THROW(parseBandRowsFlag("64", true, false), gbl::UserError);   // --eval cpu
    EXPECT_THROW(parseBandRowsFlag("64", false, true), gbl::UserError);   // ground truth
}

// compare's memory estimate, checked before its first render: bands bound it, layouts and views
// add to it, and it stays above the measured peaks it was fitted to (compare_memory.cpp).
TEST(CompareBands, TheMemoryEstimateCountsBandsLayoutsAndViews) {
    using gbl::compare::compareMemoryBytes;
    constexpr double MiB = 1 << 20;
    const uint32_t bandImageRows = 64 + 2 * gbl::flipHaloRows();
    EXPECT_LT(compareMemoryBytes(3840, 2160, bandImageRows, 3, 3), 0.7 * compareMemoryBytes(3840, 2160, 0, 3, 3));
    EXPECT_LT(compareMemoryBytes(1024, 1024, 0, 3, 1), compareMemoryBytes(1024, 1024, 0, 19, 1));
    EXPECT_LT(compareMemoryBytes(1024, 1024, 0, 19, 1), compareMemoryBytes(1024, 1024, 0, 19, 3));
    EXPECT_EQ(compareMemoryBytes(1024, 1024, 1024, 3, 1), compareMemoryBytes(1024, 1024, 0, 3, 1));
    // Measured peaks (MiB): 3 layouts, 1 view: 664 / 1604 whole at 1024 / 2048 px a side, 321 / 627 in
    // 64-row bands; 19 layouts at 1024: 997 (1 view), 1082 (3 views).
    EXPECT_GT(compareMemoryBytes(1024, 1024, 0, 3, 1), 664 * MiB);
    EXPECT_GT(compareMemoryBytes(2048, 2048, 0, 3, 1), 1604 * MiB);
    EXPECT_GT(compareMemoryBytes(1024, 1024, bandImageRows, 3, 1), 321 * MiB);
    EXPECT_GT(compareMemoryBytes(2048, 2048, bandImageRows, 3, 1), 627 * MiB);
    EXPECT_GT(compareMemoryBytes(1024, 1024, 0, 19, 1), 997 * MiB);
    EXPECT_GT(compareMemoryBytes(1024, 1024, 0, 19, 3), 1082 * MiB);
}

}  // namespace
