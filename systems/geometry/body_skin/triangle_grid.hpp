// Exact closest-point queries on a triangle list: a uniform grid over the triangles' bounding boxes searched
// in growing shells of cells around the query, stopped once no unvisited cell can hold a closer point (exact up
// to the rounding of the coordinates: the same minimum as a search over every triangle). Load
// time work (surface maps between skin resolutions, the simplifier's distance bound) on meshes of any size:
// the cost of a query near the surface does not grow with the triangle count.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace aloha {

/// Closest point of triangle (a, b, c) to p as barycentric weights of a, b, c (Ericson 5.1.5). A degenerate
/// triangle (collinear or coincident corners) gives the closest point of its longest edge, so the weights are
/// always finite and sum to 1.
[[nodiscard]] glm::vec3 closest_barycentric(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c);

/// The grid. Keeps spans of the positions and indices it was built over: both must outlive it, unchanged.
class TriangleGrid {
public:
    /// Indexes `indices` (triangles over `positions`, all finite; every index < positions.size(), size a
    /// multiple of 3).
    /// Cell edge: the triangles' mean longest edge, widened where the grid would exceed ~16 cells a triangle.
    TriangleGrid(std::span<const glm::vec3> positions, std::span<const uint32_t> indices);

    /// A closest point: the triangle (kNone when there is none closer than the bound), its barycentric weights
    /// and its squared distance.
    struct Hit {
        static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
        uint32_t triangle = kNone;
        glm::vec3 bary{1.0f, 0.0f, 0.0f};
        float distance_sq = std::numeric_limits<float>::infinity();
    };

    /// The closest point of the triangles to p, among those strictly closer than sqrt(bound_sq) (a distance
    /// already known elsewhere lets the search stop sooner). Ties go to the first triangle met in the search,
    /// which is deterministic. Requires a finite p. Thread-safe (const, no scratch).
    [[nodiscard]] Hit closest(glm::vec3 p, float bound_sq = std::numeric_limits<float>::infinity()) const;

    /// The number of triangles indexed.
    [[nodiscard]] size_t triangle_count() const { return indices_.size() / 3; }

private:
    [[nodiscard]] glm::ivec3 cell_of(glm::vec3 p) const;
    [[nodiscard]] size_t cell_index(glm::ivec3 c) const;
    // Squared distance from p to every cell outside the box [lo, hi] (cell coordinates), or infinity when the
    // box covers the whole grid.
    [[nodiscard]] float outside_box_distance_sq(glm::vec3 p, glm::ivec3 lo, glm::ivec3 hi) const;

    std::span<const glm::vec3> positions_;
    std::span<const uint32_t> indices_;
    glm::vec3 origin_{0.0f};
    float cell_ = 1.0f;
    float face_slack_ = 0.0f;  // how far before a cell face a point binned behind it may sit (rounding)
    glm::ivec3 dims_{1, 1, 1};
    std::vector<uint32_t> first_;      // per cell: its triangles are triangles_[first_[c], first_[c + 1])
    std::vector<uint32_t> triangles_;  // triangle numbers, by cell
    std::vector<glm::vec3> box_lo_, box_hi_;  // per triangle: its bounding box (a cheap test before the exact one)
};

}  // namespace aloha
