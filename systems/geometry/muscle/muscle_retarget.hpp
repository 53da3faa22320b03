// Muscle layouts written for the canonical humanoid (anchors on canonical joint names, offsets in
// the built-in humanoid's model-aligned joint frames) carried over to any skeleton the humanoid map
// maps: each anchor point is placed on the target's bone as it lies on the reference's (the same
// fraction along the bone, the offset turned with the bone) and re-expressed in the target joint's
// frame. Anchors on canonical joints the target lacks go to the nearest mapped canonical ancestor.
#pragma once

#include "engine/anim/humanoid_fit.hpp"
#include "engine/anim/humanoid_map.hpp"
#include "engine/anim/skeleton.hpp"
#include "systems/geometry/muscle/muscle_set.hpp"

#include <span>
#include <vector>

namespace aloha {

/// Rewrites `defs` for `target`: anchors on canonical joints become anchors on target joints with
/// along = 0 and the offset computed from `fit`; depth axes are turned likewise. Anchors on other
/// names are left as written (joints of the target itself). Requires map.humanoid and `fit` from
/// fit_canonical(target, map, ...) with the reference the layout was written for, scaled to the
/// target's height (scale_muscle_defs).
[[nodiscard]] std::vector<MuscleDef> retarget_muscle_defs(std::span<const MuscleDef> defs, const Skeleton& target,
                                                          const HumanoidMap& map, const CanonicalFit& fit);

}  // namespace aloha
