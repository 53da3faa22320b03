// Dynamic walk: constraint drift, uprightness, tracking of the kinematic target, real simulation.
#include "systems/motion/dynamic/dynamic_walk.hpp"
#include "systems/motion/ik/chain_fk.hpp"
#include "tests/systems/motion/dynamic/walk_target.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

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

// The humanoid under a "root" joint on the ground (Unreal's layout) with an IK helper leaf beside
// the pelvis: the same joints, one level down.
Skeleton rooted_humanoid() {
    const Skeleton h = test::make_humanoid(true);
    RawSkeleton raw;
    raw.joints.push_back(RawJoint{"root", -1, glm::vec3(0.0f), glm::quat(1, 0, 0, 0), glm::vec3(1.0f)});
    for (int j = 0; j < h.joint_count(); ++j) {
        const auto u = static_cast<size_t>(j);
        raw.joints.push_back(RawJoint{h.names()[u], h.parents()[u] + 1, h.rest_translations()[u], h.rest_rotations()[u], glm::vec3(1.0f)});
    }
    raw.joints.push_back(RawJoint{"ik_foot_root", 0, glm::vec3(0.1f, 0.0f, 0.0f), glm::quat(1, 0, 0, 0), glm::vec3(1.0f)});
    return build_skeleton(raw, "rooted").value();
}

TEST(DynamicWalk, AJointAboveThePelvisChangesNothingOfTheSimulation) {
    // With the pelvis as the root body, "root" and the helper are not simulated: the bodies, contacts and
    // targets are the pelvis-rooted humanoid's, so every step computes the same numbers and the simulated
    // pelvis and feet agree with the plain simulation's to float rounding (1e-5 m: the only new operations
    // are products with root's transform and its inverse). root moves on its own target translation (root
    // motion carried by the root joint): it takes that translation, and the pelvis stays where it was simulated.
    Sim plain;
    const Skeleton skel = rooted_humanoid();
    const int hips = skel.find("Hips"), root = skel.find("root"), helper = skel.find("ik_foot_root");
    PoseBuffers out = test::rest_pose(skel);
    std::vector<glm::quat> target(out.r.size());
    auto targets = [&](float t) {
        // The plain fixture's targets, moved one joint down; root and helper at rest.
        const glm::vec3 pelvis = test::walk_target(plain.skel, t, plain.walk, plain.target);
        for (int j = 0; j < plain.skel.joint_count(); ++j) target[static_cast<size_t>(skel.find(plain.skel.names()[static_cast<size_t>(j)]))] = plain.target[static_cast<size_t>(j)];
        target[static_cast<size_t>(root)] = target[static_cast<size_t>(helper)] = glm::quat(1, 0, 0, 0);
        return pelvis;
    };
    const glm::vec3 start = targets(0.0f);
    out.r = target;
    out.t[static_cast<size_t>(hips)] = start;
    test::compute_model(skel, out);
    DynamicWalkSettings settings;
    settings.root_joint = hips;
    DynamicWalkState state;
    ASSERT_TRUE(init_dynamic_walk(skel, out.cview(), glm::mat4(1.0f), state, settings).ok());
    ASSERT_EQ(state.bodies.size(), plain.state.bodies.size());
    EXPECT_EQ(state.bodies[0].joint, hips);
    EXPECT_EQ(state.owner[static_cast<size_t>(root)], -1);
    EXPECT_EQ(state.owner[static_cast<size_t>(helper)], -1);
    EXPECT_EQ(state.contacts.size(), plain.state.contacts.size());
    std::vector<glm::vec3> translations(out.t.size());
    const int foot = skel.find("LeftAnkle"), plain_foot = plain.skel.find("LeftAnkle");
    float worst = 0.0f;
    for (int i = 1; i <= 120; ++i) {
        plain.step(1.0f / 60.0f);
        const float t = static_cast<float>(i) / 60.0f;
        const glm::vec3 pelvis = targets(t);
        translations = out.t;
        translations[static_cast<size_t>(root)] = glm::vec3(0.1f * std::sin(3.0f * t), 0.0f, 0.05f * t);
        step_dynamic_walk(skel, target, pelvis, 1.0f / 60.0f, state, out.view(), nullptr, translations);
        for (const auto& [a, b] : {std::pair{hips, 0}, std::pair{foot, plain_foot}})
            worst = std::max(worst, glm::length(glm::vec3(out.m[static_cast<size_t>(a)][3]) - glm::vec3(plain.out.m[static_cast<size_t>(b)][3])));
        // The joints above and beside the pelvis take their target; the helper rides on root.
        EXPECT_EQ(out.t[static_cast<size_t>(root)], translations[static_cast<size_t>(root)]);
        EXPECT_GT(std::abs(out.r[static_cast<size_t>(root)].w), 1.0f - 1e-6f);
        EXPECT_LT(glm::length(glm::vec3(out.m[static_cast<size_t>(helper)][3]) - translations[static_cast<size_t>(root)] - glm::vec3(0.1f, 0.0f, 0.0f)),
                  1e-6f);
    }
    std::printf("[figure] rooted humanoid: pelvis and left ankle within %.2e m of the pelvis-rooted simulation over 2 s\n", static_cast<double>(worst));
    EXPECT_LT(worst, 1e-5f) << "pelvis and left ankle against the pelvis-rooted simulation";
    EXPECT_LT(max_constraint_error(state), 1e-3f);
}

TEST(DynamicWalk, RootJointAndContactsMustBeInTheSkeletonsSimulatedPart) {
    const Skeleton skel = rooted_humanoid();
    PoseBuffers pose = test::rest_pose(skel);
    DynamicWalkState state;
    DynamicWalkSettings settings;
    settings.root_joint = 999;
    const Status far = init_dynamic_walk(skel, pose.cview(), glm::mat4(1.0f), state, settings);
    ASSERT_FALSE(far.ok());
    EXPECT_NE(far.error().message.find("root joint 999 is not a joint"), std::string::npos) << far.error().to_string();
    settings.root_joint = skel.find("Hips");
    settings.contact_points = {DynamicContactPoint{skel.find("ik_foot_root"), glm::vec3(0.0f)}};
    const Status outside = init_dynamic_walk(skel, pose.cview(), glm::mat4(1.0f), state, settings);
    ASSERT_FALSE(outside.ok());
    EXPECT_NE(outside.error().message.find("'ik_foot_root' is outside the simulated subtree of root joint 'Hips'"), std::string::npos)
        << outside.error().to_string();
}

}  // namespace
}  // namespace aloha
