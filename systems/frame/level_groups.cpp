#include "systems/frame/level_groups.hpp"

#include <algorithm>
#include <cassert>
#include <numeric>

namespace aloha {

void group_keys(std::span<const CharacterRef> refs, std::span<const GeomLod> geom, std::vector<uint32_t>& keys) {
    assert(refs.size() == geom.size());
    keys.resize(refs.size());
    for (size_t e = 0; e < refs.size(); ++e) keys[e] = level_group_key(refs[e].type, geom[e].level);
}

void group_by_level(std::span<const CharacterRef> refs, std::span<const GeomLod> geom, CharacterGroups& out) {
    group_keys(refs, geom, out.keys);
    const size_t n = out.keys.size();
    out.order.resize(n);
    std::iota(out.order.begin(), out.order.end(), 0u);
    out.in_place_ = std::is_sorted(out.keys.begin(), out.keys.end());
    if (!out.in_place_)
        std::stable_sort(out.order.begin(), out.order.end(),
                         [&](uint32_t a, uint32_t b) { return out.keys[a] < out.keys[b]; });
    out.ids.resize(n);
    out.ranges.clear();
    for (size_t p = 0; p < n; ++p) {
        const uint32_t e = out.order[p];
        out.ids[p] = refs[e].id;
        const uint32_t key = out.keys[e];
        if (out.ranges.empty() || level_group_key(out.ranges.back().type, out.ranges.back().level) != key)
            out.ranges.push_back({refs[e].type, geom[e].level, static_cast<uint32_t>(p), static_cast<uint32_t>(p)});
        out.ranges.back().end = static_cast<uint32_t>(p + 1);
    }
}

}  // namespace aloha
