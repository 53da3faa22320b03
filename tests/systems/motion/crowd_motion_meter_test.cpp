// CrowdMotionMeter: exact figures on synthetic characters, split by level and interval.
#include "systems/motion/crowd_motion_meter.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

constexpr float kDt = 1.0f / 60.0f;

// Character 0 walks 1 m/s for 60 frames with one sole sliding 0.1 m/s on the ground: frames 0-29 at
// level 2 (interval 4), frames 30-59 at level 3 (interval 8), the change on frame 30. Character 1 stands
// still at level 3 with its sole 10 cm up (never in contact).
CrowdMotionMeter recorded() {
    CrowdMotionMeter m(2);
    for (int f = 0; f < 60; ++f) {
        const float t = static_cast<float>(f) * kDt;
        const bool late = f >= 30;
        const glm::vec3 root0(0.0f, 0.0f, t);
        const glm::vec3 sole0(0.0f, 0.0f, 0.1f * t);
        const glm::vec3 joints0[2] = {root0 + glm::vec3(0, 1, 0), root0 + glm::vec3(0, 0.5f, 0) + (late && f == 30 ? glm::vec3(0.05f, 0, 0) : glm::vec3(0))};
        m.add(0, joints0, std::span<const glm::vec3>(&sole0, 1), root0, kDt, late ? 3 : 2, late ? 8 : 4,
              f == 30 ? MotionFrameKind::Switch : MotionFrameKind::Ordinary);
        const glm::vec3 root1(5.0f, 0.0f, 0.0f), sole1(5.0f, 0.1f, 0.0f);
        const glm::vec3 joints1[2] = {root1, root1};
        m.add(1, joints1, std::span<const glm::vec3>(&sole1, 1), root1, kDt, 3, 8, MotionFrameKind::Ordinary);
    }
    return m;
}

TEST(CrowdMotionMeter, SplitsSkateAndPopsByLevelAndInterval) {
    const CrowdMotionMeter m = recorded();
    const auto buckets = m.buckets();
    ASSERT_EQ(buckets.size(), 2u);
    const MotionBucketFigures& a = buckets[0];
    const MotionBucketFigures& b = buckets[1];
    EXPECT_EQ(a.level, 2);
    EXPECT_EQ(a.interval, 4);
    EXPECT_EQ(b.level, 3);
    EXPECT_EQ(b.interval, 8);
    // Steps 1-29 at level 2 (29 steps of 1/60 m walked, 0.1/60 m slid); steps 30-59 at level 3 (30 steps).
    EXPECT_EQ(a.frames, 30u);
    EXPECT_EQ(b.frames, 90u);  // 30 of character 0, all 60 of character 1
    EXPECT_NEAR(a.walked_m, 29.0 / 60.0, 1e-5);
    EXPECT_NEAR(b.walked_m, 30.0 / 60.0, 1e-5);
    EXPECT_NEAR(a.mm_per_metre(), 100.0, 1e-2);  // 0.1 m/s sliding at 1 m/s walked
    EXPECT_NEAR(b.mm_per_metre(), 100.0, 1e-2);
    // The change frame: the second joint moved 1/60 m forward and 5 cm aside.
    EXPECT_EQ(b.switch_frames, 1u);
    EXPECT_NEAR(b.worst_switch_m, std::hypot(0.05f, kDt), 1e-5f);
    EXPECT_EQ(a.switch_frames, 0u);
    // Ordinary frames of character 0 move 1/60 m (and the frame after the change comes back 5 cm).
    EXPECT_NEAR(a.ordinary_p95_m, kDt, 1e-5f);
    const MotionBucketFigures all = m.overall();
    EXPECT_EQ(all.frames, 120u);
    EXPECT_NEAR(all.walked_m, 59.0 / 60.0, 1e-5);
    EXPECT_EQ(all.switch_frames, 1u);
}

TEST(CrowdMotionMeter, TransitionFramesAreKeptApart) {
    CrowdMotionMeter m(1);
    const glm::vec3 sole(0.0f);
    for (int f = 0; f < 10; ++f) {
        const glm::vec3 j[1] = {glm::vec3(0.0f, 0.0f, f < 5 ? 0.0f : 0.3f * static_cast<float>(f - 4))};
        m.add(0, j, std::span<const glm::vec3>(&sole, 1), glm::vec3(0.0f), kDt, 0, 1,
              f >= 5 ? MotionFrameKind::Transition : MotionFrameKind::Ordinary);
    }
    const MotionBucketFigures b = m.overall();
    EXPECT_EQ(b.transition_frames, 5u);
    EXPECT_NEAR(b.worst_transition_m, 0.3f, 1e-6f);
    EXPECT_NEAR(b.ordinary_max_m, 0.0f, 1e-6f);
    EXPECT_EQ(b.switch_frames, 0u);
}

}  // namespace
}  // namespace aloha
