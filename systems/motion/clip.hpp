// Runtime animation clip: RawAnimation tracks decoded onto one shared key timeline and stored
// keyframe-major, so sampling one time touches two contiguous key blocks. Plus the ClipLibrary
// (the animation cache's clip store) that owns decoded clips by id.
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <deque>
#include <vector>

namespace aloha {

/// An immutable, sampling-ready clip for one skeleton.
///
/// Layout: `key_count()` key blocks of `block_floats()` floats each. A block holds, for all joints,
/// translations as packed xyz (3n floats), rotations as four planes x[n] y[n] z[n] w[n] (4n floats,
/// structure-of-arrays so normalisation vectorises) and scales as packed xyz (3n floats).
/// Every track is re-evaluated on the union of all key times; rotation keys are hemisphere-aligned
/// (consecutive keys have a non-negative dot product) and inserted keys hold the un-normalised
/// chord value, so lerp + normalise between blocks reproduces the source track's nlerp exactly.
class AnimationClip {
public:
    AnimationClip() = default;

    /// Clip name (from the RawAnimation).
    [[nodiscard]] const std::string& name() const { return name_; }
    /// Joint count of the skeleton the clip was built for.
    [[nodiscard]] int joint_count() const { return joints_; }
    /// Number of key blocks (>= 1).
    [[nodiscard]] int key_count() const { return static_cast<int>(times_.size()); }
    /// Clip length in seconds (time of the last key; 0 for a single-key clip).
    [[nodiscard]] float duration() const { return duration_; }
    /// True when keys are evenly spaced, so the key of a time is found in O(1) without a cursor.
    [[nodiscard]] bool uniform() const { return uniform_; }
    /// Seconds between keys when uniform(); 0 otherwise.
    [[nodiscard]] float key_spacing() const { return spacing_; }
    /// 1 / key_spacing() when uniform(); 0 otherwise.
    [[nodiscard]] float inverse_key_spacing() const { return inv_spacing_; }
    /// Key times (seconds, strictly increasing, first is 0).
    [[nodiscard]] std::span<const float> times() const { return times_; }
    /// Floats per key block: 10 * joint_count().
    [[nodiscard]] size_t block_floats() const { return static_cast<size_t>(joints_) * 10u; }
    /// The key block of key `k` (requires 0 <= k < key_count()).
    [[nodiscard]] const float* block(int k) const { return keys_.data() + static_cast<size_t>(k) * block_floats(); }
    /// Root-joint (joint 0) model translation at the first and last key, for root-motion extraction.
    [[nodiscard]] glm::vec3 root_start() const { return root_start_; }
    [[nodiscard]] glm::vec3 root_end() const { return root_end_; }
    /// Horizontal (XZ) root speed averaged over the clip in m/s (0 for a still or 0-length clip).
    [[nodiscard]] float root_speed() const;
    /// Bytes of key data held.
    [[nodiscard]] size_t byte_size() const { return keys_.size() * sizeof(float) + times_.size() * sizeof(float); }

private:
    friend Result<AnimationClip> build_clip(const RawAnimation& raw, const Skeleton& skeleton);
    std::string name_;
    int joints_ = 0;
    float duration_ = 0.0f;
    bool uniform_ = false;
    float spacing_ = 0.0f;
    float inv_spacing_ = 0.0f;
    std::vector<float> times_;
    std::vector<float> keys_;
    glm::vec3 root_start_{0.0f};
    glm::vec3 root_end_{0.0f};
};

/// Validates `raw` against `skeleton` (at most joint_count() tracks, times finite, >= 0 and strictly
/// increasing, one value per time, finite values, non-zero quaternions) and decodes it. Joints with
/// no track (or an empty one) keep the skeleton's rest value. Errors name the clip (`raw.name`),
/// the joint and the track.
Result<AnimationClip> build_clip(const RawAnimation& raw, const Skeleton& skeleton);

/// Id of a clip in a ClipLibrary (MotionRequest::clip).
using ClipId = uint16_t;

/// Owns decoded clips by id: the clip store of the animation cache. Ids are dense, in insertion order.
class ClipLibrary {
public:
    /// Adds a built clip and returns its id. Requires fewer than 65535 clips.
    ClipId add(AnimationClip clip);
    /// Builds `raw` for `skeleton` and adds it; returns the id or the build error.
    Result<ClipId> add(const RawAnimation& raw, const Skeleton& skeleton);
    /// The clip with id `id`, or nullptr when there is none.
    [[nodiscard]] const AnimationClip* find(ClipId id) const;
    /// Id of the first clip named `name`, or -1.
    [[nodiscard]] int find(const std::string& name) const;
    /// Number of clips.
    [[nodiscard]] size_t size() const { return clips_.size(); }

private:
    std::deque<AnimationClip> clips_;  // deque: clip addresses stay valid as clips are added
};

}  // namespace aloha
