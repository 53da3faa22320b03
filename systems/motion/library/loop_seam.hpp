// Closing a loop's seam: a loop cut from a take (or authored as a cycle) whose last pose and motion differ a
// little from its first would jump each time it repeats. The difference is split between the two ends and faded
// in over a window at each, so the looped clip is continuous in pose, and in velocity where the source was.
#pragma once

#include "engine/anim/raw_animation.hpp"

#include <vector>

namespace aloha {

/// A rotation as a rotation vector: its axis times its angle (radians), the shorter way round.
[[nodiscard]] glm::vec3 rotation_vector(glm::quat q);

/// The rotation of a rotation vector (the inverse of rotation_vector).
[[nodiscard]] glm::quat from_rotation_vector(const glm::vec3& r);

/// How far into the loop from each end the seam's difference is spread (seconds).
inline constexpr float kSeamWindow = 0.25f;

/// The velocities the source take has where a loop was cut from it, per joint (index as the loop's tracks): the
/// loop's seam should carry on as the take does at its end, so the velocity to correct is the difference between
/// the take's velocities at the two cut points, measured alike (a kink the take has at both, a heel strike, is no
/// seam). Rotations as angular velocities (rad/s, parent space), translations in m/s.
struct SeamRates {
    std::vector<glm::vec3> rotation_start, rotation_end;
    std::vector<glm::vec3> translation_start, translation_end;
};

/// The most closing a seam whose ends are `pose_error` apart (m per joint) with their velocities `velocity_error`
/// apart (m/s, the part to match) moves a joint, per joint on the mean: half the pose difference (the value offset)
/// plus 4/27 of half the velocity difference times `window` (the peak of the velocity offset's Hermite cubic
/// s^3 - s^2). An upper bound: the two offsets do not peak together.
[[nodiscard]] float seam_bend(float pose_error, float velocity_error, float window = kSeamWindow);

/// What closing a seam changed: the largest offset it put on any key, so callers can say how much the loop was
/// bent to meet itself.
struct SeamClosing {
    float max_rotation = 0.0f;     ///< largest rotation offset on any joint's key (rad)
    float max_translation = 0.0f;  ///< largest translation offset on any joint's key (m)
};

/// Makes `loop` meet itself where it wraps. For every animated track with keys at both ends of the clip, the
/// difference between its first and last values, and the difference between its velocities at the two ends, is
/// halved: one half is faded in over the last `window` seconds, the other faded out over the first, each as a cubic
/// Hermite offset that is zero with zero slope where its window starts. Keys further than `window` from both ends
/// are unchanged; the first and last keys become equal. Rotations are offset on the left by a rotation vector, the
/// others added.
/// Velocities: with `rates` (the take's, for a loop cut from inside it) the difference of those is matched; without
/// (a take looped whole), only the part of the seam's velocity jump (last step to first, per track) beyond the largest
/// jump between steps inside the loop: a motion's own kinks (a knee at heel strike) are not smoothed away. Scales
/// are matched in value only.
/// The root's (track 0's) horizontal translation keeps its first-to-last travel (what the loop walks each cycle).
/// Requires tracks whose first key is at 0 and last at `loop.duration` (what cut_loop makes); tracks with fewer than
/// 3 keys, or not spanning the loop, are left as they are. `window` is clamped to half the loop.
SeamClosing close_loop_seam(RawAnimation& loop, const SeamRates* rates = nullptr, float window = kSeamWindow);

}  // namespace aloha
