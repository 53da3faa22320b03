// meshoptimizer's simplifier and vertex-cache order for a lighter skinned level (see simplified_indices.hpp).
#include "systems/geometry/controller/simplified_indices.hpp"

#include <meshoptimizer.h>

#include <cassert>

namespace aloha {

SimplifiedIndices simplify_indices(std::span<const glm::vec3> positions, std::span<const uint32_t> indices, float target_error) {
    assert(target_error > 0.0f && indices.size() % 3 == 0);
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "positions are read as tight float triples");
    SimplifiedIndices out;
    if (indices.empty() || positions.empty()) return out;
    const auto* xyz = reinterpret_cast<const float*>(positions.data());
    out.extent = meshopt_simplifyScale(xyz, positions.size(), sizeof(glm::vec3));
    std::vector<uint32_t> simplified(indices.size());
    // Target 0 triangles: the error bound alone decides where the collapses stop.
    const size_t n = meshopt_simplify(simplified.data(), indices.data(), indices.size(), xyz, positions.size(), sizeof(glm::vec3),
                                      /*target_index_count=*/0, target_error, /*options=*/0, &out.relative_error);
    simplified.resize(n);
    out.indices.resize(n);
    meshopt_optimizeVertexCache(out.indices.data(), simplified.data(), n, positions.size());
    return out;
}

}  // namespace aloha
