// Test fixture: the built-in humanoid, its leg rig and the generated gait clips in a clip library,
// for tests that walk it through the motion controller.
#pragma once

#include "systems/motion/clip.hpp"
#include "systems/motion/controller.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "tests/common/test_humanoid.hpp"
#include "tests/systems/motion/walk_request.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace aloha::test {

/// Holds `sk`, `rig`, `clips` and the ids of the generated gait clips in `gaits` (walk and run).
class GeneratedGait : public ::testing::Test {
protected:
    void SetUp() override {
        const MotionLibrary lib = make_motion_library(sk, rig, "h");
        for (const RawAnimation& g : lib.gaits) gaits.push_back(clips.add(g, sk).value());
    }
    Skeleton sk = humanoid_skeleton_for();
    WalkRig rig = humanoid_rig(sk);
    ClipLibrary clips;
    std::vector<ClipId> gaits;

    /// One character walking straight at `speed` m/s through its own controller over the fixture's
    /// clips; `lod` is its animation level, changed freely between steps.
    struct Walker {
        Walker(const GeneratedGait& g, float speed) : mc(g.sk, g.clips, 1) {
            mc.set_walk_rig(g.rig);
            mc.set_walk_clips(g.gaits);
            EXPECT_TRUE(mc.push_request(0, straight_walk(speed)));
        }
        /// Advances one frame of `dt` seconds.
        void step(float dt) { mc.update(dt, lods, states, xs, vs); }
        /// World position of every joint after the last step.
        void world_joints(std::vector<glm::vec3>& out) const {
            const auto model = mc.poses().view(0).model;
            out.resize(model.size());
            for (size_t j = 0; j < out.size(); ++j) out[j] = xs[0].position + xs[0].rotation * glm::vec3(model[j][3]);
        }
        AnimLod& lod() { return lods[0]; }

        MotionController mc;
        std::vector<AnimLod> lods = std::vector<AnimLod>(1);
        std::vector<MotionState> states = std::vector<MotionState>(1);
        std::vector<Transform> xs = std::vector<Transform>(1);
        std::vector<Velocity> vs = std::vector<Velocity>(1);
    };
};

}  // namespace aloha::test
