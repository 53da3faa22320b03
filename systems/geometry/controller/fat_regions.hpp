// Per-region fat-spring tuning for the geometric controller: which region each skin vertex's springs
// follow (the region of the muscle it hangs on most), and the tuning of every region for one frame.
#pragma once

#include "systems/geometry/body_skin/blend_binding.hpp"
#include "systems/geometry/muscle/muscle_set.hpp"
#include "systems/geometry/spring_skin/fat_spring.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Per skin vertex: the fat region (MuscleSet::fat_region: 0 = the controller's tuning, k = region
/// k - 1) of its heaviest muscle influence. Empty when no muscle names a region (every vertex 0).
[[nodiscard]] std::vector<uint8_t> vertex_fat_regions(std::span<const BlendBinding> bindings, const MuscleSet& muscles);

/// The tuning of every region for one frame: out[0] = `base`, out[k] = `base` with region k - 1's
/// given values. Returns the number written (1 + regions.size(); `out` holds kMaxSpringTunings).
size_t region_spring_params(const FatSpringParams& base, std::span<const FatRegion> regions, std::span<FatSpringParams> out);

}  // namespace aloha
