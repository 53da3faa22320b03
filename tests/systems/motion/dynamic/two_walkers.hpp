// Test fixture: two humanoids on one motion controller with the dynamic-walk hook registered, both
// given the same straight walk; character 0 walks with `method0`, character 1 with `method1`.
#pragma once

#include "systems/motion/dynamic/dynamic_hook.hpp"
#include "tests/systems/motion/ik/humanoid.hpp"
#include "tests/systems/motion/walk_request.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace aloha::test {

/// Two walkers stepped at 60 Hz; joint positions are read back in world space.
struct TwoWalkers {
    static constexpr float kDt = 1.0f / 60.0f;

    TwoWalkers(WalkMethod method0, WalkMethod method1, float speed) {
        mc.set_walk_rig(resolve_walk_rig(sk, "humanoid").value());
        register_dynamic_walk_hook(mc, dyn);
        lods[0].walk = method0;
        lods[1].walk = method1;
        EXPECT_TRUE(mc.push_request(0, straight_walk(speed)));
        EXPECT_TRUE(mc.push_request(1, straight_walk(speed)));
    }
    /// Advances both characters one frame.
    void step() { mc.update(kDt, lods, states, xs, vs); }
    /// World position of joint j of character c.
    glm::vec3 joint(uint32_t c, size_t j) const {
        return xs[c].position + xs[c].rotation * glm::vec3(mc.poses().view(c).model[j][3]);
    }
    /// World pelvis (the root joint) of character c.
    glm::vec3 pelvis(uint32_t c) const { return joint(c, 0); }
    /// Every joint of character c in world space.
    std::vector<glm::vec3> joints(uint32_t c) const {
        std::vector<glm::vec3> out(static_cast<size_t>(sk.joint_count()));
        for (size_t j = 0; j < out.size(); ++j) out[j] = joint(c, j);
        return out;
    }

    Skeleton sk = make_humanoid(true);
    ClipLibrary clips;
    MotionController mc{sk, clips, 2};
    DynamicHookContext dyn;
    std::vector<AnimLod> lods{2};
    std::vector<MotionState> states{2};
    std::vector<Transform> xs{2};
    std::vector<Velocity> vs{2};
};

}  // namespace aloha::test
