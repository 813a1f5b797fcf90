// Memory sized by an input, checked before it is allocated, in the commands that render: the
// frame of `render --size` (whole or in bands), and an environment map whose header claims more
// than the budget. Run as the real executable and measured; every refusal comes before a Vulkan
// device exists, so these need no driver.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "hostile_images.h"
#include "image_io.h"
#include "measured_run.h"
#include "memory_budget.h"
#include "renderer.h"

namespace fs = std::filesystem;

namespace {

using namespace gbl::test;

const CliScratch scratch("gbl_input_bounds_test_");

std::string gib(double bytes) { return std::to_string(uint64_t(bytes / double(1 << 20))) + "M"; }

}  // namespace

// In bands only the HDR image and the G-buffer's targets are frame-sized: the estimate says so.
TEST(InputBounds, TheRenderEstimateCountsBands) {
    const double whole = gbl::renderMemoryBytes(16384, 16384, 0);
    const double banded = gbl::renderMemoryBytes(16384, 16384, 64);
    EXPECT_LT(banded, 0.5 * whole);
    EXPECT_LT(gbl::renderMemoryBytes(16384, 16384, 64), gbl::renderMemoryBytes(16384, 16384, 1024));
    EXPECT_EQ(gbl::renderMemoryBytes(1920, 1080, 1080), gbl::renderMemoryBytes(1920, 1080, 0));  // one band: whole
}

// render --size 16384x16384 --band-rows 64 was refused with an estimate of the whole frame,
// after allocating its 4.3 GB HDR image. Now the band-aware estimate is checked first: with a
// budget between the two estimates the whole frame is refused and the banded one goes on (to
// the next check, a missing environment map, so that nothing is rendered here).
TEST(InputBounds, RenderChecksItsBandAwareEstimateFirst) {
    const double whole = gbl::renderMemoryBytes(16384, 16384, 0);
    const double banded = gbl::renderMemoryBytes(16384, 16384, 64);
    const std::vector<std::pair<std::string, std::string>> between = {{"GBL_MEMORY_BUDGET", gib((whole + banded) / 2)}};
    expectBoundedRefusal(runMeasured(scratch(), {"render", "--size", "16384x16384", "--env", "missing.hdr"}, between),
                         {"--size 16384x16384", "GBL_MEMORY_BUDGET", "--band-rows"});
    expectBoundedRefusal(runMeasured(scratch(), {"render", "--size", "16384x16384", "--band-rows", "64", "--env",
                                                 "missing.hdr"},
                                     between),
                         {"missing.hdr"});
    const std::vector<std::pair<std::string, std::string>> below = {{"GBL_MEMORY_BUDGET", gib(banded / 2)}};
    const MeasuredRun m = runMeasured(scratch(), {"render", "--size", "16384x16384", "--band-rows", "64"}, below);
    expectBoundedRefusal(m, {"--size 16384x16384 in bands of 64 rows", "GBL_MEMORY_BUDGET"});
    EXPECT_FALSE(fs::exists(scratch() / "out"));
}

// An environment map's header is checked against the budget before it is decoded.
TEST(InputBounds, AnEnvironmentMapBeyondTheBudgetIsRefusedFromItsHeader) {
    // 40000 random pixels in one PIZ chunk, the header claiming 40000 rows: the file holds all
    // the chunk it names, so only the size of the claim can refuse it.
    gbl::Image row(40000, 1, 3);
    std::mt19937 rng(3);
    for (float& v : row.pixels) v = float(rng() % 1000) / 100.0f;
    gbl::writeExr((scratch() / "sky.exr").string(), row);
    claimExrHeight((scratch() / "sky.exr").string(), 40000);
    const MeasuredRun m =
        runMeasured(scratch(), {"render", "--env", "sky.exr", "--size", "64x64"}, {{"GBL_MEMORY_BUDGET", "8G"}});
    expectBoundedRefusal(m, {"sky.exr", "40000x40000", "environment map", "GBL_MEMORY_BUDGET"});
}

// A malformed budget is one line naming the variable.
TEST(InputBounds, AMalformedBudgetIsNamed) {
    expectBoundedRefusal(runMeasured(scratch(), {"render", "--size", "64x64"}, {{"GBL_MEMORY_BUDGET", "lots"}}),
                         {"GBL_MEMORY_BUDGET", "lots", "8G"});
}
