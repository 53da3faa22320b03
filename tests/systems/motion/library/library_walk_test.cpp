// The motion library inside the motion controller: walk requests at the clip level play the
// nearest gait and warp its cadence (feet stay planted in the world at any requested speed), and the
// kinematic walk carries the gait's upper body (arms swing) over its IK-planted legs.
#include "systems/motion/controller.hpp"
#include "systems/motion/library/gait_clip.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "tests/common/test_humanoid.hpp"
#include "tests/systems/motion/skate_meter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

namespace aloha {
namespace {

class LibraryWalk : public ::testing::Test {
protected:
    void SetUp() override {
        const MotionLibrary lib = make_motion_library(sk, rig, "h");
        for (const RawAnimation& g : lib.gaits) gaits.push_back(clips.add(g, sk).value());
    }
    // Walks one character for `seconds` at `speed` with `method`; calls probe(model, transform) each frame.
    template <class Probe>
    void walk(float speed, WalkMethod method, float seconds, Probe probe, uint16_t interval = 1,
              float dt = 1.0f / 120.0f) {
        MotionController mc(sk, clips, 1);
        mc.set_walk_rig(rig);
        mc.set_walk_clips(gaits);
        std::vector<AnimLod> lods(1);
        lods[0].walk = method;
        lods[0].update_interval = interval;
        std::vector<MotionState> states(1);
        std::vector<Transform> xs(1);
        std::vector<Velocity> vs(1);
        MotionRequest r;
        r.kind = RequestKind::Walk;
        r.speed = speed;
        r.target = glm::vec3(0, 0, 1);
        r.crossfade_s = 0.0f;
        ASSERT_TRUE(mc.push_request(0, r));
        for (int f = 0; f < static_cast<int>(seconds / dt); ++f) {
            mc.update(dt, lods, states, xs, vs);
            probe(mc.poses().view(0).model, xs[0]);
        }
    }
    Skeleton sk = test::humanoid_skeleton_for();
    WalkRig rig = test::humanoid_rig(sk);
    ClipLibrary clips;
    std::vector<ClipId> gaits;
};

// The bound: at most 2 mm of contact travel per metre walked, at any requested speed.
TEST_F(LibraryWalk, ClipLevelFeetStayPlantedAtAnySpeed) {
    PoseBuilder rest(sk);
    for (float speed : {0.8f, 1.0f, 1.4f, 2.0f, 2.5f}) {
        test::SkateMeter m;
        walk(speed, WalkMethod::ClipPlayback, 4.0f,
             [&](std::span<const glm::mat4> model, const Transform& x) { m.add(rig, rest, model, x); });
        const float walked = speed * 4.0f;
        EXPECT_GE(m.contacts, 8) << speed;
        EXPECT_LE(1000.0f * m.total / walked, 2.0f) << "mm per metre at " << speed << " m/s";
        std::printf("clip level %.1f m/s: %.3f mm per metre\n", speed, 1000.0f * m.total / walked);
    }
}

// Throttled at update intervals 2, 4 and 8 (60 Hz frames): the frames between updates show the
// blend of the key poses, so a planted foot stays within 5 mm of where it touched down (the issue's
// bound) instead of sliding with the transform by speed * dt per skipped frame (2.3 cm per frame
// at 1.4 m/s, 16 cm over an interval of 8).
TEST_F(LibraryWalk, ThrottledClipLevelKeepsFeetPlanted) {
    PoseBuilder rest(sk);
    for (uint16_t interval : {uint16_t{2}, uint16_t{4}, uint16_t{8}}) {
        test::SkateMeter m;
        walk(1.4f, WalkMethod::ClipPlayback, 4.0f,
             [&](std::span<const glm::mat4> model, const Transform& x) { m.add(rig, rest, model, x); }, interval,
             1.0f / 60.0f);
        EXPECT_GE(m.contacts, 8) << interval;
        EXPECT_LE(m.worst, 0.005f) << "interval " << interval;
        std::printf("interval %d: worst contact travel %.2f mm, %.3f mm per metre\n", interval, 1000.0f * m.worst,
                    1000.0f * m.total / 5.6f);
    }
}

TEST_F(LibraryWalk, KinematicWalkSwingsTheArms) {
    const HumanoidJoints j = find_humanoid_joints(sk);
    float lo = 1e9f, hi = -1e9f;
    walk(1.4f, WalkMethod::Kinematic, 2.0f, [&](std::span<const glm::mat4> model, const Transform&) {
        // Left wrist forward of the pelvis, in the character's frame.
        const float z = model[static_cast<size_t>(j.wrist[0])][3].z - model[0][3].z;
        lo = std::min(lo, z), hi = std::max(hi, z);
    });
    EXPECT_GT(hi - lo, 0.1f) << "the arm swings forward and back over the cycle";
}

}  // namespace
}  // namespace aloha
