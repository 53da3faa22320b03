// Error measure shared by the IK solvers: E = E_p + E_o (eq. 11) for the current effector state.
#pragma once

#include "systems/motion/ik/ik_types.hpp"

#include <glm/glm.hpp>

namespace aloha::ik {

/// Position and orientation error of an effector model matrix against a target.
struct IkError {
    float position = 0.0f;     ///< |P_c - P_d| (metres)
    float orientation = 0.0f;  ///< angle between O_c and O_d (radians)
    float combined = 0.0f;     ///< position (+ weight * orientation when the target uses orientation)
};

/// Evaluates E for `effector_model` (model matrix of the effector joint) against `target`.
[[nodiscard]] IkError ik_error(const glm::mat4& effector_model, const IkTarget& target);

/// Fills an IkResult from an error and an iteration count.
[[nodiscard]] IkResult make_ik_result(const IkError& e, int iterations, float tolerance);

}  // namespace aloha::ik
