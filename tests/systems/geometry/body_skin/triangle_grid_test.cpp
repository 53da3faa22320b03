// TriangleGrid against a brute-force search over every triangle, and closest_barycentric on degenerate triangles.
#include "systems/geometry/body_skin/triangle_grid.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace aloha {
namespace {

struct Soup {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
};

// Triangles of very different sizes and shapes: small ones clustered on a sphere (a skin's scale), a few
// large ones crossing many cells, slivers, and degenerate ones (collinear and coincident corners).
Soup mixed_soup(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    Soup s;
    const auto add = [&s](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        for (const glm::vec3& p : {a, b, c}) {
            s.indices.push_back(static_cast<uint32_t>(s.positions.size()));
            s.positions.push_back(p);
        }
    };
    for (int i = 0; i < 1500; ++i) {
        const glm::vec3 centre = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)) + glm::vec3(1e-3f));
        const glm::vec3 d1(unit(rng), unit(rng), unit(rng)), d2(unit(rng), unit(rng), unit(rng));
        add(centre, centre + 0.03f * d1, centre + 0.03f * d2);
    }
    for (int i = 0; i < 20; ++i)
        add({unit(rng) * 3, unit(rng) * 3, unit(rng) * 3}, {unit(rng) * 3, unit(rng) * 3, unit(rng) * 3},
            {unit(rng) * 3, unit(rng) * 3, unit(rng) * 3});
    for (int i = 0; i < 30; ++i) {
        const glm::vec3 a(unit(rng), unit(rng), unit(rng)), b(unit(rng), unit(rng), unit(rng));
        add(a, b, a + 1e-4f * glm::vec3(unit(rng), unit(rng), unit(rng)));  // sliver
        add(a, 0.5f * (a + b), b);                                           // collinear
        add(b, b, b);                                                        // a point
    }
    return s;
}

TriangleGrid::Hit brute_force(const Soup& s, glm::vec3 p) {
    TriangleGrid::Hit best;
    for (uint32_t f = 0; f < s.indices.size() / 3; ++f) {
        const glm::vec3 a = s.positions[s.indices[3 * f]], b = s.positions[s.indices[3 * f + 1]], c = s.positions[s.indices[3 * f + 2]];
        const glm::vec3 w = closest_barycentric(p, a, b, c);
        const glm::vec3 q = w.x * a + w.y * b + w.z * c;
        const float d = glm::dot(p - q, p - q);
        if (d < best.distance_sq) best = {f, w, d};
    }
    return best;
}

TEST(TriangleGrid, FindsTheSameClosestDistanceAsEveryTriangle) {
    // The grid's answer is a minimum over the same per-triangle values as the brute force's, so it is equal
    // bit for bit (only the triangle may differ where two are exactly as close).
    // Seed 4 lies 2 km from the origin, where a coordinate's rounding (0.1 mm) is a hundredth of a cell.
    for (uint32_t seed : {1u, 2u, 3u, 4u}) {
        Soup s = mixed_soup(seed);
        const glm::vec3 offset = seed == 4 ? glm::vec3(1000.0f, -500.0f, 2000.0f) : glm::vec3(0.0f);
        for (glm::vec3& p : s.positions) p += offset;
        const TriangleGrid grid(s.positions, s.indices);
        std::mt19937 rng(seed + 100);
        std::uniform_real_distribution<float> near(-1.2f, 1.2f), far(-40.0f, 40.0f);
        for (int q = 0; q < 600; ++q) {
            const glm::vec3 p = offset + (q % 3 == 2 ? glm::vec3(far(rng), far(rng), far(rng)) : glm::vec3(near(rng), near(rng), near(rng)));
            const TriangleGrid::Hit expected = brute_force(s, p);
            const TriangleGrid::Hit got = grid.closest(p);
            ASSERT_NE(got.triangle, TriangleGrid::Hit::kNone);
            ASSERT_EQ(got.distance_sq, expected.distance_sq) << "seed " << seed << " query " << q;
            EXPECT_NEAR(got.bary.x + got.bary.y + got.bary.z, 1.0f, 1e-6f);
        }
    }
}

TEST(TriangleGrid, ABoundLeavesOutEveryTriangleNoCloser) {
    const Soup s = mixed_soup(7);
    const TriangleGrid grid(s.positions, s.indices);
    const glm::vec3 p(0.2f, -1.7f, 0.4f);
    const TriangleGrid::Hit exact = grid.closest(p);
    ASSERT_NE(exact.triangle, TriangleGrid::Hit::kNone);
    // A bound at the closest distance itself: nothing is strictly closer.
    EXPECT_EQ(grid.closest(p, exact.distance_sq).triangle, TriangleGrid::Hit::kNone);
    // A looser bound finds the same point.
    const TriangleGrid::Hit bounded = grid.closest(p, 4.0f * exact.distance_sq + 1e-6f);
    EXPECT_EQ(bounded.distance_sq, exact.distance_sq);
}

TEST(TriangleGrid, OneTriangleAndAFlatListAreSearchedWhereverThePointIs) {
    // One triangle in the z = 0 plane: the grid is one cell thick; points far off every side find it.
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<uint32_t> indices = {0, 1, 2};
    const TriangleGrid grid(positions, indices);
    EXPECT_FLOAT_EQ(grid.closest({0.25f, 0.25f, 5.0f}).distance_sq, 25.0f);
    EXPECT_FLOAT_EQ(grid.closest({-3.0f, 0.0f, 0.0f}).distance_sq, 9.0f);
    EXPECT_FLOAT_EQ(grid.closest({1e6f, 0.0f, 0.0f}).distance_sq, (1e6f - 1.0f) * (1e6f - 1.0f));
    // An empty list has no closest point.
    const TriangleGrid empty(positions, {});
    EXPECT_EQ(empty.closest({0, 0, 0}).triangle, TriangleGrid::Hit::kNone);
}

TEST(ClosestBarycentric, DegenerateTrianglesGiveFiniteWeightsOnTheirSegment) {
    const auto point = [](glm::vec3 w, glm::vec3 a, glm::vec3 b, glm::vec3 c) { return w.x * a + w.y * b + w.z * c; };
    // Two corners equal (each pair in turn) and p beside the segment they span with the third: its foot.
    const glm::vec3 p(0.5f, 1.0f, 0.0f), o(0, 0, 0), x(1, 0, 0);
    for (const auto& [a, b, c] : {std::tuple{o, o, x}, std::tuple{o, x, o}, std::tuple{x, o, o}}) {
        const glm::vec3 w = closest_barycentric(p, a, b, c);
        ASSERT_TRUE(std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z));
        EXPECT_NEAR(w.x + w.y + w.z, 1.0f, 1e-6f);
        EXPECT_NEAR(glm::length(point(w, a, b, c) - glm::vec3(0.5f, 0, 0)), 0.0f, 1e-6f);
    }
    // Collinear corners, p past the far end: the far corner.
    const glm::vec3 w = closest_barycentric({3, 0, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0});
    EXPECT_NEAR(glm::length(point(w, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}) - glm::vec3(2, 0, 0)), 0.0f, 1e-6f);
    // All corners equal: that point.
    const glm::vec3 same = closest_barycentric({0, 0, 2}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1});
    EXPECT_NEAR(same.x + same.y + same.z, 1.0f, 1e-6f);
}

}  // namespace
}  // namespace aloha
