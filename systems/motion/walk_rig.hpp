// Leg rig for walking: which joints are the hips, knees, ankles and toes of a skeleton (found by
// name through a mapping table with fallbacks), their rest measurements, and the analytic
// two-bone leg IK used to plant feet.
#pragma once

#include "engine/anim/pose.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"

#include <array>
#include <string>
#include <vector>

namespace aloha {

/// Leg joint roles, per side (0 = left, 1 = right).
enum class LegRole : uint8_t { Hip = 0, Knee = 1, Ankle = 2, Toe = 3 };

/// Candidate joint names per side and role, tried in order. The default table covers the CMU BVH
/// skeleton (LeftHip, LeftKnee, LeftAnkle, LeftToe, Right...), Mixamo / HumanIK (LeftUpLeg,
/// LeftLeg, LeftFoot, LeftToeBase, with or without a "mixamorig:" prefix), Unreal (thigh_l,
/// calf_l, foot_l, ball_l) and CesiumMan (leg_joint_L_1, _2, _3, _5). Add rows for other skeletons.
struct LegNameTable {
    std::array<std::array<std::vector<std::string>, 4>, 2> names;  ///< [side][role] candidates
};

/// The built-in table described above.
[[nodiscard]] const LegNameTable& default_leg_names();

/// Joint indices and rest measurements of a two-legged skeleton. Model space: Y up, the character
/// faces +Z (CMU convention), ground at y = 0 once the walk places the root.
struct WalkRig {
    int root = 0;                    ///< the root joint (pelvis), joint 0
    std::array<int, 2> hip{};        ///< thigh joints (rotate the thigh)
    std::array<int, 2> knee{};       ///< knee joints; parent is the hip
    std::array<int, 2> ankle{};      ///< ankle joints; parent is the knee
    std::array<int, 2> toe{-1, -1};  ///< toe joints or -1
    std::array<float, 2> thigh{};    ///< hip-to-knee length (m)
    std::array<float, 2> shin{};     ///< knee-to-ankle length (m)
    float ankle_height = 0.0f;       ///< rest ankle height above the lowest foot point (m)
    float hip_drop = 0.0f;           ///< rest root height minus hip height (m, root above hips > 0)
    std::array<glm::vec3, 2> hip_offset{};  ///< rest hip position relative to the root (model axes)
    float leg_length = 0.0f;         ///< mean thigh + shin (m)
    std::vector<glm::quat> rest_model_rotations;  ///< rest pose model rotation of every joint
};

/// Finds the leg joints of `skeleton` with `table` and measures them. Errors name the missing role
/// and the candidates tried, or a knee/ankle whose parent is not the hip/knee. `source` names the
/// skeleton for errors.
Result<WalkRig> resolve_walk_rig(const Skeleton& skeleton, const std::string& source,
                                 const LegNameTable& table = default_leg_names());

/// Where a two-bone chain's middle and end joints go to reach a target.
struct TwoBoneSolution {
    glm::vec3 middle;  ///< new middle joint (knee, elbow) position
    glm::vec3 end;     ///< new end joint position: the target, clamped to the reachable range
};

/// Analytic two-bone IK in positions: chain H (upper) - K (middle) - A (end) reaching `target`, the
/// middle joint bending towards `pole`; keeps 1e-4 m from full extension or folding.
[[nodiscard]] TwoBoneSolution solve_two_bone(const glm::vec3& H, const glm::vec3& K, const glm::vec3& A,
                                             const glm::vec3& target, const glm::vec3& pole);

/// For skeletons whose rest pose stands with its soles on y = 0 (the project's humanoid): measures
/// the ankle height from that ground instead of from the lowest foot joint. Requires the rig of
/// `skeleton` and rest ankles above y = 0.
void stand_rig_on_rest_ground(WalkRig& rig, const Skeleton& skeleton);

/// Shortest rotation taking unit vector `from` onto unit vector `to`.
[[nodiscard]] glm::quat rotation_between(const glm::vec3& from, const glm::vec3& to);

/// Rotation part of an affine model matrix (columns normalised to remove scale).
[[nodiscard]] glm::quat matrix_rotation(const glm::mat4& m);

/// Analytic two-bone IK on one leg of `pose`: rewrites the local rotations of hip and knee so the
/// ankle reaches `target` (model space; clamped to the reachable range), the knee bending towards
/// `pole` (model direction), and of the ankle so the foot keeps its rest model orientation.
/// Requires pose.model to hold the model matrices of the current local pose; leaves them stale
/// (run local-to-model again). Returns the distance left between ankle and target (0 when reachable).
float solve_leg_ik(const WalkRig& rig, const Skeleton& skeleton, int side, const glm::vec3& target,
                   const glm::vec3& pole, const PoseView& pose);

}  // namespace aloha
