// Motion meters: exact figures on synthetic feet and joints, then the generated walk through the
// controller at the clip level (update intervals 1 to 8) and across walk-method switches.
#include "systems/motion/controller.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "systems/motion/motion_metrics.hpp"
#include "tests/common/test_humanoid.hpp"
#include "tests/systems/motion/generated_gait_fixture.hpp"
#include "tests/systems/motion/walk_request.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace aloha {
namespace {

constexpr float kDt = 1.0f / 60.0f;

// One foot, 2 s at 60 Hz, root at 1 m/s: planted for 0.5 s (sliding forward at `slip` m/s), then
// swinging 5 cm up at 2 m/s for 0.5 s, twice.
FootSkateMeter synthetic_walk(float slip) {
    FootSkateMeter m;
    glm::vec3 foot(0.0f, 0.08f, 0.0f);
    for (int i = 0; i <= 120; ++i) {
        const float t = static_cast<float>(i) * kDt;
        const bool stance = std::fmod(t, 1.0f) < 0.5f - 1e-4f;
        if (i > 0) foot.z += (stance ? slip : 2.0f) * kDt;
        foot.y = stance ? 0.08f : 0.13f;
        const glm::vec3 f[1] = {foot};
        m.add(f, glm::vec3(0.0f, 0.9f, t), kDt);
    }
    return m;
}

TEST(FootSkateMeter, PlantedFeetGiveZeroAndSlipsAreMeasuredExactly) {
    EXPECT_FLOAT_EQ(synthetic_walk(0.0f).mm_per_metre(), 0.0f) << "swing steps are not contact (5 cm up, 2 m/s)";
    // Slipping at 0.1 m/s: two stances of 0.5 s = 30 steps each, but the step into each stance starts in
    // the air; 29 + 29 steps of 0.1 / 60 m each over 2 m walked.
    const FootSkateMeter m = synthetic_walk(0.1f);
    EXPECT_NEAR(m.walked_m(), 2.0f, 1e-4f);
    EXPECT_NEAR(m.skate_m(), 58.0f * 0.1f * kDt, 1e-5f);
    // A foot sliding faster than the contact speed is swinging, by definition.
    EXPECT_FLOAT_EQ(synthetic_walk(0.6f).skate_m(), 0.0f);
}

TEST(PopMeter, SeparatesSwitchFramesFromOrdinaryOnes) {
    PopMeter m;
    for (int i = 0; i < 100; ++i) {
        const glm::vec3 j[2] = {glm::vec3(0.01f * static_cast<float>(i), 0, 0), glm::vec3(0, 0.001f * static_cast<float>(i), 0)};
        m.add(j, false);
    }
    const glm::vec3 jump[2] = {glm::vec3(1.04f, 0, 0), glm::vec3(0, 0.1f, 0)};  // 5 cm on the switch frame
    m.add(jump, true);
    EXPECT_NEAR(m.ordinary_p95(), 0.01f, 1e-6f);
    EXPECT_NEAR(m.ordinary_max(), 0.01f, 1e-6f);
    EXPECT_NEAR(m.worst_switch(), 0.05f, 1e-5f);
    EXPECT_EQ(m.switches(), 1u);
}

class MeteredWalk : public test::GeneratedGait {
protected:
    void SetUp() override {
        GeneratedGait::SetUp();
        for (const char* name : {"LeftAnkle", "LeftToe", "RightAnkle", "RightToe"}) feet.push_back(sk.find(name));
        for (int foot : feet) ASSERT_GE(foot, 0);
        soles = sole_offsets(sk, feet);
    }
    // Walks at 1.4 m/s for `seconds`; `lod_at(frame, lod)` may change the level each frame.
    template <class LodAt>
    void walk(float seconds, FootSkateMeter& skate, PopMeter& pops, LodAt lod_at) {
        Walker w(*this, 1.4f);
        std::vector<glm::vec3> world;
        std::vector<glm::vec3> foot(feet.size());
        for (int f = 0; f < static_cast<int>(seconds / kDt); ++f) {
            const AnimLod before = w.lod();
            lod_at(f, w.lod());
            const bool switched = before.walk != w.lod().walk || before.update_interval != w.lod().update_interval;
            w.step(kDt);
            w.world_joints(world);
            const auto model = w.mc.poses().view(0).model;
            const Transform& x = w.xs[0];
            for (size_t k = 0; k < feet.size(); ++k)
                foot[k] = x.position + x.rotation * glm::vec3(model[static_cast<size_t>(feet[k])] * glm::vec4(soles[k], 1.0f));
            skate.add(foot, x.position, kDt);
            pops.add(world, switched);
        }
    }
    std::vector<int> feet;
    std::vector<glm::vec3> soles;
};

// The bound: at most 10 mm of skate per metre at every update interval (contact: a sole point
// within 5 mm of its lowest height and slower than 0.5 m/s).
TEST_F(MeteredWalk, ClipLevelSkateAtEveryUpdateInterval) {
    for (uint16_t interval : {uint16_t{1}, uint16_t{2}, uint16_t{4}, uint16_t{8}}) {
        FootSkateMeter skate;
        PopMeter pops;
        walk(6.0f, skate, pops, [&](int, AnimLod& lod) {
            lod.walk = WalkMethod::ClipPlayback;
            lod.update_interval = interval;
        });
        std::printf("clip level, interval %d: %.2f mm per metre over %.1f m\n", interval,
                    static_cast<double>(skate.mm_per_metre()), static_cast<double>(skate.walked_m()));
        EXPECT_LE(skate.mm_per_metre(), 10.0f) << "interval " << interval;
    }
}

// Switching between the clip and kinematic walks every second (12-frame cross-fade): the largest joint
// jump on a switch frame stays within the 95th percentile of ordinary frames (the bound; the
// ordinary figure is dominated by the swinging toes, about 9 m/s at their fastest).
TEST_F(MeteredWalk, WalkMethodSwitchesAgainstOrdinaryFrames) {
    FootSkateMeter skate;
    PopMeter pops;
    walk(8.0f, skate, pops, [](int frame, AnimLod& lod) {
        lod.walk = (frame / 60) % 2 ? WalkMethod::Kinematic : WalkMethod::ClipPlayback;
        lod.crossfade_s = 0.2f;
    });
    std::printf("clip <-> kinematic every 1 s: %zu switches, worst switch-frame joint jump %.2f cm, ordinary p95 %.2f cm, "
                "skate %.2f mm per metre\n",
                pops.switches(), static_cast<double>(100.0f * pops.worst_switch()),
                static_cast<double>(100.0f * pops.ordinary_p95()), static_cast<double>(skate.mm_per_metre()));
    EXPECT_EQ(pops.switches(), 7u);
    EXPECT_GT(pops.ordinary_p95(), 0.0f);
    EXPECT_LE(pops.worst_switch(), pops.ordinary_p95());
}

}  // namespace
}  // namespace aloha
