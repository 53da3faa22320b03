// Distances between triangle lists over the same vertices (see surface_distance.hpp).
#include "systems/geometry/controller/surface_distance.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

namespace aloha {

float point_triangle_distance(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 w = closest_barycentric(p, a, b, c);
    const glm::vec3 q = w.x * a + w.y * b + w.z * c;
    return std::sqrt(glm::dot(p - q, p - q));  // the grid's squared distance, so the two agree bit for bit
}

SurfaceDistance::SurfaceDistance(std::span<const glm::vec3> positions, std::span<const uint32_t> to)
    : positions_(positions), to_(to), first_(positions.size() + 1, 0), grid_(positions, to) {
    assert(to.size() % 3 == 0);
    for (const uint32_t v : to) {
        assert(v < positions.size());
        ++first_[v + 1];
    }
    for (size_t v = 0; v < positions.size(); ++v) first_[v + 1] += first_[v];
    touching_.resize(to.size());
    std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
    for (size_t i = 0; i < to.size(); ++i) touching_[fill[to[i]]++] = static_cast<uint32_t>(i / 3);
}

float SurfaceDistance::distance(glm::vec3 p, std::span<const uint32_t> near_vertices) const {
    float best = std::numeric_limits<float>::max();
    const auto triangle = [&](uint32_t t) {
        return point_triangle_distance(p, positions_[to_[3 * t]], positions_[to_[3 * t + 1]], positions_[to_[3 * t + 2]]);
    };
    for (const uint32_t v : near_vertices)
        for (uint32_t k = first_[v]; k < first_[v + 1]; ++k) best = std::min(best, triangle(touching_[k]));
    if (best == 0.0f) return best;
    // Only a triangle closer than the best so far can change it.
    const TriangleGrid::Hit hit = grid_.closest(p, best == std::numeric_limits<float>::max() ? std::numeric_limits<float>::infinity() : best * best);
    return hit.triangle != TriangleGrid::Hit::kNone ? std::min(best, std::sqrt(hit.distance_sq)) : best;
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
