// Damped-least-squares IK: 3 rotational DOF per joint, dq = J^T (J J^T + lambda^2 I)^-1 e, with
// Levenberg-Marquardt adaptation of lambda (raised when a step would increase E, lowered when it
// succeeds), extra damping near singular configurations and joint limits by clamping.
#pragma once

#include "engine/anim/pose.hpp"
#include "engine/anim/skeleton.hpp"
#include "systems/motion/ik/ik_types.hpp"

#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Solves `chain` toward `target` with damped least squares. Same requirements and outputs as
/// solve_ccd. Rows: 3 (position) or 6 (position + orientation_weight * rotation vector). A step
/// that does not reduce E is rejected and retried with 4x the damping (at most 6 tries per
/// iteration), so the recorded error never increases.
IkResult solve_dls(const Skeleton& skeleton, std::span<const int> chain, PoseView pose, const IkTarget& target,
                   const IkSettings& settings, std::span<float> error_per_iteration = {});

/// Job form of solve_dls for one character.
struct DlsJob {
    const Skeleton* skeleton = nullptr;     ///< required
    std::span<const int> chain;             ///< base..effector, 1..kMaxIkChain joints
    PoseView pose;                          ///< local transforms + model matrices, joint_count long
    IkTarget target;                        ///< model-space target
    IkSettings settings;                    ///< iteration cap, tolerance, damping
    std::span<float> error_per_iteration;   ///< optional convergence curve
    IkResult* result = nullptr;             ///< optional output

    /// Checks every requirement, appending one message per failure. True when runnable.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Runs the solve; requires Validate().
    void Run() const;
};

}  // namespace aloha
