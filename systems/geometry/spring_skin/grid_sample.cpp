// Bilinear (theta, phi) sampling of surface_grid grids.
#include "systems/geometry/spring_skin/grid_sample.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace aloha {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Index of grid vertex at ring r in [0, P] (0 = south pole, P = north pole) and column t (wraps).
uint32_t vertex_at(uint32_t T, uint32_t P, uint32_t r, uint32_t t) {
    if (r == 0) return 0;
    if (r >= P) return grid_vertex_count(T, P) - 1;
    return grid_ring_vertex(T, r, t % T);
}

// Continuous ring coordinate in [0, P] and column coordinate in [0, T) of a parameter.
void continuous_coords(uint32_t T, uint32_t P, GridParam param, float& rf, float& tf) {
    rf = std::clamp((param.phi + 0.5f * kPi) * static_cast<float>(P) / kPi, 0.0f, static_cast<float>(P));
    tf = (param.theta + kPi) * static_cast<float>(T) / (2.0f * kPi);
    tf = tf - std::floor(tf / static_cast<float>(T)) * static_cast<float>(T);
    if (!(tf < static_cast<float>(T))) tf = 0.0f;  // rounding up to T wraps to column 0
}

}  // namespace

GridParam grid_vertex_param(uint32_t theta_steps, uint32_t phi_steps, uint32_t index) {
    const uint32_t V = grid_vertex_count(theta_steps, phi_steps);
    assert(index < V);
    if (index == 0) return {0.0f, -0.5f * kPi};
    if (index == V - 1) return {0.0f, 0.5f * kPi};
    const uint32_t ring = 1 + (index - 1) / theta_steps, t = (index - 1) % theta_steps;
    return {-kPi + static_cast<float>(t) * 2.0f * kPi / static_cast<float>(theta_steps),
            -0.5f * kPi + static_cast<float>(ring) * kPi / static_cast<float>(phi_steps)};
}

GridCell grid_cell(uint32_t theta_steps, uint32_t phi_steps, GridParam param) {
    const uint32_t T = theta_steps, P = phi_steps;
    float rf = 0.0f, tf = 0.0f;
    continuous_coords(T, P, param, rf, tf);
    const uint32_t r0 = std::min(static_cast<uint32_t>(rf), P - 1);
    const uint32_t t0 = std::min(static_cast<uint32_t>(tf), T - 1);
    GridCell cell;
    cell.corner[0] = vertex_at(T, P, r0, t0);
    cell.corner[1] = vertex_at(T, P, r0, t0 + 1);
    cell.corner[2] = vertex_at(T, P, r0 + 1, t0);
    cell.corner[3] = vertex_at(T, P, r0 + 1, t0 + 1);
    cell.ft = tf - static_cast<float>(t0);
    cell.fr = rf - static_cast<float>(r0);
    return cell;
}

glm::vec3 sample_grid(std::span<const glm::vec3> values, uint32_t theta_steps, uint32_t phi_steps,
                      GridParam param) {
    assert(values.size() == grid_vertex_count(theta_steps, phi_steps));
    return sample_grid(values, grid_cell(theta_steps, phi_steps, param));
}

GridFrame sample_grid_frame(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                            uint32_t theta_steps, uint32_t phi_steps, GridParam param) {
    return sample_grid_frame(positions, normals, grid_cell(theta_steps, phi_steps, param));
}

}  // namespace aloha
