// Continuous (theta, phi) addressing of one surface_grid muscle/skin grid: the parameters of each
// grid vertex, bilinear sampling of positions/normals at any (theta, phi), and a local frame there.
// Used to carry points between tessellations (geomorphing) and to bind mesh vertices to muscles.
#pragma once

#include "systems/geometry/surface_grid.hpp"

#include <glm/glm.hpp>

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

/// Bilinear sample of one grid's per-vertex values at (theta, phi): between the two rings around
/// phi and the two columns around theta (theta wraps; a pole ring is its single pole vertex).
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

/// Samples position and normal at (theta, phi) and builds a right-handed orthonormal frame whose
/// normal is the sampled normal and whose tangent follows the grid's theta direction (any
/// perpendicular when that direction degenerates, e.g. exactly at a pole).
/// Requires positions and normals of size grid_vertex_count(T, P).
GridFrame sample_grid_frame(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                            uint32_t theta_steps, uint32_t phi_steps, GridParam param);

}  // namespace aloha
