// Skin mesh: index buffer and area-weighted normals of the grid-layout skin.
#include "systems/geometry/spring_skin/skin_mesh.hpp"

#include "systems/geometry/surface_grid.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {
namespace {

// Adds the area-weighted normal of triangle (a, b, c) to its three vertices.
inline void add_triangle(std::span<const glm::vec3> p, std::span<glm::vec3> n, uint32_t a, uint32_t b, uint32_t c) {
    const glm::vec3 fn = glm::cross(p[b] - p[a], p[c] - p[a]);
    n[a] += fn;
    n[b] += fn;
    n[c] += fn;
}

}  // namespace

std::vector<uint32_t> build_skin_indices(uint32_t theta_steps, uint32_t phi_steps, uint32_t muscle_count) {
    std::vector<uint32_t> indices;
    indices.reserve(static_cast<size_t>(muscle_count) * 3 * grid_triangle_count(theta_steps, phi_steps));
    const uint32_t V = grid_vertex_count(theta_steps, phi_steps);
    for (uint32_t m = 0; m < muscle_count; ++m) append_grid_triangles(theta_steps, phi_steps, m * V, indices);
    return indices;
}

bool SkinJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string message) {
        ok = false;
        if (errors) errors->push_back("SkinJob: " + std::move(message));
    };
    if (theta_steps < 3) fail("theta_steps must be >= 3");
    if (phi_steps < 2) fail("phi_steps must be >= 2");
    if (theta_steps >= 3 && phi_steps >= 2 && positions.size() % grid_vertex_count(theta_steps, phi_steps) != 0)
        fail("positions size is not a multiple of the grid vertex count");
    if (normals.size() != positions.size()) fail("normals size differs from positions");
    if (!fallback_normals.empty() && fallback_normals.size() != positions.size())
        fail("fallback_normals must be empty or the size of positions");
    return ok;
}

void SkinJob::Run() const {
    assert(Validate());
    const uint32_t T = theta_steps, P = phi_steps, V = grid_vertex_count(T, P);
    const size_t grids = positions.size() / V;
    std::fill(normals.begin(), normals.end(), glm::vec3(0.0f));
    for (size_t g = 0; g < grids; ++g) {
        const auto p = positions.subspan(g * V, V);
        const auto n = normals.subspan(g * V, V);
        const uint32_t south = 0, north = V - 1;
        // Same triangles, same winding as append_grid_triangles.
        for (uint32_t t = 0; t < T; ++t) add_triangle(p, n, south, grid_ring_vertex(T, 1, t + 1), grid_ring_vertex(T, 1, t));
        for (uint32_t r = 1; r + 1 < P; ++r) {
            for (uint32_t t = 0; t < T; ++t) {
                const uint32_t a = grid_ring_vertex(T, r, t), b = grid_ring_vertex(T, r, t + 1);
                const uint32_t c = grid_ring_vertex(T, r + 1, t + 1), d = grid_ring_vertex(T, r + 1, t);
                add_triangle(p, n, a, b, c);
                add_triangle(p, n, a, c, d);
            }
        }
        for (uint32_t t = 0; t < T; ++t) add_triangle(p, n, north, grid_ring_vertex(T, P - 1, t), grid_ring_vertex(T, P - 1, t + 1));
        for (uint32_t i = 0; i < V; ++i) {
            const float len2 = glm::dot(n[i], n[i]);
            if (len2 > 1e-30f) {
                n[i] *= 1.0f / std::sqrt(len2);
            } else {
                n[i] = fallback_normals.empty() ? glm::vec3(0.0f, 0.0f, 1.0f) : fallback_normals[g * V + i];
            }
        }
    }
}

void accumulate_vertex_normals(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                               std::span<glm::vec3> normals) {
    assert(indices.size() % 3 == 0 && normals.size() == positions.size());
    std::fill(normals.begin(), normals.end(), glm::vec3(0.0f));
    for (size_t i = 0; i + 2 < indices.size(); i += 3) add_triangle(positions, normals, indices[i], indices[i + 1], indices[i + 2]);
    for (glm::vec3& n : normals) {
        const float len2 = glm::dot(n, n);
        n = len2 > 1e-30f ? n / std::sqrt(len2) : glm::vec3(0.0f, 0.0f, 1.0f);
    }
}

}  // namespace aloha
