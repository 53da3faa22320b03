// Reordering loader clips between raw joint order (file order) and runtime joint order.
//
// Convention used by every ALOHA loader: RawAnimation::tracks is indexed by RUNTIME joint, i.e.
// tracks[r] animates Skeleton joint r of build_skeleton(data.skeleton). The loaders build their
// tracks in raw order and call remap_to_runtime() before returning, so callers do nothing.
// Use these helpers only for clips you assemble yourself in raw (RawSkeleton::joints) order.
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/skeleton.hpp"

#include <vector>

namespace aloha {

/// Returns a copy of `raw_order` whose tracks[r] is raw_order.tracks[skeleton.source_index()[r]].
/// Requires raw_order.tracks.size() == skeleton.joint_count().
[[nodiscard]] RawAnimation remap_to_runtime(const RawAnimation& raw_order, const Skeleton& skeleton);

/// For each raw joint index, its runtime index in `skeleton` (the inverse of source_index()).
[[nodiscard]] std::vector<int> runtime_index_of_raw(const Skeleton& skeleton);

}  // namespace aloha
