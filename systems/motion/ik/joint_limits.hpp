// Joint-limit helpers: Euler XYZ decomposition of a local rotation relative to the rest rotation
// and clamping to a JointLimit box. Convention: local = rest * relative, relative = Rx(a) Ry(b) Rz(c).
#pragma once

#include "engine/anim/raw_skeleton.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace aloha::ik {

/// Euler angles (a, b, c) with q = Rx(a) * Ry(b) * Rz(c); b in [-pi/2, pi/2], a and c in (-pi, pi].
/// Requires a unit quaternion.
[[nodiscard]] glm::vec3 euler_xyz(const glm::quat& q);

/// Rotation Rx(e.x) * Ry(e.y) * Rz(e.z).
[[nodiscard]] glm::quat quat_from_euler_xyz(const glm::vec3& e);

/// Angles of `local` relative to `rest` (euler_xyz(inverse(rest) * local)). Requires unit quaternions.
[[nodiscard]] glm::vec3 relative_euler_xyz(const glm::quat& rest, const glm::quat& local);

/// Returns `local` with its rest-relative Euler angles clamped into `limit` (unchanged if the limit
/// is not `limited`). Requires unit quaternions.
[[nodiscard]] glm::quat clamp_to_limit(const JointLimit& limit, const glm::quat& rest, const glm::quat& local);

/// Axes (in the parent joint's frame) of the three Euler rotations of `local = rest * Rx(e.x) Ry(e.y) Rz(e.z)`:
/// axis 0 = rest * X, axis 1 = rest * Rx * Y, axis 2 = rest * Rx * Ry * Z. Used by limited joints,
/// which the solvers move one Euler angle at a time so box limits are enforced exactly.
void euler_axes(const glm::quat& rest, const glm::vec3& e, glm::vec3 axes[3]);

/// Angle theta about unit `axis` maximising sum_i b_i . (R(theta) a_i) (1-D Wahba; exact closed form).
[[nodiscard]] float best_angle_about(const glm::vec3& axis, const glm::vec3* a, const glm::vec3* b, int count);

}  // namespace aloha::ik
