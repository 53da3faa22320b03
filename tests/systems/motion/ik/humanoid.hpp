// Test fixture: a hand-built CMU-like humanoid (Y up, facing +Z, T-pose arms along +-X, metres)
// with realistic bone lengths and joint limits, plus a helper to compute model matrices.
#pragma once

#include "engine/anim/pose.hpp"
#include "engine/anim/skeleton.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cassert>
#include <string>
#include <vector>

namespace aloha::test {

/// Owning SoA pose with a PoseView accessor.
struct PoseBuffers {
    std::vector<glm::vec3> t;
    std::vector<glm::quat> r;
    std::vector<glm::vec3> s;
    std::vector<glm::mat4> m;
    /// Mutable view over the buffers.
    PoseView view() { return {t, r, s, m}; }
    /// Read-only view over the buffers.
    [[nodiscard]] ConstPoseView cview() const { return {t, r, s, m}; }
};

/// Builds the humanoid; with_limits adds realistic limits on hips, knees, ankles, shoulders, elbows.
inline Skeleton make_humanoid(bool with_limits) {
    RawSkeleton raw;
    auto add = [&](const char* name, int parent, glm::vec3 t) {
        raw.joints.push_back(RawJoint{name, parent, t, glm::quat(1, 0, 0, 0), glm::vec3(1.0f)});
        return static_cast<int>(raw.joints.size()) - 1;
    };
    const int hips = add("Hips", -1, {0.0f, 0.95f, 0.0f});
    for (int side = 0; side < 2; ++side) {
        const float sx = side == 0 ? 1.0f : -1.0f;
        const std::string p = side == 0 ? "Left" : "Right";
        const int hj = add(side == 0 ? "LHipJoint" : "RHipJoint", hips, {0.0f, 0.0f, 0.0f});
        const int hip = add((p + "Hip").c_str(), hj, {sx * 0.09f, -0.06f, 0.0f});
        const int knee = add((p + "Knee").c_str(), hip, {0.0f, -0.42f, 0.0f});
        const int ankle = add((p + "Ankle").c_str(), knee, {0.0f, -0.41f, 0.0f});
        const int toe = add((p + "Toe").c_str(), ankle, {0.0f, -0.06f, 0.13f});
        add((p + "ToeEnd").c_str(), toe, {0.0f, 0.0f, 0.05f});
    }
    const int lowerback = add("lowerback", hips, {0.0f, 0.0f, 0.0f});
    const int chest = add("Chest", lowerback, {0.0f, 0.21f, 0.0f});
    const int neck = add("Neck", chest, {0.0f, 0.25f, 0.0f});
    const int head = add("Head", neck, {0.0f, 0.10f, 0.0f});
    add("HeadTop", head, {0.0f, 0.18f, 0.0f});
    for (int side = 0; side < 2; ++side) {
        const float sx = side == 0 ? 1.0f : -1.0f;
        const std::string p = side == 0 ? "Left" : "Right";
        const int collar = add((p + "Collar").c_str(), chest, {sx * 0.02f, 0.20f, 0.0f});
        const int shoulder = add((p + "Shoulder").c_str(), collar, {sx * 0.17f, 0.0f, 0.0f});
        const int elbow = add((p + "Elbow").c_str(), shoulder, {sx * 0.29f, 0.0f, 0.0f});
        const int wrist = add((p + "Wrist").c_str(), elbow, {sx * 0.25f, 0.0f, 0.0f});
        add((p + "Hand").c_str(), wrist, {sx * 0.08f, 0.0f, 0.0f});
    }
    auto built = build_skeleton(raw, "humanoid");
    assert(built.ok());
    Skeleton skel = std::move(built).value();
    if (with_limits) {
        std::vector<std::string> names;
        std::vector<JointLimit> limits;
        auto lim = [&](const std::string& n, glm::vec3 lo, glm::vec3 hi) {
            names.push_back(n);
            limits.push_back(JointLimit{lo, hi, true});
        };
        for (const std::string p : {"Left", "Right"}) {
            const float s = p == "Left" ? 1.0f : -1.0f;
            lim(p + "Hip", {-2.0f, -0.7f, -0.8f}, {0.6f, 0.7f, 0.8f});
            lim(p + "Knee", {0.0f, -0.1f, -0.1f}, {2.5f, 0.1f, 0.1f});  // hinge about X
            lim(p + "Ankle", {-0.8f, -0.3f, -0.4f}, {0.7f, 0.3f, 0.4f});
            lim(p + "Shoulder", {-2.8f, -1.4f, -2.8f}, {2.8f, 1.4f, 2.8f});
            // Hinge about Z with mirrored ranges: both forearms flex toward +Y from the T-pose.
            lim(p + "Elbow", {-0.15f, -0.15f, s > 0 ? 0.0f : -2.5f}, {0.15f, 0.15f, s > 0 ? 2.5f : 0.0f});
            lim(p + "Wrist", {-1.2f, -0.5f, -1.2f}, {1.2f, 0.5f, 1.2f});
        }
        const Status st = set_joint_limits(skel, names, limits, "humanoid");
        assert(st.ok());
        (void)st;
    }
    return skel;
}

/// Recomputes every model matrix from the local pose (parents precede children).
inline void compute_model(const Skeleton& skel, PoseBuffers& pose) {
    for (int j = 0; j < skel.joint_count(); ++j) {
        const auto u = static_cast<size_t>(j);
        glm::mat4 local = glm::mat4_cast(pose.r[u]);
        local[0] *= pose.s[u].x;
        local[1] *= pose.s[u].y;
        local[2] *= pose.s[u].z;
        local[3] = glm::vec4(pose.t[u], 1.0f);
        const int p = skel.parents()[u];
        pose.m[u] = p < 0 ? local : pose.m[static_cast<size_t>(p)] * local;
    }
}

/// Rest pose with model matrices.
inline PoseBuffers rest_pose(const Skeleton& skel) {
    PoseBuffers pose;
    pose.t.assign(skel.rest_translations().begin(), skel.rest_translations().end());
    pose.r.assign(skel.rest_rotations().begin(), skel.rest_rotations().end());
    pose.s.assign(skel.rest_scales().begin(), skel.rest_scales().end());
    pose.m.resize(pose.t.size());
    compute_model(skel, pose);
    return pose;
}

}  // namespace aloha::test
