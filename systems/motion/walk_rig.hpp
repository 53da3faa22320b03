// Leg rig for walking: which joints are the hips, knees, ankles and toes of a skeleton (the
// canonical humanoid's LeftHip, LeftKnee, LeftAnkle, LeftToe and Right*, found through the humanoid
// map), their rest measurements, and the analytic two-bone leg IK used to plant feet.
#pragma once

#include "engine/anim/humanoid_map.hpp"
#include "engine/anim/pose.hpp"
#include "engine/anim/rest_pose.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"

#include <array>
#include <string>
#include <vector>

namespace aloha {

/// Leg joint roles, per side (0 = left, 1 = right).
enum class LegRole : uint8_t { Hip = 0, Knee = 1, Ankle = 2, Toe = 3 };

/// Joint indices and rest measurements of a two-legged skeleton. Model space: Y up, the character
/// faces +Z (CMU convention), ground at y = 0 once the walk places the root.
struct WalkRig {
    int root = 0;                    ///< the pelvis (canonical Hips)
    std::array<int, 2> hip{};        ///< thigh joints (rotate the thigh)
    std::array<int, 2> knee{};       ///< knee joints; descendants of the hips (twist joints may sit between)
    std::array<int, 2> ankle{};      ///< ankle joints; descendants of the knees
    std::array<int, 2> toe{-1, -1};  ///< toe joints or -1
    std::array<float, 2> thigh{};    ///< hip-to-knee length (m)
    std::array<float, 2> shin{};     ///< knee-to-ankle length (m)
    float ankle_height = 0.0f;       ///< rest ankle height above the lowest foot point (m)
    float hip_drop = 0.0f;           ///< rest root height minus hip height (m, root above hips > 0)
    std::array<glm::vec3, 2> hip_offset{};  ///< rest hip position relative to the root (model axes)
    float leg_length = 0.0f;         ///< mean thigh + shin (m)
    std::vector<glm::quat> rest_model_rotations;  ///< rest pose model rotation of every joint
};

/// Takes the leg joints of `skeleton` from `map` and measures them. Errors (naming `source`): a
/// missing hip, knee or ankle, a knee not below its hip or an ankle not below its knee in the
/// hierarchy, a zero-length bone.
Result<WalkRig> resolve_walk_rig(const Skeleton& skeleton, const HumanoidMap& map, const std::string& source);

/// The same with the skeleton's own humanoid map (map_humanoid without an explicit map).
Result<WalkRig> resolve_walk_rig(const Skeleton& skeleton, const std::string& source);

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

/// Rotation part of an affine model matrix (columns normalised to remove scale).
[[nodiscard]] glm::quat matrix_rotation(const glm::mat4& m);

/// Analytic two-bone IK on one leg of `pose`: rewrites the local rotations of hip and knee so the
/// ankle reaches `target` (model space; clamped to the reachable range), the knee bending towards
/// `pole` (model direction), and of the ankle so the foot keeps its rest model orientation. Joints
/// between hip and knee or knee and ankle (twist bones) keep their local rotations.
/// Requires pose.model to hold the model matrices of the current local pose; leaves them stale
/// (run local-to-model again). Returns the distance left between ankle and target (0 when reachable).
float solve_leg_ik(const WalkRig& rig, const Skeleton& skeleton, int side, const glm::vec3& target,
                   const glm::vec3& pole, const PoseView& pose);

}  // namespace aloha
