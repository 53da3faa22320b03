// Immutable runtime skeleton: joints sorted so every parent precedes its children, rest pose
// stored structure-of-arrays, names for lookup. Built once from a RawSkeleton.
#pragma once

#include "engine/anim/raw_skeleton.hpp"
#include "engine/core/result.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace aloha {

/// Runtime skeleton. Invariant: parents()[i] < i for every non-root joint, roots have -1.
class Skeleton {
public:
    Skeleton() = default;

    /// Number of joints.
    [[nodiscard]] int joint_count() const { return static_cast<int>(parents_.size()); }
    /// Parent index of each joint (-1 for roots); parents precede children.
    [[nodiscard]] std::span<const int16_t> parents() const { return parents_; }
    /// Joint names in runtime order.
    [[nodiscard]] std::span<const std::string> names() const { return names_; }
    /// Rest-pose local translations / rotations / scales (structure of arrays).
    [[nodiscard]] std::span<const glm::vec3> rest_translations() const { return rest_t_; }
    [[nodiscard]] std::span<const glm::quat> rest_rotations() const { return rest_r_; }
    [[nodiscard]] std::span<const glm::vec3> rest_scales() const { return rest_s_; }
    /// Per-joint limits (all free unless set with set_limits at build time).
    [[nodiscard]] std::span<const JointLimit> limits() const { return limits_; }
    /// Index of the joint named `name`, or -1.
    [[nodiscard]] int find(std::string_view name) const;
    /// For each runtime joint, its index in the RawSkeleton it was built from.
    [[nodiscard]] std::span<const int> source_index() const { return source_index_; }

private:
    friend Result<Skeleton> build_skeleton(const RawSkeleton& raw, const std::string& source_name);
    friend Status set_joint_limits(Skeleton& skeleton, std::span<const std::string> names,
                                   std::span<const JointLimit> limits, const std::string& source_name);
    std::vector<int16_t> parents_;
    std::vector<std::string> names_;
    std::vector<glm::vec3> rest_t_;
    std::vector<glm::quat> rest_r_;
    std::vector<glm::vec3> rest_s_;
    std::vector<JointLimit> limits_;
    std::vector<int> source_index_;
};

/// Validates `raw` (parent indices in range, no cycles, at most 32767 joints, finite values) and
/// builds a Skeleton with parents ordered before children. `source_name` names the file for errors.
Result<Skeleton> build_skeleton(const RawSkeleton& raw, const std::string& source_name);

/// Sets limits for the joints named in `names` (same length as `limits`); unknown names are errors.
Status set_joint_limits(Skeleton& skeleton, std::span<const std::string> names,
                        std::span<const JointLimit> limits, const std::string& source_name);

}  // namespace aloha
