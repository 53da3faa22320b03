// Dynamic walk through the motion controller: a character walking with WalkMethod::Dynamic for
// 5 s stays upright, differs from the kinematic gait it tracks, never produces NaN, and its
// simulation is released when it stops.
#include "systems/motion/dynamic/dynamic_hook.hpp"
#include "tests/systems/motion/ik/humanoid.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

constexpr float kDt = 1.0f / 60.0f;

bool finite_pose(const ConstPoseView& p) {
    for (size_t j = 0; j < p.rotations.size(); ++j) {
        const glm::quat& q = p.rotations[j];
        if (!std::isfinite(q.x + q.y + q.z + q.w)) return false;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(p.model[j][c][r])) return false;
    }
    return true;
}

TEST(DynamicHook, FiveSecondWalkStaysUprightAndDiffersFromKinematic) {
    const Skeleton sk = test::make_humanoid(true);
    ClipLibrary clips;
    // Character 0 walks dynamically, character 1 kinematically with the same request.
    MotionController mc(sk, clips, 2);
    mc.set_walk_rig(resolve_walk_rig(sk, "humanoid").value());
    DynamicHookContext dyn;
    register_dynamic_walk_hook(mc, dyn);
    std::vector<AnimLod> lods(2);
    lods[0].walk = WalkMethod::Dynamic;
    lods[1].walk = WalkMethod::Kinematic;
    std::vector<MotionState> states(2);
    std::vector<Transform> xs(2);
    std::vector<Velocity> vs(2);
    MotionRequest walk;
    walk.kind = RequestKind::Walk;
    walk.speed = 1.2f;
    walk.target = glm::vec3(0, 0, 1);
    walk.crossfade_s = 0.0f;
    ASSERT_TRUE(mc.push_request(0, walk));
    ASSERT_TRUE(mc.push_request(1, walk));
    const size_t hips = 0, head = static_cast<size_t>(sk.find("Head"));
    float max_diff = 0.0f;
    float min_head_above_hips = 1e9f, min_hips = 1e9f;
    for (int frame = 0; frame < 300; ++frame) {  // 5 s
        mc.update(kDt, lods, states, xs, vs);
        const ConstPoseView d = mc.poses().view(0), k = mc.poses().view(1);
        ASSERT_TRUE(finite_pose(d)) << "frame " << frame;
        ASSERT_EQ(dyn.simulated(), 1u);
        const glm::vec3 h = glm::vec3(d.model[hips][3]), top = glm::vec3(d.model[head][3]);
        min_head_above_hips = std::min(min_head_above_hips, top.y - h.y);
        min_hips = std::min(min_hips, h.y);
        for (size_t j = 0; j < d.rotations.size(); ++j)
            max_diff = std::max(max_diff, 2.0f * std::acos(std::min(1.0f, std::abs(glm::dot(d.rotations[j], k.rotations[j])))));
    }
    // Upright: the rest head is 0.56 m above the hips (chest 0.21 + neck 0.25 + head 0.10); a torso
    // leaning less than ~45 degrees keeps it above 0.56 * cos(45) = 0.40 m. The pelvis stays above
    // 0.6 m (the kinematic gait holds it near 0.9 m; a fall would put it below 0.3 m).
    EXPECT_GT(min_head_above_hips, 0.40f);
    EXPECT_GT(min_hips, 0.6f);
    // Simulated, not copied: some joint differs from the kinematic gait by more than 0.02 rad.
    EXPECT_GT(max_diff, 0.02f);
    // Both walked the same root motion (the controller moves the Transform): 5 s at 1.2 m/s.
    EXPECT_NEAR(xs[0].position.z, 6.0f, 0.05f);
    EXPECT_EQ(xs[0].position, xs[1].position);
    // Tracking: the simulated pelvis stays near the kinematic one (within 0.15 m).
    EXPECT_LT(glm::length(glm::vec3(mc.poses().view(0).model[hips][3]) - glm::vec3(mc.poses().view(1).model[hips][3])), 0.15f);

    // Leaving the method releases the simulation; the character falls back to the kinematic gait.
    lods[0].walk = WalkMethod::Kinematic;
    mc.update(kDt, lods, states, xs, vs);
    EXPECT_EQ(dyn.simulated(), 0u);
    EXPECT_TRUE(dyn.characters[0].state.bodies.empty());
}

TEST(DynamicHook, WithoutHookDynamicFallsBackToKinematic) {
    const Skeleton sk = test::make_humanoid(true);
    ClipLibrary clips;
    MotionController a(sk, clips, 1), b(sk, clips, 1);
    a.set_walk_rig(resolve_walk_rig(sk, "humanoid").value());
    b.set_walk_rig(resolve_walk_rig(sk, "humanoid").value());
    std::vector<AnimLod> la(1), lb(1);
    la[0].walk = WalkMethod::Dynamic;
    lb[0].walk = WalkMethod::Kinematic;
    std::vector<MotionState> sa(1), sb(1);
    std::vector<Transform> xa(1), xb(1);
    std::vector<Velocity> va(1), vb(1);
    MotionRequest walk;
    walk.kind = RequestKind::Walk;
    walk.target = glm::vec3(0, 0, 1);
    ASSERT_TRUE(a.push_request(0, walk));
    ASSERT_TRUE(b.push_request(0, walk));
    for (int frame = 0; frame < 30; ++frame) {
        a.update(kDt, la, sa, xa, va);
        b.update(kDt, lb, sb, xb, vb);
    }
    EXPECT_EQ(a.poses().view(0).rotations[2], b.poses().view(0).rotations[2]);
}

}  // namespace
}  // namespace aloha
