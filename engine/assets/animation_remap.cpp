#include "engine/assets/animation_remap.hpp"

#include <cassert>

namespace aloha {

RawAnimation remap_to_runtime(const RawAnimation& raw_order, const Skeleton& skeleton) {
    assert(raw_order.tracks.size() == static_cast<size_t>(skeleton.joint_count()));
    RawAnimation out;
    out.name = raw_order.name;
    out.duration = raw_order.duration;
    out.start_offset = raw_order.start_offset;
    const std::span<const int> source = skeleton.source_index();
    out.tracks.resize(source.size());
    for (size_t r = 0; r < source.size(); ++r) out.tracks[r] = raw_order.tracks[static_cast<size_t>(source[r])];
    return out;
}

std::vector<int> runtime_index_of_raw(const Skeleton& skeleton) {
    const std::span<const int> source = skeleton.source_index();
    std::vector<int> out(source.size(), -1);
    for (size_t r = 0; r < source.size(); ++r) out[static_cast<size_t>(source[r])] = static_cast<int>(r);
    return out;
}

}  // namespace aloha
