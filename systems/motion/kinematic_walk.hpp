// Kinematic cyclic walk (WalkMethod::Kinematic): a speed-controlled procedural gait with planted
// feet. The root advances at the requested speed; each foot alternates stance (its world position
// stays fixed where it touched down) and swing (a raised arc to the next predicted landing point);
// analytic two-bone leg IK places the ankles and keeps the feet level.
#pragma once

#include "components/transform.hpp"
#include "engine/anim/pose.hpp"
#include "engine/anim/skeleton.hpp"
#include "systems/motion/walk_rig.hpp"

#include <array>
#include <cstdint>

namespace aloha {

/// Gait shape parameters (defaults are a normal human walk).
struct GaitParams {
    float duty = 0.6f;          ///< fraction of the cycle each foot is in stance (> 0.5: double support)
    float clearance = 0.08f;    ///< swing foot lift, as a fraction of leg length
    float reach = 0.97f;        ///< largest hip-to-ankle distance used, as a fraction of leg length
    float min_stride = 0.3f;    ///< stride length (two steps) at zero speed, fraction of leg length
    float stride_gain = 0.6f;   ///< stride growth per m/s of speed, fraction of leg length
    float max_stride = 1.9f;    ///< longest stride, fraction of leg length
};

/// Per-character walk state that lives across frames (part of the animation cache).
struct KinematicWalkState {
    float phase = 0.0f;                          ///< cycle phase in [0,1): left foot touches down at 0
    std::array<glm::vec3, 2> planted{};          ///< world position of each foot's last touchdown
    std::array<uint8_t, 2> stance{0, 0};         ///< 1 when the foot was in stance at the last pose
    uint8_t initialised = 0;                     ///< 0 until the first pose (feet then placed in gait)
};

/// Stride length (m, one full cycle = two steps) used at `speed` m/s.
[[nodiscard]] float walk_stride(const WalkRig& rig, float speed, const GaitParams& gait = {});

/// Advances the cycle phase by `dt` seconds at `speed` m/s (call every frame, posed or not).
void advance_walk_phase(KinematicWalkState& state, const WalkRig& rig, float speed, float dt,
                        const GaitParams& gait = {});

/// Writes the walking pose (local and model) for the current phase into `pose`: rest pose for the
/// upper body, root lowered so the legs reach, feet planted or swinging, leg IK. `placement` is the
/// character's world transform (root on the ground, facing its local +Z). Updates touchdown state.
void kinematic_walk_pose(const WalkRig& rig, const Skeleton& skeleton, KinematicWalkState& state, float speed,
                         const Transform& placement, const PoseView& pose, const GaitParams& gait = {});

/// World position of joint `joint` given model matrices `model` placed by `placement`.
[[nodiscard]] glm::vec3 joint_world_position(std::span<const glm::mat4> model, int joint, const Transform& placement);

}  // namespace aloha
