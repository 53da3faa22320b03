// Overlays: a reach layered over a walk. The walk beneath goes on untouched (same root motion, same
// legs and trunk, bit for bit, as a character walking without it), the hand reaches a reachable target
// within the LOD's tolerance, an unreachable one gives a best effort and a status without stopping
// the body, and clearing the overlay or losing IK at a lower LOD fades the arm back instead of
// snapping it.
#include "systems/motion/controller.hpp"
#include "systems/motion/ik/chain_fk.hpp"
#include "systems/motion/ik/ik_hooks.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "tests/common/test_humanoid.hpp"
#include "tests/systems/motion/walk_request.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace aloha {
namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr float kFade = 0.3f;

// One walking character driven by its own controller and IK context.
struct Walker {
    Walker(const Skeleton& sk, const WalkRig& rig, const ClipLibrary& clips, std::span<const ClipId> gaits, WalkMethod m)
        : mc(sk, clips, 1) {
        mc.set_walk_rig(rig);
        mc.set_walk_clips(gaits);
        register_ik_hooks(mc, ik);
        lods[0].walk = m;
        lods[0].ik = IkSolver::Dls;
        lods[0].ik_iterations = 10;
        lods[0].ik_tolerance = 1e-3f;
        EXPECT_TRUE(mc.push_request(0, test::straight_walk(1.4f)));
    }
    void step() { mc.update(kDt, lods, states, xs, vs); }
    glm::vec3 model_position(int joint) const { return ik::matrix_position(mc.poses().view(0).model[static_cast<size_t>(joint)]); }
    glm::vec3 world(int joint) const { return xs[0].position + xs[0].rotation * model_position(joint); }

    MotionController mc;
    IkHookContext ik;
    std::vector<AnimLod> lods{1};
    std::vector<MotionState> states{1};
    std::vector<Transform> xs{1};
    std::vector<Velocity> vs{1};
};

class OverlayTest : public ::testing::TestWithParam<WalkMethod> {
protected:
    void SetUp() override {
        const MotionLibrary lib = make_motion_library(sk, rig, "h");
        for (const RawAnimation& g : lib.gaits) gaits.push_back(clips.add(g, sk).value());
    }
    // Joints outside the right arm's reach chain (shoulder, elbow, wrist and what hangs below the wrist).
    bool in_arm(int j) const {
        for (int a = j; a >= 0; a = sk.parents()[static_cast<size_t>(a)])
            if (a == sk.find("RightShoulder")) return true;
        return false;
    }
    // The reach: the right wrist to a point in front of the reference walker's right shoulder.
    MotionRequest reach_near(const Walker& ref, glm::vec3 offset = {-0.05f, -0.15f, 0.35f}) const {
        MotionRequest r;
        r.kind = RequestKind::Reach;
        r.effector = static_cast<int16_t>(sk.find("RightWrist"));
        r.target = ref.xs[0].position + ref.xs[0].rotation * (ref.model_position(sk.find("RightShoulder")) + offset);
        r.crossfade_s = kFade;
        return r;
    }
    // Expects every joint off the arm (and the root's placement) to match the reference exactly.
    void expect_body_beneath(const Walker& a, const Walker& ref, int frame) const {
        ASSERT_EQ(a.xs[0].position, ref.xs[0].position) << "root motion goes on, frame " << frame;
        ASSERT_EQ(a.xs[0].rotation, ref.xs[0].rotation) << "frame " << frame;
        for (int j = 0; j < sk.joint_count(); ++j) {
            if (in_arm(j)) continue;
            ASSERT_EQ(a.mc.poses().view(0).model[static_cast<size_t>(j)], ref.mc.poses().view(0).model[static_cast<size_t>(j)])
                << sk.names()[static_cast<size_t>(j)] << " changed by the overlay, frame " << frame;
        }
    }
    Skeleton sk = test::humanoid_skeleton_for();
    WalkRig rig = test::humanoid_rig(sk);
    ClipLibrary clips;
    std::vector<ClipId> gaits;
};

