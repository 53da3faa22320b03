// Skin layer: the mesh of the outer fat-spring ends, in the surface_grid layout (one grid per
// muscle, same (T, P) as the muscles), with per-vertex normals.
//
// Normals are area-weighted face normals accumulated per vertex (the cross product of each
// triangle's edges, whose length is twice its area), because the skin is displaced from the
// muscle by the springs and its own shape is what gets lit. Where the accumulated normal
// degenerates (zero-area neighbourhood, e.g. zero thickness on a collapsed grid) the muscle normal
// is used instead when one is given.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Triangle index buffer of `muscle_count` concatenated grids at (T, P) (append_grid_triangles per
/// muscle). Requires T >= 3, P >= 2.
std::vector<uint32_t> build_skin_indices(uint32_t theta_steps, uint32_t phi_steps, uint32_t muscle_count);

/// Computes skin normals for a contiguous run of skin grids (any number of characters sharing T, P).
struct SkinJob {
    uint32_t theta_steps = 8;                        ///< grid steps around (T >= 3)
    uint32_t phi_steps = 6;                          ///< grid steps pole to pole (P >= 2)
    std::span<const glm::vec3> positions;            ///< skin vertices (spring ends), grids x V(T, P)
    std::span<const glm::vec3> fallback_normals;     ///< muscle normals (same size) or empty
    std::span<glm::vec3> normals;                    ///< output unit normals, same size as positions

    /// Checks sizes; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Writes the normals. Requires Validate().
    void Run() const;
};

/// Area-weighted vertex normals of an indexed triangle list (any topology): accumulates each
/// triangle's unnormalised cross product on its three vertices, then normalises; zero-area
/// neighbourhoods get (0, 0, 1). Requires indices.size() % 3 == 0, indices < positions.size(),
/// normals.size() == positions.size().
void accumulate_vertex_normals(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                               std::span<glm::vec3> normals);

}  // namespace aloha
