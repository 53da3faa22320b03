// Test helper: a procedural walk target for the humanoid fixture (local rotations + root position).
#pragma once

#include "systems/motion/ik/joint_limits.hpp"
#include "tests/systems/motion/ik/humanoid.hpp"

#include <cmath>

namespace aloha::test {

/// Gait parameters: period (s), forward speed (m/s, +Z), pelvis height (m).
struct WalkParams {
    float period = 1.1f;
    float speed = 1.1f;
    float height = 0.92f;
};

/// Writes the target local rotations at time t and returns the root position (character frame).
/// Hips swing +-0.35 rad about X, knees flex up to 0.7 rad in swing, arms hang and swing.
inline glm::vec3 walk_target(const Skeleton& skel, float t, const WalkParams& w, std::span<glm::quat> out) {
    for (size_t j = 0; j < out.size(); ++j) out[j] = skel.rest_rotations()[j];
    const float phi = 6.2831853f * t / w.period;
    auto set = [&](const char* name, glm::vec3 e) {
        const int j = skel.find(name);
        if (j >= 0) out[static_cast<size_t>(j)] = skel.rest_rotations()[static_cast<size_t>(j)] * ik::quat_from_euler_xyz(e);
    };
    for (int side = 0; side < 2; ++side) {
        const float ph = phi + (side == 0 ? 0.0f : 3.14159265f);
        const bool left = side == 0;
        const float swing = std::sin(ph);
        const float knee = 0.1f + 0.6f * std::max(0.0f, std::sin(ph + 1.2f));
        set(left ? "LeftHip" : "RightHip", {-0.35f * swing, 0.0f, 0.0f});
        set(left ? "LeftKnee" : "RightKnee", {knee, 0.0f, 0.0f});
        set(left ? "LeftAnkle" : "RightAnkle", {0.15f * std::sin(ph - 0.5f), 0.0f, 0.0f});
        // Arms: hang down (about Z) and swing opposite to the same-side leg (about Y).
        set(left ? "LeftShoulder" : "RightShoulder", {0.0f, 0.3f * swing, left ? -1.3f : 1.3f});
        set(left ? "LeftElbow" : "RightElbow", {0.0f, 0.0f, left ? 0.3f : -0.3f});
    }
    set("Chest", {0.05f, 0.08f * std::sin(phi), 0.0f});
    return {0.0f, w.height + 0.02f * std::cos(2.0f * phi), w.speed * t};
}

}  // namespace aloha::test
