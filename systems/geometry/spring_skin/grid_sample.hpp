// Continuous (theta, phi) addressing of one surface_grid muscle/skin grid: the parameters of each
// grid vertex, bilinear sampling of positions/normals at any (theta, phi), and a local frame there.
// Used to carry points between tessellations (geomorphing) and to bind mesh vertices to muscles.
#pragma once

#include "systems/geometry/surface_grid.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <span>

namespace aloha {

/// (theta, phi) of a grid point: theta in [-pi, pi) around, phi in [-pi/2, pi/2] pole to pole.
struct GridParam {
    float theta = 0.0f;
    float phi = 0.0f;
};

/// Parameters of vertex `index` of a (T, P) grid (poles get theta = 0). Requires index < V(T, P).
GridParam grid_vertex_param(uint32_t theta_steps, uint32_t phi_steps, uint32_t index);

/// What bilinear sampling at one (theta, phi) of a (T, P) grid needs that depends only on the
/// parameter and (T, P): the four grid vertices around it and the two fractions. Computed once (at
/// bind time) so per-frame sampling is only gathers and arithmetic.
struct GridCell {
    /// Vertex indices within the grid: lower ring at columns t0, t0 + 1, upper ring at t0, t0 + 1
    /// (a pole ring repeats its pole vertex).
    uint32_t corner[4] = {};
    float ft = 0.0f;  ///< fraction from column t0 towards t0 + 1
    float fr = 0.0f;  ///< fraction from the lower ring towards the upper
};

/// The cell of (theta, phi) on a (T, P) grid: between the two rings around phi and the two columns
/// around theta (theta wraps; a pole ring is its single pole vertex). Requires T >= 3, P >= 2.
GridCell grid_cell(uint32_t theta_steps, uint32_t phi_steps, GridParam param);

/// Bilinear sample of one grid's per-vertex values in `cell` (of the grid's (T, P)).
inline glm::vec3 sample_grid(std::span<const glm::vec3> values, const GridCell& cell) {
    const glm::vec3 low = glm::mix(values[cell.corner[0]], values[cell.corner[1]], cell.ft);
    const glm::vec3 high = glm::mix(values[cell.corner[2]], values[cell.corner[3]], cell.ft);
    return glm::mix(low, high, cell.fr);
}

/// Bilinear sample of one grid's per-vertex values at (theta, phi): sample_grid() in grid_cell().
/// Requires values.size() == grid_vertex_count(T, P), T >= 3, P >= 2.
glm::vec3 sample_grid(std::span<const glm::vec3> values, uint32_t theta_steps, uint32_t phi_steps,
                      GridParam param);

/// A point on a grid with an orthonormal frame (tangent along +theta, bitangent, outward normal).
struct GridFrame {
    glm::vec3 point{0.0f};
    glm::vec3 tangent{1.0f, 0.0f, 0.0f};
    glm::vec3 bitangent{0.0f, 1.0f, 0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
};

/// The frame of sample_grid_frame() in `cell` (of the grid's (T, P)); inline for the per-frame skin.
inline GridFrame sample_grid_frame(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                   const GridCell& cell) {
    const glm::vec3 p00 = positions[cell.corner[0]], p01 = positions[cell.corner[1]];
    const glm::vec3 p10 = positions[cell.corner[2]], p11 = positions[cell.corner[3]];
    GridFrame frame;
    frame.point = glm::mix(glm::mix(p00, p01, cell.ft), glm::mix(p10, p11, cell.ft), cell.fr);
    const glm::vec3 n = sample_grid(normals, cell);
    const float nlen = glm::length(n);
    frame.normal = nlen > 1e-20f ? n / nlen : glm::vec3(0.0f, 0.0f, 1.0f);
    // Theta direction: difference of the two columns around theta, blended between the rings.
    glm::vec3 tangent = glm::mix(p01 - p00, p11 - p10, cell.fr);
    tangent -= glm::dot(tangent, frame.normal) * frame.normal;
    float tlen = glm::length(tangent);
    if (!(tlen > 1e-12f)) {  // degenerate (pole): any unit vector perpendicular to the normal
        const glm::vec3 axis = std::abs(frame.normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        tangent = axis - glm::dot(axis, frame.normal) * frame.normal;
        tlen = glm::length(tangent);
    }
    frame.tangent = tangent / tlen;
    frame.bitangent = glm::cross(frame.normal, frame.tangent);
    return frame;
}

/// Samples position and normal at (theta, phi) and builds a right-handed orthonormal frame whose
/// normal is the sampled normal and whose tangent follows the grid's theta direction (any
/// perpendicular when that direction degenerates, e.g. exactly at a pole).
/// Requires positions and normals of size grid_vertex_count(T, P).
GridFrame sample_grid_frame(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                            uint32_t theta_steps, uint32_t phi_steps, GridParam param);

}  // namespace aloha
