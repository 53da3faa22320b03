// SurfaceDistance on a square pyramid against its base, where every distance is known in closed form.
#include "systems/geometry/controller/surface_distance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace aloha {
namespace {

// The unit square at z = 0 and an apex 1 above its centre.
const std::vector<glm::vec3> kPositions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 1.0f}};
const std::vector<uint32_t> kSides = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
const std::vector<uint32_t> kBase = {0, 2, 1, 0, 3, 2};

TEST(SurfaceDistance, PyramidAgainstItsBase) {
    // The apex is 1 above the base (it projects inside the square): the sides' farthest sample.
    const SurfaceDistance to_base(kPositions, kBase);
    const SurfaceDistance::Result sides = to_base.from(kSides);
    ASSERT_EQ(sides.per_triangle.size(), 4u);
    EXPECT_FLOAT_EQ(sides.largest, 1.0f);
    for (const float d : sides.per_triangle) EXPECT_FLOAT_EQ(d, 1.0f);
    // The base's farthest sample from the sides is its centre (the diagonal's midpoint): its distance to the
    // plane of a side, 0.5 h / sqrt(h^2 + 0.25) with h = 1, the foot (0.5, 0.1, 0.2) inside that side.
    const SurfaceDistance to_sides(kPositions, kSides);
    EXPECT_NEAR(to_sides.from(kBase).largest, 0.5f / std::sqrt(1.25f), 1e-6f);
    // A surface against itself: every sample lies on it.
    EXPECT_FLOAT_EQ(to_sides.from(kSides).largest, 0.0f);
}

TEST(SurfaceDistance, PointQueriesFindTheNearestTriangleWhereverTheSearchStarts) {
    const SurfaceDistance to_sides(kPositions, kSides);
    const glm::vec3 below(0.5f, 0.5f, -2.0f);  // 2 under the base's centre: nearest at the base's edges
    const float expected = std::sqrt(0.25f + 4.0f);
    EXPECT_NEAR(to_sides.distance(below, {}), expected, 1e-6f);
    const std::vector<uint32_t> far_corner = {2};
    EXPECT_NEAR(to_sides.distance(below, far_corner), expected, 1e-6f);
}

TEST(SurfaceDistance, DegenerateTrianglesMeasureToTheirSegment) {
    // Collinear corners: the distance to the segment they span.
    EXPECT_FLOAT_EQ(point_triangle_distance({0.5f, 1.0f, 0.0f}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}), 1.0f);
    EXPECT_FLOAT_EQ(point_triangle_distance({3.0f, 0.0f, 0.0f}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}), 1.0f);
    // All three corners equal: the distance to the point.
    EXPECT_FLOAT_EQ(point_triangle_distance({0.0f, 0.0f, 2.0f}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}), 2.0f);
}

}  // namespace
}  // namespace aloha
