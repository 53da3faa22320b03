// The divergence guard of the dynamic walk (a safety net): a healthy walk never trips it; a
// simulation that comes apart is handed back to the kinematic walk it tracked, inertialized from the
// pose shown last, and ends on exactly the kinematic walker's pose.
#include "systems/motion/inertialize.hpp"
#include "tests/systems/motion/dynamic/two_walkers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace aloha {
namespace {

constexpr float kDt = test::TwoWalkers::kDt;  // the fixture's step

// Character 0 walks with `method0`, character 1 kinematically (the reference), the same walk.
struct GuardScene : test::TwoWalkers {
    GuardScene(WalkMethod method0, float speed) : TwoWalkers(method0, WalkMethod::Kinematic, speed) {}
};

float largest_move(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    float m = 0.0f;
    for (size_t j = 0; j < a.size(); ++j) m = std::max(m, glm::length(a[j] - b[j]));
    return m;
}

TEST(DynamicGuard, HealthyWalksNeverTripIt) {
    for (const float speed : {0.6f, 1.2f, 1.6f}) {
        GuardScene s(WalkMethod::Dynamic, speed);
        for (int f = 0; f < 300; ++f) s.step();  // 5 s
        EXPECT_EQ(s.dyn.simulated(), 1u) << speed << " m/s";
        EXPECT_EQ(s.dyn.diverged(), 0u) << speed << " m/s";
    }
}

TEST(DynamicGuard, ComingApartHandsBackToKinematicWithoutAJump) {
    GuardScene s(WalkMethod::Dynamic, 1.2f);
    for (int f = 0; f < 120; ++f) s.step();
    // A shove no balance could absorb (25 m/s of the whole body in 0.1 s): without the guard the
    // links fly apart (joints metres from the walk, NaNs in the end).
    const float mass = s.dyn.characters[0].state.total_mass;
    ASSERT_TRUE(push_dynamic_walker(s.dyn, 0, glm::vec3(25.0f * mass, 0.0f, 0.0f)));
    std::vector<glm::vec3> before = s.joints(0);
    int handed_back = -1;
    float offset = 0.0f;       // largest joint offset from the kinematic pose at the hand-back
    float after_jump = 0.0f;   // largest frame-to-frame joint move from the hand-back on
    float ref_move = 0.0f;     // the same for the kinematic reference walker
    std::vector<glm::vec3> ref_before = s.joints(1);
    for (int f = 0; f < 60; ++f) {
        s.step();
        const std::vector<glm::vec3> now = s.joints(0);
        const std::vector<glm::vec3> ref = s.joints(1);
        for (const glm::vec3& p : now) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z)) << "frame " << f;
        if (handed_back < 0 && s.dyn.diverged() == 1) {
            handed_back = f;
            offset = largest_move(now, ref);
        } else if (handed_back >= 0) {
            after_jump = std::max(after_jump, largest_move(now, before));
            ref_move = std::max(ref_move, largest_move(ref, ref_before));
        }
        before = now;
        ref_before = ref;
    }
    ASSERT_GE(handed_back, 0) << "the guard tripped";
    EXPECT_EQ(s.dyn.simulated(), 1u) << "still at the dynamic level, walking kinematically";
    EXPECT_FALSE(push_dynamic_walker(s.dyn, 0, glm::vec3(1.0f, 0.0f, 0.0f))) << "nothing simulated to push any more";
    // The hand-back keeps the pose shown last as an offset decaying along 1 - smootherstep over
    // fallback_seconds; smootherstep's steepest slope is 15/8 per transition, so no frame moves a
    // joint by more than the kinematic walk's own motion plus offset * 15/8 * dt / T (plus 1 mm for
    // the offset being kept in local joint space, where rotations compound along the chain).
    const float bound = ref_move + offset * 1.875f * kDt / s.dyn.fallback_seconds + 0.001f;
    EXPECT_LE(after_jump, bound) << "offset at hand-back " << offset << " m";
    // After the transition the character shows exactly the kinematic walker's pose.
    EXPECT_LT(largest_move(s.joints(0), s.joints(1)), 1e-4f);
}

TEST(DynamicGuard, DetectorBounds) {
    Skeleton sk = test::make_humanoid(true);
    std::vector<glm::vec3> t(sk.rest_translations().begin(), sk.rest_translations().end());
    std::vector<glm::quat> r(sk.rest_rotations().begin(), sk.rest_rotations().end());
    std::vector<glm::vec3> sc(sk.rest_scales().begin(), sk.rest_scales().end());
    std::vector<glm::mat4> model(t.size());
    for (size_t j = 0; j < t.size(); ++j) {
        const glm::mat4 local = trs_matrix(t[j], r[j], sc[j]);
        const int p = sk.parents()[j];
        model[j] = p < 0 ? local : model[static_cast<size_t>(p)] * local;
    }
    DynamicWalkState st;
    ASSERT_TRUE(init_dynamic_walk(sk, ConstPoseView{t, r, sc, model}, glm::mat4(1.0f), st).ok());
    const DynamicGuard guard;
    const glm::quat upright = st.bodies[0].q;
    EXPECT_FALSE(dynamic_walk_diverged(st, upright, guard));
    DynamicWalkState tilted = st;
    tilted.bodies[0].q = glm::angleAxis(guard.max_pelvis_tilt + 0.05f, glm::vec3(1, 0, 0)) * upright;
    EXPECT_TRUE(dynamic_walk_diverged(tilted, upright, guard)) << "pelvis tilted past the bound";
    DynamicWalkState fast = st;
    fast.bodies[1].v = glm::vec3(0.0f, 0.0f, guard.max_body_speed * 1.1f);
    EXPECT_TRUE(dynamic_walk_diverged(fast, upright, guard)) << "a link too fast";
    DynamicWalkState apart = st;
    apart.bodies[1].x += glm::vec3(0.0f, guard.max_joint_gap * 1.5f, 0.0f);
    EXPECT_TRUE(dynamic_walk_diverged(apart, upright, guard)) << "a joint pulled apart";
    DynamicWalkState broken = st;
    broken.bodies[2].x.x = std::nanf("");
    EXPECT_TRUE(dynamic_walk_diverged(broken, upright, guard)) << "a NaN";
}

}  // namespace
}  // namespace aloha
