// A lighter triangle list over the same vertices: meshoptimizer's edge-collapse simplifier, held within a
// two-sided distance of the full surface, for a skinned level drawn small on screen (GeomLod::simplify_error).
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Result of simplify_indices: the new triangle list and how far it lies from the full one.
struct SimplifiedIndices {
    std::vector<uint32_t> indices;  ///< triangles over the input's vertices (a subset of them is used)
    float extent = 0.0f;            ///< meshopt_simplifyScale: the largest side of the positions' bounding box
    float distance = 0.0f;          ///< two-sided distance between the new surface and the full one (absolute,
                                    ///< the positions' units; surface_distance.hpp's samples), <= the bound
};

/// Simplifies the triangle list `indices` over `positions` (the rest surface) so that the two surfaces lie
/// within `target_error` times the bounding box's largest side of each other, both ways (for a standing
/// character about its height, so on a character h pixels tall the silhouette moves by at most about
/// target_error * h pixels). meshoptimizer bounds a quadric error, which holds one way only: a vertex collapsed
/// along its planes' extensions (a thin tip, a ridge) can take a hand's tip several times the bound away. So
/// each round measures both ways; where the full surface is too far from the new one, the vertices responsible
/// are kept with their triangles (left out of the simplifier's input, their ring locked as its border), and
/// where the new surface is too far from the full one the simplifier's own error is lowered; the rounds stop
/// when the bound holds (at worst the full list). The result is ordered for the post-transform vertex cache.
/// Requires target_error > 0 and a triangle list (indices.size() % 3 == 0) whose every index is <
/// positions.size(). No new vertices; a closed surface stays closed, though a thin part may collapse into a
/// few non-manifold edges (meshoptimizer does not promise a manifold result).
[[nodiscard]] SimplifiedIndices simplify_indices(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                                 float target_error);

}  // namespace aloha
