// Runtime animation clip: RawAnimation tracks decoded onto one shared key timeline and stored
// keyframe-major, so sampling one time touches two contiguous key blocks. Keys are 16-bit
// range-quantised by default (systems/motion/clip_quant.hpp: format and error bound), or floats.
// Plus the ClipLibrary (the animation cache's clip store) that owns decoded clips by id.
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"
#include "systems/motion/root_motion.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// How build_clip stores key values.
enum class ClipEncoding : uint8_t {
    Quantized16,  ///< default: one uint16 per value, range-quantised per channel; error <= error_bound()
    Float32,      ///< lossless floats: exact at keys, float lerp/nlerp between them (2x the key bytes)
};

/// Worst-case difference between what sampling a clip returns and the float source's lerp / nlerp
/// at the same time (clip_quant.hpp derives it). A Float32 clip's bound is float rounding only.
struct ClipErrorBound {
    float translation = 0.0f;  ///< per component, model units (metres)
    float rotation = 0.0f;     ///< angle between sampled and source rotation, radians
    float scale = 0.0f;        ///< per component
};

/// The joints a key block stores for one part of the pose (translations, rotations or scales):
/// joints [first, first + count). The others are constant over the clip and stored once.
struct ClipSection {
    int first = 0;        ///< first stored joint
    int count = 0;        ///< stored joints (0: the whole part is constant)
    size_t offset = 0;    ///< element offset of the section inside a key block
};

/// An immutable, sampling-ready clip for one skeleton.
///
/// Layout: `key_count()` key blocks of `block_elements()` values (uint16 or float) each. A block
/// holds the translation section (packed xyz, 3 values per stored joint), the rotation section (four
/// planes x[c] y[c] z[c] w[c] for the c stored joints, so normalisation vectorises) and the scale
/// section (packed xyz). Joints outside a section's range are constant and kept once.
/// Every track is re-evaluated on the union of all key times; rotation keys are hemisphere-aligned
/// (consecutive keys have a non-negative dot product) and inserted keys hold the un-normalised
/// chord value, so lerp + normalise between blocks reproduces the source track's nlerp (exactly for
/// Float32, within error_bound() for Quantized16).
class AnimationClip {
public:
    /// Section indices for section().
    enum Part : int { kTranslations = 0, kRotations = 1, kScales = 2 };

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
    /// How key values are stored.
    [[nodiscard]] ClipEncoding encoding() const { return encoding_; }
    /// Values (uint16 or float) per key block.
    [[nodiscard]] size_t block_elements() const { return block_; }
    /// Which joints a key block stores for `part` (kTranslations, kRotations or kScales).
    [[nodiscard]] const ClipSection& section(Part part) const { return sections_[static_cast<size_t>(part)]; }
    /// Worst-case sampling error against the float source (see ClipErrorBound).
    [[nodiscard]] const ClipErrorBound& error_bound() const { return bound_; }
    /// Root-joint (joint 0) model translation at the first and last key (as sampling returns them),
    /// for root-motion extraction.
    [[nodiscard]] glm::vec3 root_start() const { return root_start_; }
    [[nodiscard]] glm::vec3 root_end() const { return root_end_; }
    /// True when the last key's pose is the first's, every joint within kEndsMeetAngle and kEndsMeetDistance (the
    /// root's travel over the ground and its turn about the vertical aside: a clip played in place returns there
    /// anyway): played over and over, it repeats without a jump. A single-key clip's ends meet.
    [[nodiscard]] bool ends_meet() const { return ends_meet_; }
    /// Horizontal (XZ) root speed averaged over the clip in m/s (0 for a still or 0-length clip).
    [[nodiscard]] float root_speed() const;
    /// The root joint's travel and turn over the clip, key by key (root_motion.hpp): what a PlayClip request gives
    /// its character's transform when the clip moves (RootMotionTrack::moves()).
    [[nodiscard]] const RootMotionTrack& root_motion() const { return root_motion_; }
    /// Bytes of clip data held: key blocks, key times, per-channel ranges and constant values.
    [[nodiscard]] size_t byte_size() const;

private:
    friend Result<AnimationClip> build_clip(const RawAnimation& raw, const Skeleton& skeleton, ClipEncoding encoding);
    friend void sample_blocks(const AnimationClip& clip, int k, float alpha, glm::vec3* translations,
                              glm::quat* rotations, glm::vec3* scales);
    friend struct ClipEncoder;

