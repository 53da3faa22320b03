// Distances between triangle lists over the same vertices (see surface_distance.hpp).
#include "systems/geometry/controller/surface_distance.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <limits>

namespace aloha {

float point_triangle_distance(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return glm::length(p - a);
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return glm::length(p - b);
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return glm::length(p - c);
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && d4 - d3 >= 0.0f && d5 - d6 >= 0.0f)
        return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    const float sum = va + vb + vc;
    if (!(sum > 0.0f)) {  // degenerate (collinear corners): the nearest of its three edges
        const auto segment = [&](glm::vec3 s, glm::vec3 e) {
            const glm::vec3 d = e - s;
            const float len2 = glm::dot(d, d);
            const float t = len2 > 0.0f ? std::clamp(glm::dot(p - s, d) / len2, 0.0f, 1.0f) : 0.0f;
            return glm::length(p - (s + t * d));
        };
        return std::min({segment(a, b), segment(b, c), segment(c, a)});
    }
    const float denom = 1.0f / sum;
    return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

SurfaceDistance::SurfaceDistance(std::span<const glm::vec3> positions, std::span<const uint32_t> to)
    : positions_(positions), to_(to), first_(positions.size() + 1, 0) {
    assert(to.size() % 3 == 0);
    for (const uint32_t v : to) {
        assert(v < positions.size());
        ++first_[v + 1];
    }
    for (size_t v = 0; v < positions.size(); ++v) first_[v + 1] += first_[v];
    touching_.resize(to.size());
    std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
    for (size_t i = 0; i < to.size(); ++i) touching_[fill[to[i]]++] = static_cast<uint32_t>(i / 3);
    longest_edge_.resize(to.size() / 3);
    for (size_t t = 0; t < longest_edge_.size(); ++t) {
        const glm::vec3 a = positions[to[3 * t]], b = positions[to[3 * t + 1]], c = positions[to[3 * t + 2]];
        longest_edge_[t] = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    }
}

float SurfaceDistance::distance(glm::vec3 p, std::span<const uint32_t> near_vertices) const {
    float best = std::numeric_limits<float>::max();
    const auto triangle = [&](uint32_t t) {
        return point_triangle_distance(p, positions_[to_[3 * t]], positions_[to_[3 * t + 1]], positions_[to_[3 * t + 2]]);
    };
    for (const uint32_t v : near_vertices)
        for (uint32_t k = first_[v]; k < first_[v + 1]; ++k) best = std::min(best, triangle(touching_[k]));
    if (best == 0.0f) return best;
    // Every triangle, skipped where even its nearest corner's distance minus its longest edge is no better.
    for (uint32_t t = 0; t < to_.size() / 3; ++t) {
        const glm::vec3 a = positions_[to_[3 * t]], b = positions_[to_[3 * t + 1]], c = positions_[to_[3 * t + 2]];
        const float corner = std::min({glm::length(p - a), glm::length(p - b), glm::length(p - c)});
        if (corner - longest_edge_[t] >= best) continue;  // every point of the triangle is within its longest edge of a corner
        best = std::min(best, triangle(t));
    }
    return best;
}

SurfaceDistance::Result SurfaceDistance::from(std::span<const uint32_t> from) const {
    assert(from.size() % 3 == 0);
    Result r;
    r.per_triangle.assign(from.size() / 3, 0.0f);
    for (size_t f = 0; f < from.size() / 3; ++f) {
        const std::array<uint32_t, 3> corners = {from[3 * f], from[3 * f + 1], from[3 * f + 2]};
        const glm::vec3 a = positions_[corners[0]], b = positions_[corners[1]], c = positions_[corners[2]];
        const std::array<glm::vec3, kTriangleSamples> samples = {a, b, c, 0.5f * (a + b), 0.5f * (b + c), 0.5f * (c + a), (a + b + c) / 3.0f};
        float worst = 0.0f;
        for (const glm::vec3& p : samples) worst = std::max(worst, distance(p, corners));
        r.per_triangle[f] = worst;
        r.largest = std::max(r.largest, worst);
    }
    return r;
}

}  // namespace aloha
