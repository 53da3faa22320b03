// Plain data for the motion controller: animation requests and per-character motion state.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>

namespace aloha {

/// Kinds of animation request (the paper's "requests" registered with the motion controller).
enum class RequestKind : uint8_t { Rest = 0, PlayClip = 1, Walk = 2, Reach = 3, LookAt = 4 };

/// One animation request. Which fields matter depends on `kind`.
struct MotionRequest {
    RequestKind kind = RequestKind::Rest;
    uint8_t loop = 1;              ///< PlayClip: loop (1, with the clip's seam closed where it has a looped version) or once (0)
    uint16_t clip = 0;             ///< PlayClip: clip id in the motion library
    float speed = 1.0f;            ///< PlayClip: playback rate; Walk: m/s
    float start_time = 0.0f;       ///< PlayClip: seconds into the clip
    float duration = -1.0f;        ///< seconds before the next queued request starts (-1 = until done/forever)
    float crossfade_s = 0.2f;      ///< blend time from the previous request
    uint16_t path = 0xFFFF;        ///< Walk: path id (0xFFFF = straight along `target` as a direction)
    int16_t effector = -1;         ///< Reach/LookAt: end-effector joint index
    glm::vec3 target{0.0f};        ///< Reach/LookAt target (world), Walk direction when no path
    glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f}; ///< Reach: wanted effector orientation
    uint8_t use_orientation = 0;   ///< Reach: 1 when `orientation` is part of the error (eq. 11)
    /// PlayClip: 1 (default) gives a clip whose root travels or turns (systems/motion/root_motion.hpp) to the
    /// character's transform, its pose shown in place, so it moves on and repeats from where it got to; 0 leaves the
    /// travel in the pose (the transform stays, and a looping clip goes back to its start at each repeat).
    uint8_t root_motion = 1;
};

/// Per-character motion state vector that persists across frames.
struct MotionState {
    RequestKind active = RequestKind::Rest;
    uint8_t at_rest = 1;           ///< 1 = no motion work this frame (the paper's rest state)
    uint16_t frames_since_update = 0;
    float time = 0.0f;             ///< animation time of the active request (advances even when throttled)
    float phase = 0.0f;            ///< walk cycle phase in [0,1)
    float request_time = 0.0f;     ///< seconds since the active request started
    uint32_t pose_slot = 0;        ///< slot in the pose pool
    uint32_t path_cursor = 0;      ///< next waypoint index when walking a path
    /// 1 while a played clip's root motion carries the character at kTravellingSpeed or more: `phase` is then the walk
    /// phase its stride at that speed gives (what its impostor shows; a standing impostor would glide).
    uint8_t travelling = 0;
};

/// Speed (m/s) from which a played clip's root motion counts as travelling (MotionState::travelling).
inline constexpr float kTravellingSpeed = 0.2f;

}  // namespace aloha