    std::string name_;
    int joints_ = 0;
    float duration_ = 0.0f;
    bool uniform_ = false;
    float spacing_ = 0.0f;
    float inv_spacing_ = 0.0f;
    ClipEncoding encoding_ = ClipEncoding::Quantized16;
    size_t block_ = 0;
    std::array<ClipSection, 3> sections_{};
    std::vector<float> times_;
    std::vector<uint16_t> qkeys_;         // Quantized16 key blocks
    std::vector<float> fkeys_;            // Float32 key blocks
    std::vector<float> base_;             // Quantized16: per block element, value of code 0
    std::vector<float> step_;             // Quantized16: per block element, value of one code step
    std::vector<glm::vec3> const_t_;      // every joint's key-0 value when a section leaves joints out
    std::vector<glm::quat> const_r_;
    std::vector<glm::vec3> const_s_;
    ClipErrorBound bound_;
    bool ends_meet_ = true;
    glm::vec3 root_start_{0.0f};
    glm::vec3 root_end_{0.0f};
    RootMotionTrack root_motion_;
};

/// Validates `raw` against `skeleton` (at most joint_count() tracks, times finite, >= 0 and strictly
/// increasing, one value per time, finite values, non-zero quaternions) and decodes it into
/// `encoding` (Quantized16 unless asked). Joints with no track (or an empty one) keep the skeleton's
/// rest value. Errors name the clip (`raw.name`), the joint and the track.
Result<AnimationClip> build_clip(const RawAnimation& raw, const Skeleton& skeleton,
                                 ClipEncoding encoding = ClipEncoding::Quantized16);

/// How far apart a clip's ends may be and still meet (AnimationClip::ends_meet): a joint's turn of 1e-3 rad moves
/// what hangs a metre beyond it by a millimetre, the distance allowed a joint's own translation; scales alike.
inline constexpr float kEndsMeetAngle = 1e-3f;
inline constexpr float kEndsMeetDistance = 1e-3f;

/// A rotation without its turn about the vertical (+Y): the swing of its swing-twist decomposition about Y.
[[nodiscard]] glm::quat without_turn_about_vertical(const glm::quat& q);

/// Id of a clip in a ClipLibrary (MotionRequest::clip).
using ClipId = uint16_t;

/// Owns decoded clips by id: the clip store of the animation cache. Ids are dense, in insertion order.
class ClipLibrary {
public:
    /// Adds a built clip and returns its id. Requires fewer than 65535 clips.
    ClipId add(AnimationClip clip);
    /// Builds `raw` for `skeleton` (default encoding) and adds it; returns the id or the build error.
    Result<ClipId> add(const RawAnimation& raw, const Skeleton& skeleton);
    /// Gives clip `id` the version played when it repeats (a looping PlayClip): `looped`, the clip with its seam
    /// closed (library/loop_seam.hpp). A load-time edit, before anything samples it. Requires id < size() and a
    /// `looped` of the clip's joints and duration.
    void set_looped(ClipId id, AnimationClip looped);
    /// The clip with id `id`, or nullptr when there is none.
    [[nodiscard]] const AnimationClip* find(ClipId id) const;
    /// The clip to sample when `id` is played over and over: its looped version when it has one (set_looped), else
    /// the clip itself; nullptr when there is no clip `id`.
    [[nodiscard]] const AnimationClip* find_looped(ClipId id) const;
    /// Whether clip `id` has a looped version of its own.
    [[nodiscard]] bool has_looped(ClipId id) const { return id < looped_.size() && looped_[id].has_value(); }
    /// Id of the first clip named `name`, or -1.
    [[nodiscard]] int find(const std::string& name) const;
    /// Number of clips.
    [[nodiscard]] size_t size() const { return clips_.size(); }
    /// Bytes held by all clips and their looped versions (sum of byte_size()).
    [[nodiscard]] size_t byte_size() const;

private:
    std::deque<AnimationClip> clips_;                 // deque: clip addresses stay valid as clips are added
    std::deque<std::optional<AnimationClip>> looped_;  // per clip: its looped version, when it has one
};

}  // namespace aloha
