// Test helpers: a CMU-named 31-joint skeleton (offsets copied from 131_01.bvh, scaled to metres),
// a small shoulder-elbow-wrist arm, and forward kinematics for posed model matrices.
#pragma once

#include "engine/anim/skeleton.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <span>
#include <tuple>
#include <string>
#include <vector>

namespace aloha::test {

/// CMU unit to metres (CMU FAQ: 1 unit = 0.056444 m).
inline constexpr float kCmuUnit = 0.056444f;

/// Builds a skeleton from (name, parent name, offset in file units) rows scaled by `scale`.
inline Skeleton make_skeleton(const std::vector<std::tuple<std::string, std::string, glm::vec3>>& rows, float scale) {
    RawSkeleton raw;
    for (const auto& [name, parent, offset] : rows) {
        RawJoint j;
        j.name = name;
        for (size_t p = 0; p < raw.joints.size(); ++p)
            if (raw.joints[p].name == parent) j.parent = static_cast<int>(p);
        j.translation = offset * scale;
        raw.joints.push_back(j);
    }
    auto s = build_skeleton(raw, "test");
    return s.ok() ? std::move(s).value() : Skeleton{};
}

/// The 31 joints of 131_01.bvh (HIERARCHY OFFSETs copied from the file), in metres.
inline Skeleton make_cmu_skeleton() {
    return make_skeleton({
        {"Hips", "", {0, 0, 0}},
        {"LHipJoint", "Hips", {0, 0, 0}},
        {"LeftHip", "LHipJoint", {1.24777f, -1.64261f, 0.71711f}},
        {"LeftKnee", "LeftHip", {2.49329f, -6.85026f, 0}},
        {"LeftAnkle", "LeftKnee", {2.36770f, -6.50520f, 0}},
        {"LeftToe", "LeftAnkle", {0.14820f, -0.40718f, 2.21395f}},
        {"RHipJoint", "Hips", {0, 0, 0}},
        {"RightHip", "RHipJoint", {-1.18320f, -1.64261f, 0.71711f}},
        {"RightKnee", "RightHip", {-2.46559f, -6.77417f, 0}},
        {"RightAnkle", "RightKnee", {-2.38450f, -6.55136f, 0}},
        {"RightToe", "RightAnkle", {-0.17454f, -0.47954f, 2.02925f}},
        {"lowerback", "Hips", {0, 0, 0}},
        {"Chest", "lowerback", {-0.02305f, 1.98660f, 0.00319f}},
        {"Chest2", "Chest", {-0.00718f, 1.99033f, -0.00533f}},
        {"lowerneck", "Chest2", {0, 0, 0}},
        {"Neck", "lowerneck", {0.00095f, 1.61015f, 0.10698f}},
        {"Head", "Neck", {-0.01060f, 1.59924f, 0.01317f}},
        {"LeftCollar", "Chest2", {0, 0, 0}},
        {"LeftShoulder", "LeftCollar", {3.05381f, 1.47088f, -0.01697f}},
        {"LeftElbow", "LeftShoulder", {0, -4.251060f, 0}},
        {"LeftWrist", "LeftElbow", {0, -3.275920f, 0}},
        {"lhand", "LeftWrist", {0, 0, 0}},
        {"LFingers", "lhand", {0, -0.657810f, 0}},
        {"LThumb", "LeftWrist", {0, 0, 0}},
        {"RightCollar", "Chest2", {0, 0, 0}},
        {"RightShoulder", "RightCollar", {-2.83695f, 1.31619f, -0.22674f}},
        {"RightElbow", "RightShoulder", {0, -4.460730f, 0}},
        {"RightWrist", "RightElbow", {0, -3.444160f, 0}},
        {"rhand", "RightWrist", {0, 0, 0}},
        {"RFingers", "rhand", {0, -0.616510f, 0}},
        {"RThumb", "RightWrist", {0, 0, 0}},
    }, kCmuUnit);
}

/// Shoulder at the origin, elbow 0.30 m below, wrist 0.25 m below the elbow (metres).
inline Skeleton make_arm_skeleton() {
    return make_skeleton({{"Shoulder", "", {0, 0, 0}}, {"Elbow", "Shoulder", {0, -0.30f, 0}}, {"Wrist", "Elbow", {0, -0.25f, 0}}},
                         1.0f);
}

/// Model matrices for the rest translations/scales of `s` with local rotations `rot` (one per joint).
inline std::vector<glm::mat4> pose_model(const Skeleton& s, std::span<const glm::quat> rot) {
    std::vector<glm::mat4> m(static_cast<size_t>(s.joint_count()));
    for (size_t j = 0; j < m.size(); ++j) {
        const glm::mat4 local = glm::translate(glm::mat4(1.0f), s.rest_translations()[j]) * glm::mat4_cast(rot[j]);
        m[j] = s.parents()[j] < 0 ? local : m[static_cast<size_t>(s.parents()[j])] * local;
    }
    return m;
}

}  // namespace aloha::test
