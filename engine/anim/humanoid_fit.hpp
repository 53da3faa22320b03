// The canonical humanoid's rest pose laid over a mapped skeleton: where every canonical joint is
// (mapped ones where the file has them, missing optional ones interpolated between mapped
// neighbours in the reference humanoid's proportions) and how each canonical bone is turned
// relative to the reference humanoid's. Muscle layouts and joint limits written for the built-in
// humanoid are carried over to any mapped skeleton with it.
#pragma once

#include "engine/anim/humanoid_map.hpp"
#include "engine/anim/skeleton.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <vector>

namespace aloha {

/// Per canonical joint (canonical_humanoid() order).
struct CanonicalFit {
    std::vector<glm::vec3> position;   ///< rest model position on the target skeleton
    std::vector<glm::vec3> reference;  ///< rest model position on the reference humanoid
    std::vector<int> bone_child;       ///< canonical joint the bone points to (the reference's first
                                       ///< child at a non-zero offset), -1 when the joint has no bone
    std::vector<glm::quat> alignment;  ///< rotation taking the reference bone direction onto the
                                       ///< target's (the parent bone's when the joint has none)
    std::vector<float> bone_angle;     ///< angle of that rotation (radians), 0 without a bone
};

/// Fits the canonical humanoid to `target`. Requires target_map.humanoid and a reference whose
/// map (reference_map) has every canonical joint (the built-in humanoid), both in the same model
/// axes (+X left, +Y up, +Z forward) and at about the same height.
[[nodiscard]] CanonicalFit fit_canonical(const Skeleton& target, const HumanoidMap& target_map,
                                         const Skeleton& reference, const HumanoidMap& reference_map);

}  // namespace aloha
