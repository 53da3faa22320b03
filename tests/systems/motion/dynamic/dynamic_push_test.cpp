// A push on the pelvis during the walk: the dynamic walker is knocked aside and recovers (its
// balance aid pulls the pelvis back to the gait's path), the kinematic walker has nothing to push.
#include "tests/systems/motion/dynamic/two_walkers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace aloha {
namespace {

constexpr float kDt = test::TwoWalkers::kDt;  // the fixture's step

// Two characters with the same walk: 0 is pushed, 1 is not (the reference).
struct PushScene : test::TwoWalkers {
    explicit PushScene(WalkMethod method) : TwoWalkers(method, method, 1.2f) {}
    /// Centre of mass of character c's simulated links (world).
    glm::vec3 com(uint32_t c) const {
        const DynamicWalkState& st = dyn.characters[c].state;
        glm::vec3 sum(0.0f);
        for (const DynamicBody& b : st.bodies) sum += b.mass * b.x;
        return sum / st.total_mass;
    }
};

TEST(DynamicPush, DynamicWalkerIsKnockedAsideAndRecovers) {
    PushScene s(WalkMethod::Dynamic);
    for (int f = 0; f < 120; ++f) s.step();  // 2 s into the walk
    // A sideways shove that would change the whole body's velocity by 0.6 m/s.
    const float mass = s.dyn.characters[0].state.total_mass;
    ASSERT_GT(mass, 0.0f);
    const glm::vec3 shove(0.6f * mass, 0.0f, 0.0f);
    ASSERT_TRUE(push_dynamic_walker(s.dyn, 0, shove));
    float peak = 0.0f, peak_t = 0.0f, after = 0.0f;
    float min_hips = 1e9f;
    float com_peak = 0.0f, com_after = 0.0f;
    for (int f = 1; f <= 150; ++f) {  // 2.5 s after the push
        s.step();
        const float t = static_cast<float>(f) * kDt;
        const float off = std::abs(s.pelvis(0).x - s.pelvis(1).x);
        if (off > peak) peak = off, peak_t = t;
        if (t >= 1.0f) after = std::max(after, off);
        // The whole body's centre of mass against the unpushed walker's (horizontal).
        const glm::vec3 d = s.com(0) - s.com(1);
        const float com_off = std::hypot(d.x, d.z);
        com_peak = std::max(com_peak, com_off);
        if (t >= 1.0f) com_after = std::max(com_after, com_off);
        min_hips = std::min(min_hips, s.pelvis(0).y);
    }
    std::printf("push 0.6 m/s: pelvis knocked %.1f cm aside at %.2f s; within %.2f cm of the unpushed walker after 1 s\n",
                static_cast<double>(100.0f * peak), static_cast<double>(peak_t), static_cast<double>(100.0f * after));
    // The balance aid is a critically damped spring on the pelvis at w = 8 rad/s acting on the whole
    // mass: an instant velocity change u gives x(t) = u t exp(-w t), largest u / (w e) = 2.8 cm at
    // t = 1/w = 0.125 s. The push is spread over kDynamicPushSeconds (the same impulse as a sum of
    // smaller later ones), which can only lower that peak; the legs' motors and friction absorb more.
    // So the peak is below 2.8 cm (20% margin for the gait's own sway) and clearly visible (> 1 cm).
    // One second after the push x(t) / peak <= (w t') e^(1 - w t') with t' >= 0.9 s: under 2%, so the
    // pelvis is back within 5 mm of the unpushed walker.
    const float w = s.dyn.settings.balance_frequency;
    EXPECT_GT(peak, 0.01f) << "the push is absorbed by the simulation, visibly";
    EXPECT_LT(peak, 0.6f / (w * std::exp(1.0f)) * 1.2f);
    EXPECT_LT(after, 0.005f) << "recovered one second after the push";
    EXPECT_GT(min_hips, 0.6f) << "did not fall";
    // The centre of mass: knocked visibly aside (the shove alone would carry it 0.6 m/s x 0.125 s),
    // and back with the unpushed walker's within 1 cm one second after the push. Regression guard,
    // not derived: the legs and arms settle a little slower than the pelvis; seen 0.18 cm after 1 s.
    std::printf("centre of mass knocked %.1f cm aside; within %.2f cm of the unpushed walker's after 1 s\n",
                static_cast<double>(100.0f * com_peak), static_cast<double>(100.0f * com_after));
    EXPECT_GT(com_peak, 0.01f);
    EXPECT_LT(com_after, 0.01f) << "centre of mass recovered one second after the push";
}

TEST(DynamicPush, KinematicWalkerIgnoresThePush) {
    PushScene s(WalkMethod::Kinematic);
    for (int f = 0; f < 120; ++f) s.step();
    EXPECT_FALSE(push_dynamic_walker(s.dyn, 0, glm::vec3(40.0f, 0.0f, 0.0f))) << "nothing simulated to push";
    for (int f = 0; f < 60; ++f) {
        s.step();
        ASSERT_EQ(s.pelvis(0), s.pelvis(1)) << "frame " << f;
    }
}

}  // namespace
}  // namespace aloha
