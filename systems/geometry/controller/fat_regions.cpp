// Per-region fat-spring tuning (see fat_regions.hpp).
#include "systems/geometry/controller/fat_regions.hpp"

#include <algorithm>
#include <cassert>

namespace aloha {

static_assert(kMaxFatRegions + 1 <= kMaxSpringTunings, "every region and the controller's tuning fit one spring job");

std::vector<uint8_t> vertex_fat_regions(std::span<const BlendBinding> bindings, const MuscleSet& muscles) {
    if (std::all_of(muscles.fat_region.begin(), muscles.fat_region.end(), [](uint8_t r) { return r == 0; })) return {};
    std::vector<uint8_t> out(bindings.size(), 0);
    for (size_t i = 0; i < bindings.size(); ++i) {
        const BlendBinding& b = bindings[i];
        int best = 0;
        for (int k = 1; k < kBlendInfluences; ++k)
            if (b.weight[k] > b.weight[best]) best = k;
        if (b.weight[best] > 0.0f && b.muscle[best] < muscles.fat_region.size()) out[i] = muscles.fat_region[b.muscle[best]];
    }
    return out;
}

size_t region_spring_params(const FatSpringParams& base, std::span<const FatRegion> regions, std::span<FatSpringParams> out) {
    assert(out.size() >= regions.size() + 1);
    out[0] = base;
    for (size_t k = 0; k < regions.size(); ++k) {
        FatSpringParams p = base;
        const FatRegion& r = regions[k];
        p.normal_hz = r.normal_hz.value_or(p.normal_hz);
        p.normal_damping = r.normal_damping.value_or(p.normal_damping);
        p.lateral_hz = r.lateral_hz.value_or(p.lateral_hz);
        p.max_strain = r.max_strain.value_or(p.max_strain);
        out[k + 1] = p;
    }
    return regions.size() + 1;
}

}  // namespace aloha
