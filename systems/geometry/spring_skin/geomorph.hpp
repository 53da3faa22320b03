// Geomorphing between tessellations: when a character's (T, P) changes, its new skin starts on the
// old surface and slides onto the new one over N frames, so the switch is not a visible pop.
//
// At the switch, every new vertex i gets its (theta, phi) on the new grid, the old surface is
// sampled there (bilinear on the old grid) and the offset delta_i = old(theta, phi) - new_i is
// stored. Frame k = 1..N then shows new_k + (1 - k / N) * delta_i. Offsets (not frozen positions)
// keep the surface's own motion: the per-frame move of a vertex is at most
// |new_k - new_{k-1}| + |delta_i| / N (triangle inequality), and the first morphed frame moves
// |delta_i| / N away from the old surface. Normals: run SkinJob on the morphed positions.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Starts a morph for a run of grids (characters x muscles): computes the per-vertex offsets from
/// the new surface to the old surface sampled at the same (theta, phi). Pass the last old surface
/// (e.g. the previous frame's skin) and this frame's new surface.
struct GeomorphBeginJob {
    uint32_t old_theta_steps = 8;              ///< T of the old grids (>= 3)
    uint32_t old_phi_steps = 6;                ///< P of the old grids (>= 2)
    uint32_t new_theta_steps = 8;              ///< T' of the new grids (>= 3)
    uint32_t new_phi_steps = 6;                ///< P' of the new grids (>= 2)
    std::span<const glm::vec3> old_positions;  ///< grids x V(T, P)
    std::span<const glm::vec3> new_positions;  ///< same number of grids x V(T', P')
    std::span<glm::vec3> deltas;               ///< output, same size as new_positions

    /// Checks tessellations and that both surfaces hold the same number of grids.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Writes deltas. Requires Validate().
    void Run() const;
};

/// Applies running morphs to a run of characters with `vertices_per_character` skin vertices each.
/// A character with frames_left > 0 advances one frame (frames_left decrements) and shows
/// new + (frames_left / frames_total) * delta; others pass through unchanged.
struct GeomorphJob {
    uint32_t vertices_per_character = 0;             ///< skin vertices per character (> 0)
    std::span<const glm::vec3> positions;            ///< new-level skin, characters x vertices
    std::span<const glm::vec3> deltas;               ///< offsets from GeomorphBeginJob, same size
    std::span<const uint16_t> frames_total;          ///< N per character (> 0 where morphing)
    std::span<uint16_t> frames_left;                 ///< per character, in/out (set to N at the switch)
    std::span<glm::vec3> morphed;                    ///< output, same size as positions

    /// Checks sizes and that frames_left <= frames_total.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Advances every morph by one frame. Requires Validate().
    void Run() const;
};

}  // namespace aloha
