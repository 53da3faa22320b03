// Small forward-kinematics helpers for IK chains (a chain is a parent-to-child path of joints).
// Kept inside the IK module so it does not depend on the clip-sampling code.
#pragma once

#include "engine/anim/pose.hpp"
#include "engine/anim/skeleton.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <span>

namespace aloha::ik {

/// Translation part of a model matrix.
[[nodiscard]] inline glm::vec3 matrix_position(const glm::mat4& m) { return glm::vec3(m[3]); }

/// Rotation part of a model matrix (columns normalised first, so uniform scale is removed).
[[nodiscard]] glm::quat matrix_rotation(const glm::mat4& m);

/// Model matrix of the parent of `joint` read from `model` (identity for a root).
/// Requires `model` to hold the skeleton's joint count.
[[nodiscard]] glm::mat4 parent_model(const Skeleton& skeleton, std::span<const glm::mat4> model, int joint);

/// Recomputes pose.model for chain[first..] from the chain's local transforms, starting from the
/// model matrix of chain[first]'s parent. Requires a valid chain (each joint the parent of the next).
void update_chain_model(const Skeleton& skeleton, std::span<const int> chain, const PoseView& pose, size_t first);

/// Shortest-arc rotation taking direction `from` to direction `to` (identity if either is ~zero).
[[nodiscard]] glm::quat shortest_arc(const glm::vec3& from, const glm::vec3& to);

/// Rotation vector (axis * angle, angle in [0, pi]) of a unit quaternion.
[[nodiscard]] glm::vec3 rotation_vector(const glm::quat& q);

/// Unit quaternion for a rotation vector (axis * angle).
[[nodiscard]] glm::quat quat_from_rotation_vector(const glm::vec3& v);

/// Angle in [0, pi] between two unit quaternions.
[[nodiscard]] float rotation_angle_between(const glm::quat& a, const glm::quat& b);

}  // namespace aloha::ik
