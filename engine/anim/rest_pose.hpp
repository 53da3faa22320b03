// Rest-pose helpers shared by the loaders and the layers: model matrices of a skeleton's rest pose
// and the shortest rotation between two directions.
#pragma once

#include "engine/anim/skeleton.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <vector>

namespace aloha {

/// Rest-pose model matrices of `skeleton` (translation * rotation * scale down from the roots).
[[nodiscard]] std::vector<glm::mat4> skeleton_rest_model(const Skeleton& skeleton);

/// Shortest rotation taking unit vector `from` onto unit vector `to` (a half turn about an axis
/// perpendicular to `from` when they are opposite).
[[nodiscard]] glm::quat rotation_between(const glm::vec3& from, const glm::vec3& to);

}  // namespace aloha
