// Test helper: the volume a tessellated muscle's (T, P) grid encloses, by the divergence theorem.
#pragma once

#include "systems/geometry/surface_grid.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha::test {

/// Volume enclosed by shape `shape`'s (T, P) grid within `surface` (outward triangles; the sum of the
/// signed tetrahedra from the origin).
inline double grid_volume(std::span<const glm::vec3> surface, uint32_t T, uint32_t P, size_t shape) {
    std::vector<uint32_t> tri;
    append_grid_triangles(T, P, static_cast<uint32_t>(shape * grid_vertex_count(T, P)), tri);
    double v = 0.0;
    for (size_t i = 0; i < tri.size(); i += 3) {
        const glm::dvec3 a(surface[tri[i]]), b(surface[tri[i + 1]]), c(surface[tri[i + 2]]);
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return v;
}

}  // namespace aloha::test
