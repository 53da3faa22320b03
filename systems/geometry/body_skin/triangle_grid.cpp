// Exact closest-point queries on a triangle list (see triangle_grid.hpp).
#include "systems/geometry/body_skin/triangle_grid.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace aloha {
namespace {

// The closest point of the three edges, as weights: for a triangle whose barycentric formula has no
// denominator (collinear or coincident corners).
glm::vec3 closest_on_edges(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    glm::vec3 best_weights{1.0f, 0.0f, 0.0f};
    float best = glm::dot(p - a, p - a);
    const auto segment = [&](glm::vec3 s, glm::vec3 e, int is, int ie) {
        const glm::vec3 d = e - s;
        const float len2 = glm::dot(d, d);
        const float t = len2 > 0.0f ? std::clamp(glm::dot(p - s, d) / len2, 0.0f, 1.0f) : 0.0f;
        const glm::vec3 q = s + t * d;
        const float dist = glm::dot(p - q, p - q);
        if (dist < best) {
            best = dist;
            best_weights = glm::vec3(0.0f);
            best_weights[is] = 1.0f - t;
            best_weights[ie] += t;
        }
    };
    segment(a, b, 0, 1);
    segment(b, c, 1, 2);
    segment(c, a, 2, 0);
    return best_weights;
}

}  // namespace

glm::vec3 closest_barycentric(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return {1, 0, 0};
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return {0, 1, 0};
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
        if (!(d1 - d3 > 0.0f)) return closest_on_edges(p, a, b, c);  // a == b
        const float v = d1 / (d1 - d3);
        return {1 - v, v, 0};
    }
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return {0, 0, 1};
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
        if (!(d2 - d6 > 0.0f)) return closest_on_edges(p, a, b, c);  // a == c
        const float w = d2 / (d2 - d6);
        return {1 - w, 0, w};
    }
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
        if (!((d4 - d3) + (d5 - d6) > 0.0f)) return closest_on_edges(p, a, b, c);  // b == c
        const float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - w, w};
    }
    const float sum = va + vb + vc;
    if (!(sum > 0.0f)) return closest_on_edges(p, a, b, c);  // collinear corners
    const float denom = 1.0f / sum;
    const float v = vb * denom, w = vc * denom;
    return {1 - v - w, v, w};
}

TriangleGrid::TriangleGrid(std::span<const glm::vec3> positions, std::span<const uint32_t> indices)
    : positions_(positions), indices_(indices) {
    assert(indices.size() % 3 == 0);
    const size_t triangles = indices.size() / 3;
    if (triangles == 0) {
        first_.assign(2, 0);
        return;
    }
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    double edge_sum = 0.0;
    box_lo_.resize(triangles);
    box_hi_.resize(triangles);
    for (size_t f = 0; f < triangles; ++f) {
        const glm::vec3 a = positions[indices[3 * f]], b = positions[indices[3 * f + 1]], c = positions[indices[3 * f + 2]];
        box_lo_[f] = glm::min(a, glm::min(b, c));
        box_hi_[f] = glm::max(a, glm::max(b, c));
        lo = glm::min(lo, box_lo_[f]);
        hi = glm::max(hi, box_hi_[f]);
        edge_sum += std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    }
    const glm::vec3 extent = hi - lo;
    assert(std::isfinite(extent.x + extent.y + extent.z) && "positions must be finite (loaders reject others)");
    const float largest = std::max({extent.x, extent.y, extent.z});
    // A flat or point-like list still gets a positive cell; the cell never goes below a millionth of the extent.
    cell_ = std::max({static_cast<float>(edge_sum / static_cast<double>(triangles)), largest * 1e-6f, 1e-12f});
    const double cell_cap = 16.0 * static_cast<double>(triangles) + 4096.0;
    const auto dims_for = [&](float cell) {
        return glm::ivec3(glm::clamp(glm::ceil(extent / cell), glm::vec3(1.0f), glm::vec3(1 << 20)));
    };
    for (dims_ = dims_for(cell_); double(dims_.x) * dims_.y * dims_.z > cell_cap; dims_ = dims_for(cell_)) cell_ *= 1.25f;
    origin_ = lo;
    // Cell faces and a point's cell are rounded at the coordinates' magnitude: a point binned into a cell may sit
    // that much before its face (a few ulps of the largest coordinate, and a little of the cell).
    const float magnitude = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x), std::abs(hi.y), std::abs(hi.z)});
    face_slack_ = 1e-5f * cell_ + 8.0f * std::numeric_limits<float>::epsilon() * magnitude;

    // Counting sort of (cell, triangle) pairs over every cell a triangle's bounding box touches.
    const size_t cells = size_t(dims_.x) * size_t(dims_.y) * size_t(dims_.z);
    first_.assign(cells + 1, 0);
    const auto for_each_cell = [&](size_t f, auto&& visit) {
        const glm::ivec3 c0 = cell_of(box_lo_[f]), c1 = cell_of(box_hi_[f]);
        for (int z = c0.z; z <= c1.z; ++z)
            for (int y = c0.y; y <= c1.y; ++y)
                for (int x = c0.x; x <= c1.x; ++x) visit(cell_index({x, y, z}));
    };
    for (size_t f = 0; f < triangles; ++f) for_each_cell(f, [&](size_t cell) { ++first_[cell + 1]; });
    for (size_t c = 0; c < cells; ++c) first_[c + 1] += first_[c];
    triangles_.resize(first_[cells]);
    std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
    for (size_t f = 0; f < triangles; ++f)
        for_each_cell(f, [&](size_t cell) { triangles_[fill[cell]++] = static_cast<uint32_t>(f); });
}

