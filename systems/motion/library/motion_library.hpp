// The project's generated motion library for one humanoid skeleton: gait cycles at a ladder of
// speeds (walks below the walk-run transition, runs above it), idle, a turn on the spot and a wave.
// Every clip is an ordinary RawAnimation, so clip playback, the kinematic walk (which takes its
// upper body and stride from the gait) and the dynamic walk all use the same motion.
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/skeleton.hpp"
#include "systems/motion/walk_rig.hpp"

#include <string>
#include <vector>

namespace aloha {

/// Speeds (m/s) at which gait cycles are generated; requests in between warp the nearest one.
inline constexpr float kLibraryGaitSpeeds[] = {0.5f, 0.8f, 1.1f, 1.4f, 1.8f, 2.2f, 2.6f, 3.0f};

/// The library's clips, named "<prefix>.walk_1.40" / "<prefix>.run_2.60" (speed with two decimals),
/// "<prefix>.idle", "<prefix>.turn" and "<prefix>.wave".
struct MotionLibrary {
    std::vector<RawAnimation> gaits;  ///< one per kLibraryGaitSpeeds entry, slowest first
    RawAnimation idle, turn, wave;
};

/// Generates the library for `skeleton` with leg rig `rig` (ground at y = 0). Joints of the canonical
/// humanoid that the skeleton lacks keep their rest pose.
[[nodiscard]] MotionLibrary make_motion_library(const Skeleton& skeleton, const WalkRig& rig, const std::string& prefix);

/// Name of the gait clip at `speed` m/s ("walk_1.40" or "run_2.60") for a hip height of `hip_height` m.
[[nodiscard]] std::string gait_clip_name(float speed, float hip_height);

}  // namespace aloha
