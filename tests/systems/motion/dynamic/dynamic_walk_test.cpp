// Dynamic walk: constraint drift, uprightness, tracking of the kinematic target, real simulation.
#include "systems/motion/dynamic/dynamic_walk.hpp"
#include "systems/motion/ik/chain_fk.hpp"
#include "tests/systems/motion/dynamic/walk_target.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

using test::PoseBuffers;

struct Sim {
    Skeleton skel = test::make_humanoid(true);
    PoseBuffers out;
    std::vector<glm::quat> target;
    DynamicWalkState state;
    test::WalkParams walk;
    float t = 0.0f;

    explicit Sim(const DynamicWalkSettings& settings = {}) {
        out = test::rest_pose(skel);
        target.resize(out.r.size());
        const glm::vec3 root = test::walk_target(skel, 0.0f, walk, target);
        out.r = target;
        out.t[0] = root;
        test::compute_model(skel, out);
        const Status st = init_dynamic_walk(skel, out.cview(), glm::mat4(1.0f), state, settings);
        EXPECT_TRUE(st.ok()) << (st.ok() ? "" : st.error().to_string());
    }
    glm::vec3 step(float dt) {
        t += dt;
        const glm::vec3 root = test::walk_target(skel, t, walk, target);
        step_dynamic_walk(skel, target, root, dt, state, out.view(), nullptr);
        return root;
    }
};

TEST(DynamicWalk, BuildsMergedLinks) {
    Sim sim;
    // Hips absorbs the zero-length LHipJoint/RHipJoint/lowerback; leaves (ToeEnd, HeadTop, Hand) weld.
    EXPECT_EQ(sim.state.owner[static_cast<size_t>(sim.skel.find("LHipJoint"))], 0);
    EXPECT_EQ(sim.state.owner[static_cast<size_t>(sim.skel.find("lowerback"))], 0);
    const int toe = sim.state.owner[static_cast<size_t>(sim.skel.find("LeftToe"))];
    EXPECT_EQ(sim.state.owner[static_cast<size_t>(sim.skel.find("LeftToeEnd"))], toe);
    EXPECT_EQ(sim.state.bodies.size(), 20u);
    EXPECT_GT(sim.state.total_mass, 30.0f);
    EXPECT_LT(sim.state.total_mass, 120.0f);
    EXPECT_FALSE(sim.state.contacts.empty());
    EXPECT_LT(max_constraint_error(sim.state), 1e-5f);  // built from a consistent pose
}

TEST(DynamicWalk, InitRejectsBadInput) {
    const Skeleton skel = test::make_humanoid(false);
    PoseBuffers pose = test::rest_pose(skel);
    DynamicWalkState state;
    ConstPoseView bad = pose.cview();
    bad.model = bad.model.first(3);
    EXPECT_FALSE(init_dynamic_walk(skel, bad, glm::mat4(1.0f), state).ok());
    pose.m[static_cast<size_t>(skel.find("LeftHip"))][3][1] = std::nanf("");
    const Status st = init_dynamic_walk(skel, pose.cview(), glm::mat4(1.0f), state);
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.error().message.find("LeftHip"), std::string::npos);
}

}  // namespace
}  // namespace aloha
