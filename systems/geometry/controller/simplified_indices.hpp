// A lighter triangle list over the same vertices: meshoptimizer's edge-collapse simplifier within a
// geometric error bound, for a skinned level drawn small on screen (GeomLod::simplify_error).
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Result of simplify_indices: the new triangle list and the error meshoptimizer reports for it.
struct SimplifiedIndices {
    std::vector<uint32_t> indices;  ///< triangles over the input's vertices (a subset of them is used)
    float relative_error = 0.0f;    ///< meshopt's reported error, relative to the mesh's extent (see below)
    float extent = 0.0f;            ///< meshopt_simplifyScale: the largest side of the positions' bounding box
};

/// Simplifies the triangle list `indices` over `positions` (the rest surface) as far as it can while
/// meshoptimizer's error stays within `target_error` times the bounding box's largest side (for a standing
/// character about its height, so a character h pixels tall moves by at most about target_error * h
/// pixels); the result is ordered for the post-transform vertex cache. Requires target_error > 0 and a
/// triangle list (indices.size() % 3 == 0) whose every index is < positions.size(). No new vertices; a
/// closed surface stays closed, though a thin part may collapse into a few non-manifold edges (meshoptimizer
/// does not promise a manifold result) and the error bound holds one way only (docs/RULES.md, simplify_error).
[[nodiscard]] SimplifiedIndices simplify_indices(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                                 float target_error);

}  // namespace aloha
