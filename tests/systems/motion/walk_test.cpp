// Kinematic walk on a CMU-named skeleton: planted feet do not slide, the root advances at the
// requested speed, the rig resolves through the name table; plus the BVH walk clip when loadable.
#include "systems/motion/controller.hpp"
#include "systems/motion/kinematic_walk.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/walk_rig.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace aloha {
namespace {

// A hand-written CMU-named leg hierarchy with adult proportions (metres).
RawSkeleton cmu_legs() {
    RawSkeleton raw;
    auto add = [&](const char* name, int parent, glm::vec3 t) {
        RawJoint j;
        j.name = name;
        j.parent = parent;
        j.translation = t;
        raw.joints.push_back(j);
        return static_cast<int>(raw.joints.size()) - 1;
    };
    const int hips = add("Hips", -1, glm::vec3(0.0f));
    for (int side = 0; side < 2; ++side) {
        const float sx = side == 0 ? 1.0f : -1.0f;
        const int hj = add(side == 0 ? "LHipJoint" : "RHipJoint", hips, glm::vec3(0.0f));
        const int hip = add(side == 0 ? "LeftHip" : "RightHip", hj, glm::vec3(0.077f * sx, -0.107f, 0.045f));
        const int knee = add(side == 0 ? "LeftKnee" : "RightKnee", hip, glm::vec3(0.0f, -0.43f, 0.0f));
        const int ankle = add(side == 0 ? "LeftAnkle" : "RightAnkle", knee, glm::vec3(0.0f, -0.42f, 0.0f));
        add(side == 0 ? "LeftToe" : "RightToe", ankle, glm::vec3(0.0f, -0.05f, 0.12f));
    }
    const int back = add("lowerback", hips, glm::vec3(0.0f));
    add("Chest", back, glm::vec3(0.0f, 0.25f, 0.0f));
    return raw;
}

TEST(WalkRig, ResolvesCmuNamesAndReportsMissingRoles) {
    const Skeleton sk = build_skeleton(cmu_legs(), "cmu").value();
    const auto rig = resolve_walk_rig(sk, "cmu");
    ASSERT_TRUE(rig.ok()) << rig.error().to_string();
    EXPECT_EQ(sk.names()[static_cast<size_t>(rig.value().knee[1])], "RightKnee");
    EXPECT_NEAR(rig.value().thigh[0], 0.43f, 1e-6f);
    EXPECT_NEAR(rig.value().leg_length, 0.85f, 1e-6f);
    EXPECT_NEAR(rig.value().ankle_height, 0.05f, 1e-6f);  // toe 5 cm below the ankle
    RawSkeleton raw = cmu_legs();
    raw.joints[3].name = "LeftShinBone";  // no knee name any convention knows
    const Skeleton bad = build_skeleton(raw, "cmu").value();
    const auto missing = resolve_walk_rig(bad, "cmu.bvh");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().to_string().find("cmu.bvh: walk rig: no joint for canonical 'LeftKnee' in the humanoid map (convention CMU BVH)"), std::string::npos);
}

TEST(WalkRig, TwoBoneIkReachesTarget) {
    const Skeleton sk = build_skeleton(cmu_legs(), "cmu").value();
    const WalkRig rig = resolve_walk_rig(sk, "cmu").value();
    const size_t n = static_cast<size_t>(sk.joint_count());
    std::vector<glm::vec3> t(sk.rest_translations().begin(), sk.rest_translations().end());
    std::vector<glm::quat> r(sk.rest_rotations().begin(), sk.rest_rotations().end());
    std::vector<glm::vec3> s(sk.rest_scales().begin(), sk.rest_scales().end());
    std::vector<glm::mat4> m(n);
    PoseView pose{t, r, s, m};
    LocalToModelJob l2m{sk.parents(), t, r, s, nullptr, m};
    l2m.Run();
    const glm::vec3 target(0.1f, -0.8f, 0.25f);  // 0.72 m from the hip: reachable (legs 0.85 m)
    EXPECT_EQ(solve_leg_ik(rig, sk, 0, target, glm::vec3(0, 0, 1), pose), 0.0f);
    l2m.Run();
    const glm::vec3 ankle(m[static_cast<size_t>(rig.ankle[0])][3]);
    // Law-of-cosines solution in float: errors ~1e-7 per operation on 1 m values; 1e-5 m margin.
    EXPECT_NEAR(glm::length(ankle - target), 0.0f, 1e-5f);
    const glm::vec3 knee(m[static_cast<size_t>(rig.knee[0])][3]);
    EXPECT_GT(knee.z, 0.045f);  // knee bends forward (towards the pole)
}

TEST(KinematicWalk, PlantedFeetDoNotSlide) {
    const Skeleton sk = build_skeleton(cmu_legs(), "cmu").value();
    ClipLibrary clips;
    MotionController mc(sk, clips, 1);
    WalkRig rig = resolve_walk_rig(sk, "cmu").value();
    const int ankles[2] = {rig.ankle[0], rig.ankle[1]};
    mc.set_walk_rig(std::move(rig));
    std::vector<AnimLod> lods(1);
    lods[0].walk = WalkMethod::Kinematic;
    std::vector<MotionState> states(1);
    std::vector<Transform> xs(1);
    std::vector<Velocity> vs(1);
    MotionRequest walk;
    walk.kind = RequestKind::Walk;
    walk.speed = 1.3f;
    walk.target = glm::vec3(0, 0, 1);
    walk.crossfade_s = 0.0f;  // measure the pure walk
    ASSERT_TRUE(mc.push_request(0, walk));
    const float dt = 1.0f / 60.0f;
    // Per foot: world position at the start of the current stance and the largest drift from it.
    glm::vec3 start[2];
    bool in_stance[2] = {false, false};
    float worst = 0.0f;
    int stances = 0;
    const float duty = GaitParams{}.duty;
    for (int frame = 0; frame < 600; ++frame) {
        mc.update(dt, lods, states, xs, vs);
        const auto model = mc.poses().view(0).model;
        for (int side = 0; side < 2; ++side) {
            float phi = states[0].phase + (side == 0 ? 0.0f : 0.5f);
            phi -= std::floor(phi);
            const bool st = phi < duty;
            const glm::vec3 p = joint_world_position(model, ankles[side], xs[0]);
            if (st && !in_stance[side]) {
                start[side] = p;
                ++stances;
            } else if (st && frame > 0) {
                worst = std::max(worst, glm::length(p - start[side]));
            }
            in_stance[side] = st;
        }
    }
    EXPECT_GE(stances, 15);           // 10 s at ~1.2 cycles/s, two feet
    EXPECT_LT(worst, 0.01f);          // the requirement: under 1 cm per step
    EXPECT_LT(worst, 1e-4f);          // and in fact exact up to float rounding at ~5 m from the origin
    EXPECT_NEAR(xs[0].position.z, 1.3f * 600 * dt, 1e-3f);  // root advanced at the requested speed
    EXPECT_NEAR(glm::length(vs[0].linear), 1.3f, 1e-5f);
}

}  // namespace
}  // namespace aloha
