// Root motion of a played clip: the root joint's travel over the ground and its turn about the vertical, taken
// out of the pose and given to the character's transform, so a clip that walks, runs or turns moves the character
// (and, played over and over, carries on from where each repeat ended instead of going back to where it started).
//
// A clip's track holds, per key, the root's ground position (x, z) and its heading: the turn about +Y that takes
// the root's key-0 orientation to its orientation at the key, unwrapped so it grows past a half turn. F(t), the
// ground motion from key 0 to time t, maps the root's key-0 ground frame onto its frame at t:
//     F(t): p -> H(t) + R(heading(t)) (p - H(0))          (H: the root's (x, z); R: a turn about +Y)
// A pose is shown in place as F(t)^-1 applied to its root joints (their ground position back at H(0), their
// heading back to key 0's; height, lean and every other joint as the clip has them), and the transform moves by
// F(t0)^-1 F(t1) between clip times t0 and t1 (for a looping clip, F of n repeats and a part is F(D)^n F(part)),
// so transform x in-place pose is the clip's pose carried along: the same picture, continuous across repeats.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// A rigid motion of the ground plane about the vertical: p -> R(turn) p + (offset.x, p.y, offset.y), R(turn)
/// the rotation of `turn` radians about +Y (glm::angleAxis). Heights are kept.
struct GroundMotion {
    glm::vec2 offset{0.0f};  ///< (x, z) added after the turn, metres
    float turn = 0.0f;       ///< radians about +Y

    /// The motion applied to point `p` (its y unchanged).
    [[nodiscard]] glm::vec3 apply(const glm::vec3& p) const;
    /// The rotation of `turn` about +Y, as a quaternion.
    [[nodiscard]] glm::quat rotation() const;
    /// The inverse motion.
    [[nodiscard]] GroundMotion inverse() const;
    /// `*this` after `first`: p -> this(first(p)).
    [[nodiscard]] GroundMotion after(const GroundMotion& first) const;
    /// The motion repeated `n` times (n < 0: the inverse's); by squaring, so any n costs O(log |n|).
    [[nodiscard]] GroundMotion power(long long n) const;
};

/// Horizontal excursion of the root from its key-0 position (m) from which a clip's root motion is taken.
inline constexpr float kRootMotionMinTravel = 0.10f;
/// Net turn over a clip (rad, 30 degrees) from which a clip that stays in place still gives its turn to the transform.
inline constexpr float kRootMotionMinTurn = 0.5235988f;

/// A clip's root motion track (see the file comment). Empty (moves() false) for a clip whose root stays within
/// kRootMotionMinTravel of where it starts and turns less than kRootMotionMinTurn end to end: an idle's sway stays
/// in its pose.
class RootMotionTrack {
public:
    RootMotionTrack() = default;
    /// Builds the track of joint `joint` from its model translation and rotation at each key time (`times` strictly
    /// increasing from 0, one translation and rotation each, rotations unit). `inverse_spacing`: 1 / the key spacing
    /// when the keys are evenly spaced (AnimationClip::inverse_key_spacing()), at() then finds a key by a multiply;
    /// 0 otherwise. A key whose turn about the vertical cannot be read (a half turn about a horizontal axis from
    /// key 0) keeps the previous key's heading.
    static RootMotionTrack build(std::span<const float> times, std::span<const glm::vec3> root_translations,
                                 std::span<const glm::quat> root_rotations, int joint = 0, float inverse_spacing = 0.0f);

    /// Whether the clip's root travels or turns enough to be given to the transform (see the class comment).
    [[nodiscard]] bool moves() const { return moves_; }
    /// F(t) for a time inside the clip (clamped to [0, duration]); identity for a clip that does not move.
    [[nodiscard]] GroundMotion at(float t) const;
    /// F(t0)^-1 F(t1): how the transform moves when the clip clock goes from t0 to t1 (either way). Looping: the
    /// clock's repeats count (t may lie outside [0, duration]); once: both clamped to the clip.
    [[nodiscard]] GroundMotion between(float t0, float t1, bool loop) const;
    /// Largest horizontal distance of the root from its key-0 position (m).
    [[nodiscard]] float excursion() const { return excursion_; }
    /// Heading at the last key against key 0 (rad, unwrapped: a clip that turns round twice reads 4 pi).
    [[nodiscard]] float net_turn() const { return keys_.empty() ? 0.0f : keys_.back().z; }
    /// Ground distance from the root's first to its last position (m).
    [[nodiscard]] float net_travel() const;
    /// Length of the clip the track covers (s).
    [[nodiscard]] float duration() const { return times_.empty() ? 0.0f : times_.back(); }
    /// The joint whose travel and turn the track follows (build()'s `joint`).
    [[nodiscard]] int joint() const { return joint_; }

private:
    std::vector<float> times_;
    std::vector<glm::vec3> keys_;  // (x, z, unwrapped heading) per key
    float inverse_spacing_ = 0.0f;  // 1 / the key spacing when the keys are evenly spaced (at() finds a key in O(1)); else 0
    float excursion_ = 0.0f;
    bool moves_ = false;
    int joint_ = 0;
};

class AnimationClip;

/// Depth below joint 0 to which measure_root_motion() looks for the joint that travels.
inline constexpr int kRootMotionSearchDepth = 3;

/// The root motion track of `clip` (of a skeleton with `parents`), from its keys as sampling returns them: that of
/// joint 0 when it travels or turns enough to move (RootMotionTrack::moves()); where joint 0 stays put (an
/// Unreal-style root bone on the ground, the pelvis carrying the travel), that of the first joint below it along its
/// largest subtree, up to kRootMotionSearchDepth joints down, that does, in model space (the in-place pose is still
/// made at joint 0, which carries every joint below it); joint 0's (not moving) when none does.
[[nodiscard]] RootMotionTrack measure_root_motion(const AnimationClip& clip, std::span<const int16_t> parents);

/// Puts the root joints (`parents[j] < 0`) of a local pose in place: `in_place_from` (F(t)^-1 for the pose's clip
/// time t) applied to their translations (ground position) and rotations (heading).
void put_roots_in_place(const GroundMotion& in_place_from, std::span<const int16_t> parents, std::span<glm::vec3> translations,
                        std::span<glm::quat> rotations);

}  // namespace aloha
