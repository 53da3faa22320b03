// Inertialization (after Bollo, "Inertialization: High-Performance Animation Transitions in Gears of
// War", GDC 2018): when a character's animation changes level (walk method, IK solver or iterations,
// update interval), the pose it showed last is kept as an offset from the new pose, and the offset
// decays to nothing over the transition time. Nothing but the new pose is evaluated during the
// transition (a cross-fade would evaluate the old method as well, which at a level change is the
// very cost being shed, and a dynamic walk cannot be stepped twice).
//
// The offset decays along 1 - smootherstep(t / T) (10t^3 - 15t^4 + 6t^5), whose slope and curvature
// vanish at both ends: the first frame shows the pose of the frame before, then the body moves with
// the new pose's velocity while the offset melts away, and the last frames join the new pose
// without a kink. The offset's own initial velocity is taken as zero (the old pose's velocity is not
// kept per character): the velocity seen at the switch is the new method's, which at a level change
// tracks the same gait phase, so the velocity step is the small difference between two renderings
// of one walk.
#pragma once

#include "engine/anim/pose.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Weight of the offset `elapsed` seconds into a transition of `total` seconds: 1 at 0, 0 from
/// `total` on, smooth (C2) in between. Requires total > 0.
[[nodiscard]] float inertial_weight(float elapsed, float total);

/// Per-joint local offsets (rotation, translation, scale) of the characters in transition, in slots
/// handed out and taken back serially; a slot is written only by its own character.
class InertialOffsets {
public:
    /// Offsets of `joint_count` joints.
    explicit InertialOffsets(int joint_count) : joints_(static_cast<size_t>(joint_count)) {}
    /// A free slot (grows storage; not during parallel evaluation).
    uint32_t acquire();
    /// Returns `slot` to the free list.
    void release(uint32_t slot);
    /// Keeps in `slot` the pose whose model matrices are `shown` (the pose displayed last, in any
    /// state: interpolated, blended, solved), as local transforms. `parents` is the skeleton's parent
    /// table. Call before the new pose overwrites `shown`; then relate().
    void hold(uint32_t slot, const int16_t* parents, std::span<const glm::mat4> shown);
    /// Turns the pose held in `slot` into its offset from the local pose `target` (the new pose).
    void relate(uint32_t slot, const ConstPoseView& target);
    /// Takes the root's travel out of the offset in `slot` (after relate()): its translation over the ground (X, Z)
    /// and its turn about the vertical. A looping clip played in place returns to where it started at each wrap;
    /// only the rest of the pose's jump there is faded.
    void keep_root_travel(uint32_t slot);
    /// Adds `weight` times the slot's offset to the local pose `pose` (translations, rotations,
    /// scales; model matrices untouched). weight 1 gives the captured shown pose, 0 leaves `pose`.
    void apply(uint32_t slot, float weight, const PoseView& pose) const;
    /// Slots in use.
    [[nodiscard]] size_t in_use() const { return used_; }

private:
    struct Offset {  // after hold(): the shown local pose; after relate(): the offset
        glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // shown * inverse(target), w >= 0 (shorter arc)
        glm::vec3 translation{0.0f};                 // shown - target
        glm::vec3 scale{0.0f};                       // shown - target
    };
    size_t joints_;
    std::vector<Offset> offsets_;  // slot s: [s * joints, (s + 1) * joints)
    std::vector<uint32_t> free_;
    size_t used_ = 0;
};

}  // namespace aloha
