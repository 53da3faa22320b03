// Motion retargeting: a clip of one humanoid skeleton played by another, through the canonical humanoid
// joints both map (engine/anim/humanoid_map.hpp). Both skeletons are expected normalised as every file rig is at
// load (engine/assets/rig_normalise.hpp: +Y up, facing +Z, metres), but their rest poses may differ (a T-pose
// against an A-pose, bent knees, another spine count), and so may their proportions.
//
// Per key of the source clip, in model space:
// - every canonical joint mapped in both skeletons takes the source joint's rotation away from its rest,
//   applied after the rest alignment of its bone: T_g = S_g S_rest^-1 A T_rest, where S_g is the source
//   joint's model rotation, S_rest and T_rest the two joints' model rest rotations and A the shortest arc
//   turning the target's rest bone (the joint towards its canonical child) onto the source's. So each target
//   bone points where the source bone points, whatever the two rest poses; twist about the bone follows the
//   source. Joints without a canonical child (Hips, Head, hands) take A = identity.
// - joints between mapped ones, and canonical joints the source lacks, keep their rest rotation relative to
//   their parent; the mapped joint below them still gets its model rotation from the source.
// - the pelvis (canonical Hips) travels as the source's does, scaled by k, the ratio of the two rest hip heights
//   above the lowest rest joint of the body (the canonical joints: a root on the ground, an Armature node or IK
//   helpers do not count), the legs' length ratio, so a stride stays a stride of the target's legs. Heights are
//   measured from the ground each stands on: the target's lowest rest body joint, and the lowest any source body
//   joint comes over the clip (a file's rest pose need not stand where its motion does). So the target's pelvis is at
//   (k x, ground_t + k (y - ground_s), k z) for the source's at (x, y, z).
// - each ankle follows the source's ankle path scaled the same way, its height measured from its own rest
//   height (a foot flat on the ground stays flat on the target's): thigh and knee reach it by analytic two-bone
//   IK, the knee bending to the side the rotations bent it, and the foot keeps the orientation the rotations
//   give it. Where a leg cannot reach its path (shorter legs for the hip height than the source's, a straighter
//   stance), the pelvis is lowered at that key until both reach (RetargetReport::pelvis_drop). So a foot the
//   source plants is planted on the target (it moves k times as far as the source's: no skate the source does
//   not have); RetargetReport::foot_reach_error says how far an ankle stayed from its path where lowering could
//   not help (a path point farther sideways from the hip than the leg is long).
// - a root joint above the target's pelvis (Unreal's `root` on the ground) carries the pelvis's horizontal travel,
//   as such rigs' own clips do, so root motion (joint 0) follows the body; the pelvis keeps the rest.
// - other joints keep the target's rest translations (bone lengths are the target's).
// The result is a RawAnimation on the target skeleton with a key at every source key time.
#pragma once

#include "engine/anim/humanoid_map.hpp"
#include "engine/anim/raw_animation.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"

#include <string>
#include <vector>

namespace aloha {

/// One skeleton with its canonical humanoid map (HumanoidMap::humanoid must be true).
struct RetargetRig {
    const Skeleton* skeleton = nullptr;
    const HumanoidMap* map = nullptr;
};

/// What retarget_clip did besides the clip: for notes.
struct RetargetReport {
    float scale = 1.0f;                   ///< target / source rest hip height: the pelvis travel's scale
    std::vector<std::string> kept_at_rest;  ///< canonical joints the target has and the source lacks
    std::vector<std::string> not_aligned;   ///< canonical joints whose rest bone is too short in either rig to align (A = identity)
    float foot_reach_error = 0.0f;          ///< the farthest an ankle stayed from its path, m (0: the legs reached every key)
    float pelvis_drop = 0.0f;               ///< the most the pelvis was lowered below its scaled path for the legs to reach, m
};

/// Height of the rig's rest hips (canonical Hips) above its lowest rest body joint (the canonical joints), m: the
/// leg length retarget_clip scales the pelvis travel by. Requires a mapped humanoid (map->humanoid).
[[nodiscard]] float rest_hip_height(const RetargetRig& rig);

/// `clip` (on `source.skeleton`) retargeted onto `target.skeleton`, named `name`. Errors: a rig that is not
/// a mapped humanoid, a clip that does not build on the source skeleton (build_clip's errors, naming the clip),
/// a rest hip height of zero.
[[nodiscard]] Result<RawAnimation> retarget_clip(const RawAnimation& clip, const RetargetRig& source, const RetargetRig& target,
                                                 const std::string& name, RetargetReport* report = nullptr);

}  // namespace aloha
