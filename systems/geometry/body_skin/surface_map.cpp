// Surface-to-surface correspondence by closest points (see surface_map.hpp).
#include "systems/geometry/body_skin/surface_map.hpp"

#include <cassert>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace aloha {

void SurfaceMap::apply(std::span<const glm::vec3> source, std::span<glm::vec3> out) const {
    assert(out.size() == corners.size());
    for (size_t i = 0; i < corners.size(); ++i)
        out[i] = bary[i].x * source[corners[i].x] + bary[i].y * source[corners[i].y] + bary[i].z * source[corners[i].z];
}

glm::vec3 closest_barycentric(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return {1, 0, 0};
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return {0, 1, 0};
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
        const float v = d1 / (d1 - d3);
        return {1 - v, v, 0};
    }
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return {0, 0, 1};
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
        const float w = d2 / (d2 - d6);
        return {1 - w, 0, w};
    }
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
        const float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - w, w};
    }
    const float denom = 1.0f / (va + vb + vc);
    const float v = vb * denom, w = vc * denom;
    return {1 - v - w, v, w};
}

SurfaceMap map_surface(std::span<const glm::vec3> source_positions, std::span<const uint32_t> source_indices,
                       std::span<const glm::vec3> target_positions) {
    assert(source_indices.size() >= 3);
    const size_t triangles = source_indices.size() / 3;
    double edge_sum = 0.0;
    for (size_t f = 0; f < triangles; ++f)
        edge_sum += glm::length(source_positions[source_indices[3 * f + 1]] - source_positions[source_indices[3 * f]]);
    const float cell = std::max(static_cast<float>(edge_sum / static_cast<double>(triangles)), 1e-4f);
    // Hash cell -> triangles whose centroid lies in it.
    auto key = [&](glm::ivec3 c) { return (uint64_t(uint32_t(c.x) & 0x1FFFFF) << 42) | (uint64_t(uint32_t(c.y) & 0x1FFFFF) << 21) | (uint32_t(c.z) & 0x1FFFFF); };
    auto cell_of = [&](glm::vec3 p) { return glm::ivec3(glm::floor(p / cell)); };
    std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
    for (size_t f = 0; f < triangles; ++f) {
        const glm::vec3 c = (source_positions[source_indices[3 * f]] + source_positions[source_indices[3 * f + 1]] +
                             source_positions[source_indices[3 * f + 2]]) / 3.0f;
        grid[key(cell_of(c))].push_back(static_cast<uint32_t>(f));
    }
    SurfaceMap map;
    map.corners.resize(target_positions.size());
    map.bary.resize(target_positions.size());
    for (size_t i = 0; i < target_positions.size(); ++i) {
        const glm::vec3 p = target_positions[i];
        float best = std::numeric_limits<float>::infinity();
        auto consider = [&](uint32_t f) {
            const glm::uvec3 v(source_indices[3 * f], source_indices[3 * f + 1], source_indices[3 * f + 2]);
            const glm::vec3 b = closest_barycentric(p, source_positions[v.x], source_positions[v.y], source_positions[v.z]);
            const glm::vec3 q = b.x * source_positions[v.x] + b.y * source_positions[v.y] + b.z * source_positions[v.z];
            const float d = glm::dot(p - q, p - q);
            if (d < best) {
                best = d;
                map.corners[i] = v;
                map.bary[i] = b;
            }
        };
        const glm::ivec3 c0 = cell_of(p);
        for (int radius = 2; radius <= 8 && !std::isfinite(best); radius *= 2)
            for (int z = -radius; z <= radius; ++z)
                for (int y = -radius; y <= radius; ++y)
                    for (int x = -radius; x <= radius; ++x) {
                        const auto it = grid.find(key(c0 + glm::ivec3(x, y, z)));
                        if (it == grid.end()) continue;
                        for (const uint32_t f : it->second) consider(f);
                    }
        if (!std::isfinite(best))
            for (size_t f = 0; f < triangles; ++f) consider(static_cast<uint32_t>(f));
    }
    return map;
}

}  // namespace aloha
