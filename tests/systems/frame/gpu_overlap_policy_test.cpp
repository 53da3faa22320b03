// GpuOverlapPolicy: fixed modes, and Auto overlapping only while the smoothed GPU frame is too long for the
// frame rate and there is CPU time to hide, with the gaps between its thresholds holding the decision.
#include "systems/frame/gpu_overlap_policy.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

TEST(GpuOverlapPolicy, FixedModesIgnoreTheTimes) {
    GpuOverlapPolicy off(GpuOverlap::Off), on(GpuOverlap::On);
    for (const double gpu : {-1.0, 1.0, 40.0}) {
        EXPECT_FALSE(off.decide(5.0, gpu));
        EXPECT_FALSE(off.overlapping());
        EXPECT_TRUE(on.decide(5.0, gpu));
        EXPECT_TRUE(on.overlapping());
    }
}

TEST(GpuOverlapPolicy, AutoStaysSerialUntilAGpuTimeIsMeasured) {
    GpuOverlapPolicy p(GpuOverlap::Auto);
    EXPECT_FALSE(p.decide(5.0, -1.0));  // first frames: no GPU time yet
    EXPECT_DOUBLE_EQ(p.smoothed_gpu_ms(), -1.0);
    EXPECT_TRUE(p.decide(5.0, 30.0));  // the first measurement is the average
    EXPECT_DOUBLE_EQ(p.smoothed_gpu_ms(), 30.0);
    EXPECT_TRUE(p.decide(5.0, -1.0));  // an unmeasured frame keeps the average and the decision
    EXPECT_DOUBLE_EQ(p.smoothed_gpu_ms(), 30.0);
}

TEST(GpuOverlapPolicy, AutoOverlapsOnlyLongGpuFramesWithCpuTimeToHide) {
    // A short GPU frame (a close-up: ~3 ms) makes 60 Hz serially: never overlapped, whatever the CPU time.
    GpuOverlapPolicy close_up(GpuOverlap::Auto);
    for (int f = 0; f < 100; ++f) EXPECT_FALSE(close_up.decide(10.0, 3.0));
    // A long GPU frame with almost no CPU systems to hide behind it: nothing to gain.
    GpuOverlapPolicy idle_cpu(GpuOverlap::Auto);
    for (int f = 0; f < 100; ++f) EXPECT_FALSE(idle_cpu.decide(0.4, 30.0));
    // A long GPU frame and CPU systems of several ms (a large crowd on a software rasteriser): overlapped.
    GpuOverlapPolicy crowd(GpuOverlap::Auto);
    for (int f = 0; f < 100; ++f) EXPECT_TRUE(crowd.decide(5.0, 25.0));
}

TEST(GpuOverlapPolicy, AutoHoldsItsDecisionBetweenTheThresholds) {
    const GpuOverlapSettings s;  // enter above 16.7 ms, leave under 12.5 ms, smoothing 0.2
    GpuOverlapPolicy p(GpuOverlap::Auto, s);
    // 15 ms: between the thresholds, from serial: stays serial.
    for (int f = 0; f < 50; ++f) EXPECT_FALSE(p.decide(3.0, 15.0));
    // A single 40 ms frame moves the average by 0.2 * 25 = 5 ms to 20 ms: over 16.7, overlapped at once.
    EXPECT_TRUE(p.decide(3.0, 40.0));
    // Back at 15 ms the average falls towards 15 but never under 12.5: stays overlapped.
    for (int f = 0; f < 50; ++f) EXPECT_TRUE(p.decide(3.0, 15.0));
    // At 10 ms the average (15 -> 10 by 20% of the gap a frame) is under 12.5 after
    // ceil(log(2.5 / 5) / log(0.8)) = 4 frames: 15 -> 14 -> 13.2 -> 12.56 -> 12.05.
    EXPECT_TRUE(p.decide(3.0, 10.0));
    EXPECT_TRUE(p.decide(3.0, 10.0));
    EXPECT_TRUE(p.decide(3.0, 10.0));
    EXPECT_FALSE(p.decide(3.0, 10.0));
}

TEST(GpuOverlapPolicy, AutoLeavesWhenTheCpuTimeFallsUnderHalfItsMinimum) {
    GpuOverlapPolicy p(GpuOverlap::Auto, GpuOverlapSettings{.enter_gpu_ms = 16.7, .leave_gpu_ms = 12.5, .min_cpu_ms = 1.0, .smoothing = 1.0});
    EXPECT_TRUE(p.decide(1.2, 30.0));
    EXPECT_TRUE(p.decide(0.6, 30.0));   // under the minimum to enter, over half of it: held
    EXPECT_FALSE(p.decide(0.4, 30.0));  // under half: serial
    EXPECT_FALSE(p.decide(0.9, 30.0));  // not enough to enter again
}

TEST(GpuOverlapPolicy, NamesRoundTrip) {
    for (const GpuOverlap m : {GpuOverlap::Off, GpuOverlap::On, GpuOverlap::Auto}) EXPECT_EQ(parse_gpu_overlap(gpu_overlap_name(m)), m);
    EXPECT_FALSE(parse_gpu_overlap("yes").has_value());
    EXPECT_FALSE(parse_gpu_overlap("").has_value());
}

}  // namespace
}  // namespace aloha
