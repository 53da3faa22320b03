// meshoptimizer's simplifier held to a two-sided bound, and vertex-cache order, for a lighter skinned level
// (see simplified_indices.hpp).
#include "systems/geometry/controller/simplified_indices.hpp"

#include "systems/geometry/controller/surface_distance.hpp"

#include <meshoptimizer.h>

#include <cassert>

namespace aloha {
namespace {

// meshopt_simplify over the triangles of `indices` that touch no protected vertex, with the border they leave
// (the protected vertices' rings) locked; the protected triangles are appended unchanged.
std::vector<uint32_t> simplify_around(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                      const std::vector<bool>& kept, float meshopt_error) {
    std::vector<uint32_t> input, fans;
    input.reserve(indices.size());
    for (size_t f = 0; f < indices.size(); f += 3) {
        const bool fan = kept[indices[f]] || kept[indices[f + 1]] || kept[indices[f + 2]];
        (fan ? fans : input).insert((fan ? fans : input).end(), indices.begin() + f, indices.begin() + f + 3);
    }
    std::vector<uint32_t> out(input.size());
    const auto* xyz = reinterpret_cast<const float*>(positions.data());
    // Target 0 triangles: the error bound alone decides where the collapses stop.
    out.resize(meshopt_simplify(out.data(), input.data(), input.size(), xyz, positions.size(), sizeof(glm::vec3),
                                /*target_index_count=*/0, meshopt_error, meshopt_SimplifyLockBorder, nullptr));
    out.insert(out.end(), fans.begin(), fans.end());
    return out;
}

}  // namespace

SimplifiedIndices simplify_indices(std::span<const glm::vec3> positions, std::span<const uint32_t> indices, float target_error) {
    assert(target_error > 0.0f && indices.size() % 3 == 0);
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "positions are read as tight float triples");
    SimplifiedIndices out;
    if (indices.empty() || positions.empty()) return out;
    out.extent = meshopt_simplifyScale(reinterpret_cast<const float*>(positions.data()), positions.size(), sizeof(glm::vec3));
    const float bound = target_error * out.extent;
    const SurfaceDistance to_full(positions, indices);
    std::vector<bool> kept(positions.size(), false);
    float meshopt_error = target_error;
    std::vector<uint32_t> simplified;
    // Each round keeps at least one more vertex or lowers the simplifier's error, and with every vertex kept the
    // list is the full one (distance 0): the loop ends. The cap only guards against a bound no float reaches.
    for (uint32_t round = 0; round < 4 * positions.size() + 64; ++round) {
        simplified = simplify_around(positions, indices, kept, meshopt_error);
        const SurfaceDistance to_simplified(positions, simplified);
        const SurfaceDistance::Result full_side = to_simplified.from(indices);
        const SurfaceDistance::Result simple_side = to_full.from(simplified);
        if (full_side.largest <= bound && simple_side.largest <= bound) {
            out.distance = std::max(full_side.largest, simple_side.largest);
            break;
        }
        if (simple_side.largest > bound) meshopt_error *= 0.8f;  // the quadric let a new triangle stray
        bool more = false;
        for (size_t f = 0; f < full_side.per_triangle.size(); ++f) {
            if (full_side.per_triangle[f] <= bound) continue;
            // Keep the corner farthest from the new surface (the collapsed tip) with its fan.
            uint32_t worst = indices[3 * f];
            float far = -1.0f;
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = indices[3 * f + k];
                const float d = to_simplified.distance(positions[v], std::span<const uint32_t>(&indices[3 * f + k], 1));
                if (d > far) far = d, worst = v;
            }
            more = more || !kept[worst];
            kept[worst] = true;
        }
        if (!more && simple_side.largest <= bound) {  // every offending corner already kept: keep whole triangles
            for (size_t f = 0; f < full_side.per_triangle.size(); ++f)
                if (full_side.per_triangle[f] > bound)
                    for (int k = 0; k < 3; ++k) kept[indices[3 * f + k]] = true;
        }
    }
    out.indices.resize(simplified.size());
    meshopt_optimizeVertexCache(out.indices.data(), simplified.data(), simplified.size(), positions.size());
    return out;
}

}  // namespace aloha
