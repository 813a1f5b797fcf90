// The stage clock charges wall time to the innermost marked stage, so stages add up to the total
// and a nested stage (a shader compile inside rendering) is not counted twice.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "stage_clock.h"

namespace {

using gbl::Stage;
using gbl::StageClock;

void busyFor(std::chrono::milliseconds d) {  // sleep: the clock measures wall time
    std::this_thread::sleep_for(d);
}

TEST(StageClock, NestedStagesAreExclusiveAndSumToTheTotal) {
    StageClock& clock = StageClock::global();
    clock.start();
    {
        gbl::ScopedStage render(Stage::Render);
        busyFor(std::chrono::milliseconds(10));
        {
            gbl::ScopedStage compile(Stage::ShaderCompile);
            busyFor(std::chrono::milliseconds(250));
        }
        busyFor(std::chrono::milliseconds(10));
    }
    const gbl::StageTimes t = clock.read();
    EXPECT_GE(t[Stage::ShaderCompile], 250.0);
    EXPECT_GE(t[Stage::Render], 20.0);
    // Render excludes the nested compile: counted inclusively it would be >= 270 ms.
    EXPECT_LT(t[Stage::Render], 250.0);
    double sum = 0.0;
    for (double ms : t.ms) sum += ms;
    EXPECT_DOUBLE_EQ(sum, t.totalMs);
    EXPECT_GE(t.totalMs, 270.0);
}

TEST(StageClock, OtherThreadsAndAStoppedClockRecordNothing) {
    StageClock& clock = StageClock::global();
    clock.start();
    std::thread other([] {
        gbl::ScopedStage metrics(Stage::Metrics);  // not the clock's thread: ignored
        busyFor(std::chrono::milliseconds(20));
    });
    other.join();
    const gbl::StageTimes t = clock.read();
    EXPECT_EQ(t[Stage::Metrics], 0.0);
    EXPECT_GE(t[Stage::Other], 20.0);  // the starting thread waited, outside any stage
    EXPECT_STREQ(gbl::stageName(Stage::Readback), "read-back");
}

}  // namespace
