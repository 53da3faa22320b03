// Foot lock: keeps a planted foot still in the world over whatever the pose beneath does between
// updates. Interpolating between the keys of a throttled update, or decaying the offset of an
// inertialized level change, moves a foot that plants between two keys (or that the two levels place
// differently) while it is on the ground. The lock runs last, on the model matrices shown this frame:
// per foot, while its sole is low (heel or toe within FootLockParams::contact_height of the lowest the
// foot has been) it accumulates an offset that cancels the horizontal motion of its contact point (the
// lower of heel and toe: the heel at touchdown, the toe once the heel rolls off), and the leg is re-solved in model space by
// the analytic two-bone IK so the ankle lands on the held spot (the foot keeps its orientation). When
// both points lift off (or the offset passes the leg's reach margin) the offset decays to nothing in
// the air, so the foot rejoins the pose without a step. Everything is in seconds and metres scaled by
// the character: any frame rate, any rig the walk rig covers (WalkRig from the humanoid map).
#pragma once

#include "components/transform.hpp"
#include "engine/anim/skeleton.hpp"
#include "systems/motion/walk_rig.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Contact detection and release of the foot lock (world metres and seconds, before character scale).
struct FootLockParams {
    float contact_height = 0.015f;  ///< a heel or toe this close to the lowest it has been is on the ground
    float engage_speed = 0.5f;      ///< a low point moving slower than this (m/s, horizontal) gets locked
    float release_speed = 1.5f;     ///< a held foot whose pose moves faster than this (m/s) is swinging: let go
    float release_time = 0.05f;     ///< time constant (s) of the offset's decay once the foot lifts off
    float max_offset = 0.15f;       ///< largest offset, in leg lengths: a held foot reaching it is let go there
    float ground_rise = 0.02f;      ///< m/s the remembered lowest height rises (adapts to a new clip)
    float ground_floor = 0.02f;     ///< the remembered lowest height stays at most this far below the rest sole (m)
};

/// Per-character foot lock state (structure of arrays, two feet per character) and the leg re-solve.
/// A character's entries are touched only by apply()/reset() for that character, so different
/// characters may be processed concurrently.
class FootLock {
public:
    /// Lock for `capacity` characters of `skeleton` whose legs are `rig`.
    FootLock(const Skeleton& skeleton, const WalkRig& rig, size_t capacity, FootLockParams params = {});

    /// Holds the planted feet of character `c`, whose final model matrices for this frame are `model`
    /// (edited in place), placed by `placement`, `dt` seconds after its previous apply(). With `engage`
    /// false no foot is newly locked (offsets held so far decay): for poses that are not a walk.
    void apply(uint32_t c, float dt, const Transform& placement, std::span<glm::mat4> model, bool engage = true);
    /// Character `c`'s shown pose (with the lock's corrections) becomes the pose beneath: offsets go to 0
    /// and the feet stay held where they are. For an inertialized level change, whose offset carries the
    /// shown pose (corrections included) into the new level: applied on top again, they would count twice.
    void rebase(uint32_t c);
    /// Forgets character `c` (its next apply() starts afresh, nothing held).
    void reset(uint32_t c);
    /// True while foot `side` (0 left, 1 right) of character `c` is held.
    [[nodiscard]] bool locked(uint32_t c, int side) const { return locked_[2 * c + static_cast<size_t>(side)] != 0; }
    /// World offset (horizontal, m) applied to foot `side` of character `c` at its last apply().
    [[nodiscard]] glm::vec3 offset(uint32_t c, int side) const { return offset_[2 * c + static_cast<size_t>(side)]; }
    /// The parameters in force.
    [[nodiscard]] const FootLockParams& params() const { return params_; }

private:
    // Joints moved with each part of one leg: thigh (hip and below, above the knee), shin (knee and
    // below, above the ankle), foot (ankle and below).
    struct Leg {
        std::vector<int> thigh, shin, foot;
    };
    void move_leg(int side, const glm::vec3& target, std::span<glm::mat4> model) const;

    WalkRig rig_;
    FootLockParams params_;
    std::array<Leg, 2> legs_;
    std::array<glm::vec3, 2> heel_sole_{}, toe_sole_{};  // sole points in the ankle's and toe's frames
    std::array<glm::vec3, 2> roll_heel_{};               // the heel rolled over at touchdown, ankle frame
    std::array<float, 2> rest_heel_{}, rest_toe_{};      // their rest model heights
    // Per foot (index 2c + side).
    std::vector<glm::vec3> offset_;     // world, horizontal
    std::vector<glm::vec3> prev_heel_;  // unlocked world heel sole point at the last apply
    std::vector<glm::vec3> prev_toe_;   // unlocked world toe sole point at the last apply
    std::vector<glm::vec3> prev_roll_;  // unlocked world rolling heel at the last apply
    std::vector<float> low_heel_, low_toe_;  // lowest model heights seen (rising slowly)
    std::vector<uint8_t> locked_;
    std::vector<uint8_t> primed_;       // per character: prev_* hold last frame's points
};

}  // namespace aloha
