// Inverse-kinematics shared types: targets, settings, results, chain construction.
// Used by the CCD (eq. 9-11 of the ALOHA paper) and damped-least-squares solvers.
#pragma once

#include "engine/anim/skeleton.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <vector>

namespace aloha {

/// Longest chain (joints from base to effector inclusive) the solvers accept; they allocate nothing.
inline constexpr int kMaxIkChain = 16;

/// Desired end-effector state in the character's model space (the paper's P_d and O_d).
struct IkTarget {
    glm::vec3 position{0.0f};                        ///< P_d, metres (model space)
    glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};   ///< O_d, model-space rotation of the effector joint
    bool use_orientation = false;                    ///< include E_o in E = E_p + E_o (eq. 11)
    float orientation_weight = 0.1f;                 ///< metres per radian: E = |dp| + weight * angle
};

/// Stopping rule and damping shared by both solvers.
struct IkSettings {
    int max_iterations = 10;  ///< iteration cap (a CCD iteration is one tip-to-base sweep)
    float tolerance = 1e-3f;  ///< stop when E = |dp| (+ weight * angle) <= tolerance (metres)
    float damping = 0.05f;    ///< DLS: initial / singularity damping lambda (metres); CCD ignores it
};

/// What a solve did.
struct IkResult {
    int iterations = 0;            ///< iterations performed (0 if the start pose already met the tolerance)
    float position_error = 0.0f;   ///< final |P_c - P_d| (metres)
    float orientation_error = 0.0f;///< final angle between O_c and O_d (radians; computed even if unused)
    bool converged = false;        ///< final E <= tolerance
};

/// Joints from `base_joint` down to `effector_joint` inclusive (base first), following parents.
/// Empty if either index is out of range, base is not an ancestor of (or equal to) the effector,
/// or the chain would be longer than kMaxIkChain.
[[nodiscard]] std::vector<int> make_ik_chain(const Skeleton& skeleton, int base_joint, int effector_joint);

}  // namespace aloha
