// Clip sampling: the per-character SamplingCache (key cursor, last time) and the SampleJob that
// writes one character's local pose at a time. Sampling is a lerp of two contiguous key blocks
// followed by a quaternion normalisation (nlerp): linear between keys, and at keys exact for Float32
// clips and within AnimationClip::error_bound() for the default 16-bit quantised ones.
#pragma once

#include "engine/anim/pose.hpp"
#include "systems/motion/clip.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace aloha {

/// Per-character sampling state that lives across frames (part of the animation cache). For
/// non-uniform clips the cursor makes steady forward playback O(1): the next key is found by
/// stepping forward from the last one, never by searching from the start.
struct SamplingCache {
    const AnimationClip* clip = nullptr;  ///< clip the cursor belongs to (a different clip resets it)
    int cursor = 0;                       ///< key k with times[k] <= last_time < times[k+1]
    float last_time = 0.0f;               ///< last sampled time (seconds into the clip)
    uint32_t restarts = 0;                ///< times the cursor was searched for from the clip start
    uint32_t steps = 0;                   ///< single forward cursor steps taken

    /// Forgets the cursor (next sample of any clip starts from key 0).
    void reset() { clip = nullptr; cursor = 0; last_time = 0.0f; }
};

/// Maps an unbounded playback time to a time inside [0, duration]: wraps when `loop`, clamps otherwise.
[[nodiscard]] float wrap_clip_time(float time, float duration, bool loop);

/// Finds the key segment of `time` (already inside [0, duration]) in `clip`: returns k and the
/// fraction `alpha` in [0,1] between key k and k+1 (k+1 == k for a single-key clip). Uses O(1)
/// arithmetic for uniform clips, else the cache cursor (`cache` may be null: then binary search).
void find_key(const AnimationClip& clip, float time, SamplingCache* cache, int* k, float* alpha);

/// Writes the lerp of key blocks k and k+1 at `alpha` into a local pose (translations, rotations
/// normalised, scales), dequantising 16-bit keys on the fly (clip_quant.hpp); joints a clip keeps
/// constant are copied. Requires the outputs to have clip.joint_count() elements and 0 <= k < key_count().
void sample_blocks(const AnimationClip& clip, int k, float alpha, glm::vec3* translations, glm::quat* rotations,
                   glm::vec3* scales);

/// Samples one clip at one time into one character's local pose.
struct SampleJob {
    const AnimationClip* clip = nullptr;   ///< required
    float time = 0.0f;                     ///< seconds into the clip; wrapped when loop, else clamped
    bool loop = true;                      ///< wrap (true) or clamp (false) `time` to the clip
    SamplingCache* cache = nullptr;        ///< optional: cursor for non-uniform clips
    std::span<glm::vec3> translations;     ///< output, clip->joint_count() elements
    std::span<glm::quat> rotations;        ///< output, clip->joint_count() elements
    std::span<glm::vec3> scales;           ///< output, clip->joint_count() elements

    /// True when the job can run; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Samples. Requires Validate().
    void Run() const;
};

}  // namespace aloha
