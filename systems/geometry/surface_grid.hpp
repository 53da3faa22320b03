// The shared vertex layout of one tessellated super-ellipsoid (muscle surface, fat spring roots,
// skin shell). One parameter pair (theta_steps T, phi_steps P) sets every count:
//   vertex 0            : south pole (phi = -pi/2)
//   vertices 1 + (r-1)*T + t : ring r in [1, P-1] (phi = -pi/2 + r*pi/P), t in [0, T) (theta = -pi + t*2pi/T)
//   last vertex         : north pole (phi = +pi/2)
// Faces: T triangles at each pole, T*(P-2) quads between rings (theta wraps around).
#pragma once

#include <cassert>
#include <cstdint>
#include <vector>

namespace aloha {

/// Vertices of one muscle grid at (theta_steps, phi_steps). Requires T >= 3 and P >= 2.
constexpr uint32_t grid_vertex_count(uint32_t theta_steps, uint32_t phi_steps) {
    return theta_steps * (phi_steps - 1) + 2;
}

/// Index of ring vertex (ring r in [1, P-1], column t in [0, T)).
constexpr uint32_t grid_ring_vertex(uint32_t theta_steps, uint32_t ring, uint32_t t) {
    return 1 + (ring - 1) * theta_steps + (t % theta_steps);
}

/// Triangles of one muscle grid (quads split in two), counter-clockwise seen from outside.
constexpr uint32_t grid_triangle_count(uint32_t theta_steps, uint32_t phi_steps) {
    return 2 * theta_steps + 2 * theta_steps * (phi_steps - 2);
}

/// Face list for subdivision: per face its vertex count (3 or 4) and the vertex indices.
struct GridFaces {
    std::vector<int> vertex_counts;
    std::vector<int> vertex_indices;
};

/// Builds the triangle index list of one grid, offset by `base` (for concatenating muscles).
inline void append_grid_triangles(uint32_t theta_steps, uint32_t phi_steps, uint32_t base,
                                  std::vector<uint32_t>& out) {
    assert(theta_steps >= 3 && phi_steps >= 2);
    const uint32_t T = theta_steps, P = phi_steps;
    const uint32_t south = base, north = base + grid_vertex_count(T, P) - 1;
    for (uint32_t t = 0; t < T; ++t) {  // south cap
        out.insert(out.end(), {south, base + grid_ring_vertex(T, 1, t + 1), base + grid_ring_vertex(T, 1, t)});
    }
    for (uint32_t r = 1; r + 1 < P; ++r) {
        for (uint32_t t = 0; t < T; ++t) {
            const uint32_t a = base + grid_ring_vertex(T, r, t), b = base + grid_ring_vertex(T, r, t + 1);
            const uint32_t c = base + grid_ring_vertex(T, r + 1, t + 1), d = base + grid_ring_vertex(T, r + 1, t);
            out.insert(out.end(), {a, b, c, a, c, d});
        }
    }
    for (uint32_t t = 0; t < T; ++t) {  // north cap
        out.insert(out.end(), {north, base + grid_ring_vertex(T, P - 1, t), base + grid_ring_vertex(T, P - 1, t + 1)});
    }
}

/// Builds the quad/triangle face list of one grid (for OpenSubdiv), offset by `base`.
inline void append_grid_faces(uint32_t theta_steps, uint32_t phi_steps, int base, GridFaces& out) {
    assert(theta_steps >= 3 && phi_steps >= 2);
    const uint32_t T = theta_steps, P = phi_steps;
    const int south = base, north = base + static_cast<int>(grid_vertex_count(T, P)) - 1;
    auto ring = [&](uint32_t r, uint32_t t) { return base + static_cast<int>(grid_ring_vertex(T, r, t)); };
    for (uint32_t t = 0; t < T; ++t) {
        out.vertex_counts.push_back(3);
        out.vertex_indices.insert(out.vertex_indices.end(), {south, ring(1, t + 1), ring(1, t)});
    }
    for (uint32_t r = 1; r + 1 < P; ++r) {
        for (uint32_t t = 0; t < T; ++t) {
            out.vertex_counts.push_back(4);
            out.vertex_indices.insert(out.vertex_indices.end(), {ring(r, t), ring(r, t + 1), ring(r + 1, t + 1), ring(r + 1, t)});
        }
    }
    for (uint32_t t = 0; t < T; ++t) {
        out.vertex_counts.push_back(3);
        out.vertex_indices.insert(out.vertex_indices.end(), {north, ring(P - 1, t), ring(P - 1, t + 1)});
    }
}

}  // namespace aloha
