// Reach and look-at hooks driven through the motion controller on the CMU-like humanoid: world
// targets reached within the LOD's tolerance, cheaper LODs give larger errors, warm starts, the
// ramp-in, look-at direction, chain tables.
#include "systems/motion/ik/chain_fk.hpp"
#include "systems/motion/ik/ik_hooks.hpp"
#include "tests/systems/motion/ik/humanoid.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

constexpr float kDt = 1.0f / 60.0f;

struct Scene {
    Skeleton sk = test::make_humanoid(true);
    ClipLibrary clips;
    MotionController mc{sk, clips, 1};
    IkHookContext ik;
    std::vector<AnimLod> lods{1};
    std::vector<MotionState> states{1};
    std::vector<Transform> xs{1};
    std::vector<Velocity> vs{1};
    Scene(IkSolver solver, int iterations) {
        register_ik_hooks(mc, ik);
        lods[0].ik = solver;
        lods[0].ik_iterations = static_cast<uint8_t>(iterations);
        lods[0].ik_tolerance = 1e-3f;
        // A placed, turned character: targets must be converted into its model space.
        xs[0].position = glm::vec3(2.0f, 0.0f, -1.0f);
        xs[0].rotation = glm::angleAxis(0.5f, glm::vec3(0, 1, 0));
    }
    void step() { mc.update(kDt, lods, states, xs, vs); }
    // World position of a joint of the posed character.
    glm::vec3 world(int joint) const {
        return xs[0].position + xs[0].rotation * ik::matrix_position(mc.poses().view(0).model[static_cast<size_t>(joint)]);
    }
    glm::vec3 to_world(const glm::vec3& model) const { return xs[0].position + xs[0].rotation * model; }
};

// Reachable with the limits of the fixture: 0.40 m from the right shoulder (arm 0.54 m), forward-down.
const glm::vec3 kReachModel(-0.35f, 1.15f, 0.3f);

MotionRequest reach(const Scene& s, float crossfade) {
    MotionRequest r;
    r.kind = RequestKind::Reach;
    r.effector = static_cast<int16_t>(s.sk.find("RightWrist"));
    r.target = s.to_world(kReachModel);
    r.crossfade_s = crossfade;
    return r;
}

TEST(IkHooks, ChainTablesFollowTheNames) {
    Scene s(IkSolver::Ccd, 4);
    EXPECT_EQ(s.ik.reach_base[static_cast<size_t>(s.sk.find("RightWrist"))], s.sk.find("RightShoulder"));
    EXPECT_EQ(s.ik.reach_base[static_cast<size_t>(s.sk.find("LeftAnkle"))], s.sk.find("LeftHip"));
    EXPECT_EQ(s.ik.look_base[static_cast<size_t>(s.sk.find("Head"))], s.sk.find("Neck"));  // head/neck chain
    EXPECT_EQ(s.ik.default_reach_effector, s.sk.find("RightWrist"));
    EXPECT_EQ(s.ik.default_look_effector, s.sk.find("Head"));
    // Fallback by depth for an unknown name: 3 joints, never the root.
    EXPECT_EQ(s.ik.reach_base[static_cast<size_t>(s.sk.find("HeadTop"))], s.sk.find("Neck"));
    EXPECT_EQ(s.ik.reach_base[static_cast<size_t>(s.sk.find("lowerback"))], s.sk.find("lowerback"));
}

TEST(IkHooks, ReachEndsWithinToleranceAndRampsIn) {
    Scene s(IkSolver::Dls, 10);
    const int wrist = s.sk.find("RightWrist");
    const glm::vec3 start = s.world(wrist);
    const MotionRequest r = reach(s, 0.3f);
    ASSERT_TRUE(s.mc.push_request(0, r));
    // Ramp: the wrist moves gradually (smoothstep weight over 0.3 s = 18 frames). The largest
    // per-frame step of a smoothstep ramp is 1.5 * dt / T of the distance, plus the arc's curvature:
    // bound it by 2x that.
    const float distance = glm::length(r.target - start);
    const float bound = 2.0f * 1.5f * kDt / 0.3f * distance;
    glm::vec3 prev = start;
    float worst = 0.0f;
    for (int frame = 0; frame < 40; ++frame) {
        s.step();
        worst = std::max(worst, glm::length(s.world(wrist) - prev));
        prev = s.world(wrist);
    }
    EXPECT_LE(worst, bound);
    EXPECT_GT(worst, 0.0f);
    // Done ramping: the solution itself. Tolerance = the LOD's 1e-3 m plus float FK error (~1e-5 m
    // over a 1.5 m chain of mat4 products).
    EXPECT_LE(glm::length(s.world(wrist) - r.target), 1e-3f + 1e-4f);
    EXPECT_TRUE(s.ik.characters[0].last.converged);
    // Warm start: steady reaching needs no iterations once converged.
    EXPECT_EQ(s.ik.characters[0].last.iterations, 0);
}

