// Correspondence between two triangle surfaces of the same shape (two resolutions of one skin): every
// vertex of the target is located on the source as a triangle and barycentric weights, so a quantity
// on the source (its current, deformed positions) can be read at the target's vertices. Used to
// geomorph between levels whose skins differ and to compare a level with a reference level.
#pragma once

#include "systems/geometry/body_skin/triangle_grid.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Target vertex i = sum_k bary[i][k] * source[corners[i][k]].
struct SurfaceMap {
    std::vector<glm::uvec3> corners;  ///< source vertex indices per target vertex
    std::vector<glm::vec3> bary;      ///< barycentric weights (sum 1)

    /// Evaluates the map on `source` values (one per source vertex) into `out` (one per target vertex).
    void apply(std::span<const glm::vec3> source, std::span<glm::vec3> out) const;
};

/// Maps every target vertex onto the source surface at its closest point (exact: TriangleGrid; ties to the
/// first triangle the search meets). Requires a non-empty source triangle list.
[[nodiscard]] SurfaceMap map_surface(std::span<const glm::vec3> source_positions, std::span<const uint32_t> source_indices,
                                     std::span<const glm::vec3> target_positions);

}  // namespace aloha
