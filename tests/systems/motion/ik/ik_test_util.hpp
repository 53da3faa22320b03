// Helpers for the IK tests: random in-limit configurations and reach targets for the humanoid.
#pragma once

#include "systems/motion/ik/chain_fk.hpp"
#include "systems/motion/ik/ik_types.hpp"
#include "systems/motion/ik/joint_limits.hpp"
#include "tests/systems/motion/ik/humanoid.hpp"

#include <random>
#include <span>

namespace aloha::test {

using namespace aloha::ik;  // NOLINT: IK helpers in tests

/// A reach problem: a chain and a target produced by a known in-limit configuration.
struct Reach {
    std::vector<int> chain;
    glm::vec3 position;
    glm::quat orientation;
};

/// A relaxed start pose: elbows and knees flexed 0.4 rad, as an animated pose would be. A fully
/// straight limb pointing at the target is a stationary point of both CCD and DLS (the hinge's
/// gradient vanishes), so IK is always applied on top of such a pose.
inline PoseBuffers relaxed_pose(const Skeleton& skel) {
    PoseBuffers pose = rest_pose(skel);
    const std::pair<const char*, glm::vec3> bends[] = {{"LeftElbow", {0, 0, 0.4f}}, {"RightElbow", {0, 0, -0.4f}},
                                                       {"LeftKnee", {0.4f, 0, 0}}, {"RightKnee", {0.4f, 0, 0}}};
    for (const auto& [name, e] : bends) {
        const int j = skel.find(name);
        if (j >= 0) pose.r[static_cast<size_t>(j)] = skel.rest_rotations()[static_cast<size_t>(j)] * quat_from_euler_xyz(e);
    }
    compute_model(skel, pose);
    return pose;
}

/// Sets random rest-relative Euler angles within `spread` radians of the current pose's angles,
/// kept `margin` radians inside each limited joint's box, so the target is strictly reachable.
inline void randomise_chain(const Skeleton& skel, std::span<const int> chain, PoseBuffers& pose, std::mt19937& rng,
                            float margin, float spread) {
    for (int j : chain) {
        const auto u = static_cast<size_t>(j);
        const JointLimit& l = skel.limits()[u];
        const glm::vec3 cur = relative_euler_xyz(skel.rest_rotations()[u], pose.r[u]);
        glm::vec3 e;
        for (int a = 0; a < 3; ++a) {
            std::uniform_real_distribution<float> d(-spread, spread);
            e[a] = cur[a] + d(rng);
            if (l.limited) e[a] = glm::clamp(e[a], l.min_angles[a] + margin, l.max_angles[a] - margin);
        }
        pose.r[u] = skel.rest_rotations()[u] * quat_from_euler_xyz(e);
    }
    compute_model(skel, pose);
}

/// `count` reach targets per chain (arms Shoulder..Wrist, legs Hip..Ankle) from random in-limit poses
/// within 0.7 rad per Euler angle of the relaxed pose (IK adjusts an animated pose).
inline std::vector<Reach> make_reaches(const Skeleton& skel, int count, unsigned seed) {
    std::vector<Reach> out;
    std::mt19937 rng(seed);
    const char* chains[4][2] = {{"LeftShoulder", "LeftWrist"}, {"RightShoulder", "RightWrist"},
                                {"LeftHip", "LeftAnkle"}, {"RightHip", "RightAnkle"}};
    for (auto& c : chains) {
        const std::vector<int> chain = make_ik_chain(skel, skel.find(c[0]), skel.find(c[1]));
        for (int i = 0; i < count; ++i) {
            PoseBuffers pose = relaxed_pose(skel);
            randomise_chain(skel, chain, pose, rng, 0.05f, 0.7f);
            const glm::mat4& m = pose.m[static_cast<size_t>(chain.back())];
            out.push_back(Reach{chain, matrix_position(m), matrix_rotation(m)});
        }
    }
    return out;
}

/// Sum of bone lengths along a chain in the rest pose.
inline float chain_length(const Skeleton& skel, std::span<const int> chain) {
    float len = 0.0f;
    for (size_t k = 1; k < chain.size(); ++k)
        len += glm::length(skel.rest_translations()[static_cast<size_t>(chain[k])]);
    return len;
}

}  // namespace aloha::test