glm::ivec3 TriangleGrid::cell_of(glm::vec3 p) const {
    const glm::vec3 c = glm::floor((p - origin_) / cell_);
    return glm::clamp(glm::ivec3(glm::clamp(c, glm::vec3(-1.0f), glm::vec3(dims_))), glm::ivec3(0), dims_ - 1);
}

size_t TriangleGrid::cell_index(glm::ivec3 c) const {
    return (size_t(c.z) * size_t(dims_.y) + size_t(c.y)) * size_t(dims_.x) + size_t(c.x);
}

float TriangleGrid::outside_box_distance_sq(glm::vec3 p, glm::ivec3 lo, glm::ivec3 hi) const {
    // Every cell outside the box lies beyond one of its faces that has cells behind it: the nearest such
    // half-space bounds the distance to all of them (a face on the grid's edge has nothing behind it).
    float nearest = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (lo[a] > 0) nearest = std::min(nearest, std::max(0.0f, p[a] - (origin_[a] + float(lo[a]) * cell_)));
        if (hi[a] < dims_[a] - 1) nearest = std::min(nearest, std::max(0.0f, origin_[a] + float(hi[a] + 1) * cell_ - p[a]));
    }
    nearest = std::max(0.0f, nearest - face_slack_);
    return nearest * nearest;
}

TriangleGrid::Hit TriangleGrid::closest(glm::vec3 p, float bound_sq) const {
    Hit hit;
    hit.distance_sq = bound_sq;
    if (triangles_.empty()) return hit;
    assert(std::isfinite(p.x + p.y + p.z) && "the query point must be finite");
    const auto consider = [&](uint32_t f) {
        // No point of the triangle is nearer than its bounding box; the margin keeps a triangle whose rounded
        // distance could still come out below the best (its closest point on the box's surface).
        const glm::vec3 outside = glm::max(glm::max(box_lo_[f] - p, p - box_hi_[f]), glm::vec3(0.0f));
        if (glm::dot(outside, outside) * (1.0f - 1e-5f) >= hit.distance_sq) return;
        const glm::vec3 a = positions_[indices_[3 * f]], b = positions_[indices_[3 * f + 1]], c = positions_[indices_[3 * f + 2]];
        const glm::vec3 w = closest_barycentric(p, a, b, c);
        const glm::vec3 q = w.x * a + w.y * b + w.z * c;
        const float d = glm::dot(p - q, p - q);
        if (d < hit.distance_sq) {
            hit.distance_sq = d;
            hit.triangle = f;
            hit.bary = w;
        }
    };
    const auto visit = [&](glm::ivec3 c) {
        const size_t cell = cell_index(c);
        for (uint32_t k = first_[cell]; k < first_[cell + 1]; ++k) consider(triangles_[k]);
    };
    const glm::ivec3 c0 = cell_of(p);
    const int max_radius = std::max({dims_.x, dims_.y, dims_.z});
    for (int r = 0; r <= max_radius; ++r) {
        const glm::ivec3 lo = c0 - r, hi = c0 + r;
        const glm::ivec3 clo = glm::max(lo, glm::ivec3(0)), chi = glm::min(hi, dims_ - 1);
        // The shell: cells of the box at Chebyshev distance exactly r from c0 (clipped to the grid).
        for (int z = clo.z; z <= chi.z; ++z)
            for (int y = clo.y; y <= chi.y; ++y) {
                const bool face = z == lo.z || z == hi.z || y == lo.y || y == hi.y;
                if (face) {
                    for (int x = clo.x; x <= chi.x; ++x) visit({x, y, z});
                } else {
                    if (lo.x >= 0) visit({lo.x, y, z});
                    if (hi.x < dims_.x && hi.x != lo.x) visit({hi.x, y, z});
                }
            }
        const float beyond = outside_box_distance_sq(p, lo, hi);
        if (hit.distance_sq <= beyond) break;  // also once the box covers the grid (beyond is infinite)
    }
    return hit;
}

}  // namespace aloha
