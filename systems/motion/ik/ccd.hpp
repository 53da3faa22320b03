// Cyclic coordinate descent IK (ALOHA paper eq. 9-11): one joint at a time from tip to base, each
// joint rotated to minimise E = E_p + E_o, then clamped to its joint limits.
#pragma once

#include "engine/anim/pose.hpp"
#include "engine/anim/skeleton.hpp"
#include "systems/motion/ik/ik_types.hpp"

#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Solves `chain` (from make_ik_chain) toward `target` (model space) with CCD.
/// Requires: pose spans of the skeleton's joint count holding valid local transforms and model
/// matrices (at least for the chain and its base's ancestors); 1 <= chain.size() <= kMaxIkChain.
/// On return the chain's local rotations and model matrices are updated (descendants off the chain
/// are not: the caller recomputes them). error_per_iteration[k] (if long enough) receives E after
/// iteration k. Per joint the best rotation aligns (effector - joint) with (target - joint) and,
/// with orientation, the effector axes u_i with the target axes weighted by orientation_weight
/// (Wahba's problem, solved iteratively).
IkResult solve_ccd(const Skeleton& skeleton, std::span<const int> chain, PoseView pose, const IkTarget& target,
                   const IkSettings& settings, std::span<float> error_per_iteration = {});

/// Job form of solve_ccd for one character.
struct CcdJob {
    const Skeleton* skeleton = nullptr;     ///< required
    std::span<const int> chain;             ///< base..effector, 1..kMaxIkChain joints
    PoseView pose;                          ///< local transforms + model matrices, joint_count long
    IkTarget target;                        ///< model-space target
    IkSettings settings;                    ///< iteration cap and tolerance
    std::span<float> error_per_iteration;   ///< optional convergence curve
    IkResult* result = nullptr;             ///< optional output

    /// Checks every requirement above, appending one message per failure. True when runnable.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Runs the solve; requires Validate().
    void Run() const;
};

namespace ik {
/// Shared validation of an IK job's inputs (used by CcdJob and DlsJob).
bool validate_ik_inputs(const Skeleton* skeleton, std::span<const int> chain, const PoseView& pose,
                        const IkSettings& settings, std::vector<std::string>* errors);
}  // namespace ik

}  // namespace aloha
