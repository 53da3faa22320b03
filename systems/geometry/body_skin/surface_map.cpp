// Surface-to-surface correspondence by closest points (see surface_map.hpp).
#include "systems/geometry/body_skin/surface_map.hpp"

#include <cassert>

namespace aloha {

void SurfaceMap::apply(std::span<const glm::vec3> source, std::span<glm::vec3> out) const {
    assert(out.size() == corners.size());
    for (size_t i = 0; i < corners.size(); ++i)
        out[i] = bary[i].x * source[corners[i].x] + bary[i].y * source[corners[i].y] + bary[i].z * source[corners[i].z];
}

SurfaceMap map_surface(std::span<const glm::vec3> source_positions, std::span<const uint32_t> source_indices,
                       std::span<const glm::vec3> target_positions) {
    assert(source_indices.size() >= 3);
    const TriangleGrid grid(source_positions, source_indices);
    SurfaceMap map;
    map.corners.resize(target_positions.size());
    map.bary.resize(target_positions.size());
    for (size_t i = 0; i < target_positions.size(); ++i) {
        const TriangleGrid::Hit hit = grid.closest(target_positions[i]);
        assert(hit.triangle != TriangleGrid::Hit::kNone);  // only a non-finite target finds nothing
        const size_t f = hit.triangle == TriangleGrid::Hit::kNone ? 0 : hit.triangle;
        map.corners[i] = glm::uvec3(source_indices[3 * f], source_indices[3 * f + 1], source_indices[3 * f + 2]);
        map.bary[i] = hit.bary;
    }
    return map;
}

}  // namespace aloha
