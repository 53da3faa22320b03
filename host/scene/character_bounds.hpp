// Bounds radii that hold every pose a character takes: the frustum test and the occlusion estimate use
// a vertical cylinder (Bounds: height, radius) around the character's feet, so a radius measured on the
// rest pose alone lets a swinging foot, a reaching hand or the skin beyond the joints leave it and pop
// in a frame late at the screen's edge. The extent of a type is measured once at load: per joint, how
// far the skin lies from it, and per clip, how far its poses reach; a character's radius is that of the
// clips it plays, widened by what the IK chain of each of its reaches and look-ats can sweep.
#pragma once

#include "engine/anim/skeleton.hpp"

#include <glm/glm.hpp>

#include <span>
#include <vector>

namespace aloha {

class ClipLibrary;

/// How far a type's poses and skin reach from the character's vertical axis.
struct TypeExtent {
    std::vector<float> skin;       ///< per joint: largest rest distance to a skin point nearest to it (m)
    std::vector<float> tip;        ///< per joint: largest rest distance to one of its descendants plus
                                   ///< that one's skin (m): what hangs beyond it (a hand's fingers)
    std::vector<float> bone;       ///< per joint: rest length of the bone from its parent (0 for a root)
    std::vector<float> rest_joint; ///< per joint: horizontal distance from the root joint's vertical line at rest
    float rest_radius = 0.0f;      ///< the rest pose's radius: max over joints of horizontal distance + skin
    std::vector<float> clip_radius;///< per clip id: the same, largest over the clip's keys (a clip whose root moves, as
                                   ///< played with root motion: in place, root_motion.hpp)
    std::vector<float> clip_travel_radius;  ///< per clip id: the same with the root's travel left in the pose (root motion off)
};

/// Measures `skeleton` with its rest-pose skin `skin` (positions in the frame of `skin_joints`, the
/// joints' model matrices in that pose; empty: every joint's skin is `fallback_skin`) and every clip
/// of `clips` (nullptr: none), each pose taken about its own root joint (joint 0), so clips with root
/// travel keep their in-place shape.
[[nodiscard]] TypeExtent measure_type_extent(const Skeleton& skeleton, const ClipLibrary* clips,
                                             std::span<const glm::vec3> skin, std::span<const glm::mat4> skin_joints,
                                             float fallback_skin);

/// Radius that holds the IK chain from `base` to `effector` (an ancestor of it, or itself) pointed
/// anywhere from where the base is at rest: the base's distance from the axis plus the chain's length
/// and what hangs beyond the effector. Requires valid joint indices.
[[nodiscard]] float chain_reach_radius(const TypeExtent& extent, const Skeleton& skeleton, int base, int effector);

}  // namespace aloha