TEST(IkHooks, LowLodIsCoarserThanHighLod) {
    Scene low(IkSolver::Ccd, 2), high(IkSolver::Dls, 10);
    ASSERT_TRUE(low.mc.push_request(0, reach(low, 0.0f)));
    ASSERT_TRUE(high.mc.push_request(0, reach(high, 0.0f)));
    const int wrist = low.sk.find("RightWrist");
    const glm::vec3 goal = reach(low, 0.0f).target;
    // Error summed over the first 6 frames (the arm starts straight, a singular configuration for
    // DLS, so single frames are path-dependent; the sum measures how fast each LOD gets there).
    float sum_low = 0.0f, sum_high = 0.0f;
    for (int frame = 0; frame < 6; ++frame) {
        low.step();
        high.step();
        if (frame == 0) {
            EXPECT_EQ(low.ik.characters[0].last.iterations, 2);  // the LOD's cap was the limit
        }
        sum_low += glm::length(low.world(wrist) - goal);
        sum_high += glm::length(high.world(wrist) - goal);
    }
    // Regression guard, not derived: the straight arm's first steps go where rounding sends them, so the
    // ratio moves with the arithmetic (3.0x with the hand-written double Cholesky, 2.0x with a float LLT; both converge below).
    EXPECT_GT(sum_low, 1.5f * sum_high);
    // Warm starts let the cheap LOD converge over frames too (2 sweeps per frame accumulate).
    for (int frame = 0; frame < 30; ++frame) low.step();
    EXPECT_LE(glm::length(low.world(wrist) - goal), 1e-3f + 1e-4f);
    EXPECT_LE(glm::length(high.world(wrist) - goal), 1e-3f + 1e-4f);
    // IkSolver::None holds the base pose: the wrist stays where it was.
    Scene none(IkSolver::None, 10);
    const glm::vec3 before = none.world(wrist);
    ASSERT_TRUE(none.mc.push_request(0, reach(none, 0.0f)));
    none.step();
    EXPECT_LE(glm::length(none.world(wrist) - before), 1e-6f);
}

TEST(IkHooks, StalledReachesEscapeTheirLocalMinimum) {
    // Straight-arm T-pose base, elbow at its limit, a target at shoulder height 0.35 m from the
    // shoulder: both solvers stall 0.19 m short (the elbow hinge bends in the vertical plane) unless
    // the hook swivels the arm. Every placement and solver must converge within 30 frames.
    uint32_t stalls = 0;
    for (const IkSolver solver : {IkSolver::Dls, IkSolver::Ccd}) {
        for (const float yaw : {0.0f, 0.5f, -1.0f, 2.5f}) {
            Scene s(solver, 10);
            s.xs[0].rotation = glm::angleAxis(yaw, glm::vec3(0, 1, 0));
            MotionRequest r = reach(s, 0.0f);
            r.target = s.to_world(glm::vec3(-0.371f, 1.36f, 0.3f));
            ASSERT_TRUE(s.mc.push_request(0, r));
            for (int frame = 0; frame < 30; ++frame) s.step();
            EXPECT_LE(glm::length(s.world(s.sk.find("RightWrist")) - r.target), 1e-3f + 1e-4f)
                << "solver " << static_cast<int>(solver) << " yaw " << yaw;
            stalls += s.ik.characters[0].stalls;
        }
    }
    EXPECT_GT(stalls, 0u);  // the escape really ran
}

TEST(IkHooks, UnreachableTargetHoldsStill) {
    // 1 m from the shoulder (arm 0.54 m): the arm points at it and stays put (no swivelling).
    Scene s(IkSolver::Dls, 10);
    MotionRequest r = reach(s, 0.0f);
    r.target = s.to_world(glm::vec3(-0.6f, 1.36f, 0.9f));
    ASSERT_TRUE(s.mc.push_request(0, r));
    for (int frame = 0; frame < 20; ++frame) s.step();
    const int elbow = s.sk.find("RightElbow");
    const glm::vec3 before = s.world(elbow);
    for (int frame = 0; frame < 10; ++frame) s.step();
    EXPECT_LE(glm::length(s.world(elbow) - before), 1e-4f);  // float noise of re-solving, not motion
    EXPECT_EQ(s.ik.characters[0].stalls, 0u);
}

TEST(IkHooks, LookAtPointsTheHeadAtTheTarget) {
    Scene s(IkSolver::Ccd, 6);
    MotionRequest r;
    r.kind = RequestKind::LookAt;
    r.target = s.to_world(glm::vec3(0.6f, 1.9f, 1.5f));
    r.crossfade_s = 0.2f;
    ASSERT_TRUE(s.mc.push_request(0, r));
    for (int frame = 0; frame < 30; ++frame) s.step();
    const int head = s.sk.find("Head");
    const glm::mat4& m = s.mc.poses().view(0).model[static_cast<size_t>(head)];
    const glm::vec3 forward = s.xs[0].rotation * (ik::matrix_rotation(m) * s.ik.look_axis);
    const glm::vec3 to_target = glm::normalize(r.target - s.world(head));
    const float angle = std::acos(std::clamp(glm::dot(glm::normalize(forward), to_target), -1.0f, 1.0f));
    // E = |dp| + 1 m/rad * angle <= 1e-3: orientation within 1e-3 rad, head moved <= 1e-3 m at
    // ~1.5 m from the target (another 7e-4 rad); acos of a float dot adds ~5e-4 rad.
    EXPECT_LE(angle, 1e-3f + 7e-4f + 5e-4f);
    // It really turned: the rest forward (+Z) is far from the target direction.
    EXPECT_GT(std::acos(glm::dot(s.xs[0].rotation * glm::vec3(0, 0, 1), to_target)), 0.3f);
}

TEST(IkHooks, ReleaseDropsTheWarmStart) {
    Scene s(IkSolver::Dls, 10);
    MotionRequest r = reach(s, 0.0f);
    r.duration = 0.1f;
    ASSERT_TRUE(s.mc.push_request(0, r));
    s.step();
    EXPECT_TRUE(s.ik.characters[0].warm);
    for (int frame = 0; frame < 10; ++frame) s.step();
    EXPECT_TRUE(s.mc.active().empty());  // back to rest
    EXPECT_FALSE(s.ik.characters[0].warm);
}

}  // namespace
}  // namespace aloha
