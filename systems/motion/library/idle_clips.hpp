// Generated clips besides the gait: standing idle (breathing, weight shift, a glance around),
// a turn on the spot in stepping feet, and a wave of the right hand. Each loops with no seam:
// every motion is periodic in the clip length and the turn ends one full revolution round.
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/skeleton.hpp"
#include "systems/motion/library/pose_builder.hpp"
#include "systems/motion/walk_rig.hpp"

#include <string>

namespace aloha {

/// Length of the generated idle (s): one weight shift, two breaths of 4 s each.
inline constexpr float kIdleSeconds = 8.0f;
/// Length of the turn on the spot (s): one revolution in eight steps.
inline constexpr float kTurnSeconds = 4.0f;
/// Length of the wave (s): raise, four waves, lower.
inline constexpr float kWaveSeconds = 3.0f;

/// Standing idle with feet planted (ground y = 0, ankles rig.ankle_height above it).
[[nodiscard]] RawAnimation make_idle_clip(const Skeleton& skeleton, const WalkRig& rig, const HumanoidJoints& joints,
                                          const std::string& name);
/// A full turn to the left on the spot: the root spins about +Y at a constant rate while the feet
/// step round it, each foot still between its steps.
[[nodiscard]] RawAnimation make_turn_clip(const Skeleton& skeleton, const WalkRig& rig, const HumanoidJoints& joints,
                                          const std::string& name);
/// The idle stance with the right hand raised and waved; starts and ends in the idle pose.
[[nodiscard]] RawAnimation make_wave_clip(const Skeleton& skeleton, const WalkRig& rig, const HumanoidJoints& joints,
                                          const std::string& name);

}  // namespace aloha
