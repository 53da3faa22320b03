// Kinematic cyclic walk (WalkMethod::Kinematic): a speed-controlled procedural gait with planted
// feet. The root advances at the requested speed; each foot alternates stance (its world position
// stays fixed where it touched down) and swing (a raised arc to the next predicted landing point);
// analytic two-bone leg IK places the ankles and keeps the feet level.
#pragma once

#include "components/transform.hpp"
#include "engine/anim/pose.hpp"
#include "engine/anim/skeleton.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/sampling.hpp"
#include "systems/motion/walk_rig.hpp"

#include <array>
#include <cstdint>

namespace aloha {

/// Gait shape parameters (defaults are a normal human walk). The stride at each speed comes from the
/// gait relations shared with the generated gait clips (library/gait_model.hpp).
struct GaitParams {
    float duty = 0.6f;          ///< fraction of the cycle each foot is in stance (> 0.5: double support)
    float clearance = 0.08f;    ///< swing foot lift, as a fraction of leg length
    float reach = 0.97f;        ///< largest hip-to-ankle distance used, as a fraction of leg length
    float max_stride = 1.9f;    ///< longest stride, fraction of leg length
};

/// Per-character walk state that lives across frames (part of the animation cache).
struct KinematicWalkState {
    float phase = 0.0f;                          ///< cycle phase in [0,1): left foot touches down at 0
    std::array<glm::vec3, 2> planted{};          ///< world position of each foot's last touchdown
    std::array<uint8_t, 2> stance{0, 0};         ///< 1 when the foot was in stance at the last pose
    uint8_t initialised = 0;                     ///< 0 until the first pose (feet then placed in gait)
};

/// Stride length (m, one full cycle = two steps) used at `speed` m/s: Alexander's relation for the
/// rig's hip height (gait_cycle), at most gait.max_stride leg lengths.
[[nodiscard]] float walk_stride(const WalkRig& rig, float speed, const GaitParams& gait = {});

/// Advances the cycle phase by `dt` seconds at `speed` m/s (call every frame, posed or not).
void advance_walk_phase(KinematicWalkState& state, const WalkRig& rig, float speed, float dt,
                        const GaitParams& gait = {});

/// Samples gait cycle `clip` (root travelling along its own horizontal direction) at `time` with the
/// travel taken out and turned to face +Z, as the walk plays it in place while the transform moves.
void sample_walk_cycle(const AnimationClip& clip, float time, SamplingCache* cache, const PoseView& out);

/// Writes the walking pose (local and model) for the current phase into `pose`: the upper body,
/// pelvis motion and arm swing of gait cycle `body` sampled at the same phase (the rest pose when
/// `body` is null), root lowered as far as the legs need to reach, feet planted or swinging, leg IK.
/// `placement` is the character's world transform (root on the ground, facing its local +Z).
/// Updates touchdown state.
void kinematic_walk_pose(const WalkRig& rig, const Skeleton& skeleton, KinematicWalkState& state, float speed,
                         const Transform& placement, const PoseView& pose, const GaitParams& gait = {},
                         const AnimationClip* body = nullptr);

/// World position of joint `joint` given model matrices `model` placed by `placement`.
[[nodiscard]] glm::vec3 joint_world_position(std::span<const glm::mat4> model, int joint, const Transform& placement);

}  // namespace aloha
