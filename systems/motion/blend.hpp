// Pose blending: weighted mix of two local poses (vector lerp, quaternion nlerp with hemisphere fix).
#pragma once

#include "engine/anim/pose.hpp"

#include <span>
#include <string>
#include <vector>

namespace aloha {

/// out = (1 - weight) * a + weight * b per joint; rotations are nlerped along the shorter arc.
/// weight 0 gives `a` exactly and weight 1 gives `b` exactly (when a and b are normalised).
struct BlendJob {
    std::span<const glm::vec3> a_translations;  ///< first pose
    std::span<const glm::quat> a_rotations;
    std::span<const glm::vec3> a_scales;
    std::span<const glm::vec3> b_translations;  ///< second pose, same joint count as the first
    std::span<const glm::quat> b_rotations;
    std::span<const glm::vec3> b_scales;
    float weight = 0.0f;                        ///< in [0,1]: 0 = a, 1 = b
    std::span<glm::vec3> translations;          ///< output (may alias a or b)
    std::span<glm::quat> rotations;
    std::span<glm::vec3> scales;

    /// True when the job can run; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Blends. Requires Validate().
    void Run() const;
};

/// Blends local pose `b` into `a` in place with `weight` (0 keeps a, 1 gives b). All views need
/// the same joint count; model matrices are not touched.
void blend_into(const PoseView& a, const ConstPoseView& b, float weight);

}  // namespace aloha
