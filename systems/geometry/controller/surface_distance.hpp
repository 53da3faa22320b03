// Distances between two triangle lists over the same vertices: how far a lighter list (simplified_indices.hpp)
// strays from the full one, each way, measured at sample points of the triangles.
#pragma once

#include "systems/geometry/body_skin/triangle_grid.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Distance from p to the triangle (a, b, c): to closest_barycentric's point (Ericson, Real-Time Collision
/// Detection, 5.1.5). Degenerate triangles are allowed (the distance to the segment or point they collapse to).
[[nodiscard]] float point_triangle_distance(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c);

/// The seven sample points of a triangle the distances below are measured at: its corners, its edges'
/// midpoints and its centroid.
inline constexpr int kTriangleSamples = 7;

/// One triangle list seen from another: for each triangle of `from`, how far its samples lie from the
/// surface `to` (both over `positions`). Requires triangle lists whose every index is < positions.size().
class SurfaceDistance {
public:
    /// Indexes `to` (which triangles touch each vertex, and a TriangleGrid) for the queries below.
    SurfaceDistance(std::span<const glm::vec3> positions, std::span<const uint32_t> to);

    /// Distance from p to the surface, looking first at the triangles that touch `near_vertices` (the
    /// vertices p was sampled between): exact, the grid's search bounded by the best of those.
    [[nodiscard]] float distance(glm::vec3 p, std::span<const uint32_t> near_vertices) const;

    /// The largest distance from the samples of `from` to the surface, and for each triangle of `from`
    /// (one entry per three indices) its samples' largest distance.
    struct Result {
        float largest = 0.0f;
        std::vector<float> per_triangle;
    };
    [[nodiscard]] Result from(std::span<const uint32_t> from) const;

private:
    std::span<const glm::vec3> positions_;
    std::span<const uint32_t> to_;
    std::vector<uint32_t> first_;      // per vertex: its triangles are touching_[first_[v], first_[v + 1])
    std::vector<uint32_t> touching_;   // triangle numbers of `to`
    TriangleGrid grid_;                // over `to`
};

}  // namespace aloha
