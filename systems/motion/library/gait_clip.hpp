// Generated gait clips: a walk or run cycle for any speed, built from the gait relations
// (gait_model.hpp) on a humanoid skeleton. Stance feet are held still by construction: the foot
// rolls over its heel, lies flat, then rolls over the ball of the foot, and the legs reach those
// placements by analytic IK while the root travels at exactly the clip's speed.
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/skeleton.hpp"
#include "systems/motion/library/gait_model.hpp"
#include "systems/motion/library/pose_builder.hpp"
#include "systems/motion/walk_rig.hpp"

#include <string>

namespace aloha {

/// Where a foot touches the ground, relative to its ankle in rest model axes (ground at y = 0).
struct FootContacts {
    glm::vec3 heel{0.0f};  ///< heel contact point (on the ground) minus the ankle
    glm::vec3 ball{0.0f};  ///< pivot of the forefoot roll (the toe joint) minus the ankle
};

/// Contact points of each foot of `rig` (heel behind the ankle on the ground, the toe joint or a
/// ground point a fraction of the leg ahead when the rig has no toe).
[[nodiscard]] FootContacts foot_contacts(const WalkRig& rig, const PoseBuilder& rest, int side);

/// Key rate of generated clips (keys per second).
inline constexpr float kGeneratedKeyRate = 60.0f;

/// A gait clip and the cycle it was built from.
struct GaitClip {
    RawAnimation clip;  ///< one cycle, keys evenly spaced; root travels stride along +Z
    GaitCycle cycle;
};

/// Builds one gait cycle at `speed` m/s for `skeleton` (its leg rig `rig`, ground at y = 0 with the
/// ankles rig.ankle_height above it). Phase 0 is the left heel strike. The root's horizontal travel
/// is exactly speed * time; the pose at the last key equals the first shifted by one stride, so the
/// clip loops with no seam once that travel is taken out. Joints missing from `joints` keep their
/// rest pose.
[[nodiscard]] GaitClip make_gait_clip(const Skeleton& skeleton, const WalkRig& rig, const HumanoidJoints& joints,
                                      float speed, const std::string& name);

}  // namespace aloha
