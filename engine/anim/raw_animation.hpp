// Loader output for an animation clip: per-joint keyframe tracks as read from BVH or glTF.
// The motion system builds its optimised runtime clip from this.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <string>
#include <vector>

namespace aloha {

/// A keyframe track: times in seconds (strictly increasing, relative to clip start) and values.
template <class T>
struct RawTrack {
    std::vector<float> times;
    std::vector<T> values;
};

/// Tracks for one joint; an empty track means "use the skeleton's rest value".
struct RawJointTracks {
    RawTrack<glm::vec3> translations;
    RawTrack<glm::quat> rotations;
    RawTrack<glm::vec3> scales;
};

/// A clip for a skeleton: `tracks[i]` animates runtime joint i of that skeleton.
/// Key times are shifted so the clip starts at 0 (glTF clips whose first key is later than 0
/// are shifted at load and `start_offset` keeps the original first key time).
struct RawAnimation {
    std::string name;
    float duration = 0.0f;       ///< seconds, last key time
    float start_offset = 0.0f;   ///< original time of the first key in the file
    std::vector<RawJointTracks> tracks;
};

}  // namespace aloha