TEST_P(OverlayTest, ReachWhileWalkingKeepsTheGaitAndFadesOut) {
    Walker a(sk, rig, clips, gaits, GetParam()), ref(sk, rig, clips, gaits, GetParam());
    const int wrist = sk.find("RightWrist");
    for (int f = 0; f < 60; ++f) a.step(), ref.step();  // walking
    float ordinary = 0.0f;  // largest per-frame wrist travel of the plain walk
    float apart = 0.0f;     // largest distance between the reaching and the plain wrist
    float worst_error = 0.0f;
    for (int f = 0; f < 120; ++f) {
        const MotionRequest r = reach_near(ref);
        ASSERT_TRUE(a.mc.set_overlay(0, r));
        const glm::vec3 r0 = ref.world(wrist);
        a.step(), ref.step();
        expect_body_beneath(a, ref, f);
        ordinary = std::max(ordinary, glm::length(ref.world(wrist) - r0));
        apart = std::max(apart, glm::length(a.world(wrist) - ref.world(wrist)));
        if (static_cast<float>(f) * kDt > kFade + kDt) worst_error = std::max(worst_error, glm::length(a.world(wrist) - r.target));
    }
    // Once faded in, the wrist is where it was aimed (a world point, while the body walks on) within the
    // LOD's tolerance (1 mm) plus float FK error over the chain (~1e-5 m).
    std::printf("walk method %d: wrist %.3f mm from the target once faded in\n", static_cast<int>(GetParam()),
                static_cast<double>(1000.0f * worst_error));
    EXPECT_LE(worst_error, 1e-3f + 1e-4f);
    EXPECT_GT(apart, 0.1f) << "the arm reaches away from the swing";
    EXPECT_EQ(a.ik.overlays[0].last.converged, true);
    // Clear: the arm fades back over kFade. Per frame the weight moves by at most 1.5 dt / kFade
    // (smoothstep of a linear ramp), so the wrist moves by at most that share of how far apart the
    // poses are, twice for the arc's curvature, plus the walk's own travel.
    a.mc.clear_overlay(0, kFade);
    const float bound = 2.0f * 1.5f * kDt / kFade * apart + 2.0f * ordinary;
    float worst_jump = 0.0f;
    for (int f = 0; f < 40; ++f) {
        const glm::vec3 before = a.world(wrist);
        a.step(), ref.step();
        expect_body_beneath(a, ref, 200 + f);
        worst_jump = std::max(worst_jump, glm::length(a.world(wrist) - before));
    }
    EXPECT_LE(worst_jump, bound) << "the arm fades back, it does not snap";
    EXPECT_EQ(a.mc.overlay_weight(0), 0.0f);
    for (int j = 0; j < sk.joint_count(); ++j)
        EXPECT_EQ(a.mc.poses().view(0).model[static_cast<size_t>(j)], ref.mc.poses().view(0).model[static_cast<size_t>(j)])
            << "after the fade the pose is the walk's own: " << sk.names()[static_cast<size_t>(j)];
}

TEST_P(OverlayTest, UnreachableTargetGivesBestEffortAndAStatus) {
    Walker a(sk, rig, clips, gaits, GetParam()), ref(sk, rig, clips, gaits, GetParam());
    for (int f = 0; f < 90; ++f) {
        if (f >= 30) {
            ASSERT_TRUE(a.mc.set_overlay(0, reach_near(ref, {0.0f, 3.0f, 0.0f})));  // 3 m above the shoulder
        }
        a.step(), ref.step();
        expect_body_beneath(a, ref, f);
    }
    const IkResult& status = a.ik.overlays[0].last;
    EXPECT_FALSE(status.converged);
    EXPECT_GT(status.position_error, 2.0f) << "3 m away with an arm of about 0.6 m";
    EXPECT_GT(ref.xs[0].position.z, 1.9f) << "the walk went on (1.4 m/s for 1.5 s)";
}

TEST_P(OverlayTest, LosingIkAtALowerLodFadesTheArmBack) {
    Walker a(sk, rig, clips, gaits, GetParam()), ref(sk, rig, clips, gaits, GetParam());
    const int wrist = sk.find("RightWrist");
    float apart = 0.0f, ordinary = 0.0f;
    for (int f = 0; f < 90; ++f) {
        ASSERT_TRUE(a.mc.set_overlay(0, reach_near(ref)));
        const glm::vec3 r0 = ref.world(wrist);
        a.step(), ref.step();
        ordinary = std::max(ordinary, glm::length(ref.world(wrist) - r0));
        apart = std::max(apart, glm::length(a.world(wrist) - ref.world(wrist)));
    }
    a.lods[0].ik = IkSolver::None;  // the resolver took IK away
    const float bound = 2.0f * 1.5f * kDt / kFade * apart + 2.0f * ordinary;
    float worst_jump = 0.0f;
    for (int f = 0; f < 30; ++f) {
        ASSERT_TRUE(a.mc.set_overlay(0, reach_near(ref)));  // still asked for
        const glm::vec3 before = a.world(wrist);
        a.step(), ref.step();
        expect_body_beneath(a, ref, f);
        worst_jump = std::max(worst_jump, glm::length(a.world(wrist) - before));
    }
    EXPECT_LE(worst_jump, bound);
    EXPECT_EQ(a.mc.overlay_weight(0), 0.0f) << "faded out within kFade";
    EXPECT_LT(glm::length(a.world(wrist) - ref.world(wrist)), 1e-5f) << "the arm is the walk's again";
    a.lods[0].ik = IkSolver::Dls;  // IK back: the reach fades in again
    for (int f = 0; f < 30; ++f) {
        ASSERT_TRUE(a.mc.set_overlay(0, reach_near(ref)));
        a.step(), ref.step();
    }
    EXPECT_EQ(a.mc.overlay_weight(0), 1.0f);
    EXPECT_LT(glm::length(a.world(wrist) - reach_near(ref).target), 0.05f);
}

INSTANTIATE_TEST_SUITE_P(Methods, OverlayTest, ::testing::Values(WalkMethod::ClipPlayback, WalkMethod::Kinematic),
                         [](const ::testing::TestParamInfo<WalkMethod>& p) {
                             return std::string(p.param == WalkMethod::ClipPlayback ? "Clip" : "Kinematic");
                         });

}  // namespace
}  // namespace aloha
