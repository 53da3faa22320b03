// A skinned level with simplify_error (simplified_indices.hpp): fewer triangles over the same vertices, the
// surface closed, and within the error bound of the full list, on the built-in humanoid's 6x3 skin.
#include "systems/geometry/body_skin/skin_remesh.hpp"
#include "systems/geometry/controller/controller_level.hpp"
#include "systems/geometry/controller/simplified_indices.hpp"
#include "systems/geometry/controller/surface_distance.hpp"
#include "test_humanoid.hpp"

#include <algorithm>
#include <limits>

namespace aloha {
namespace {

// The largest distance from the samples of `from`'s triangles to the surface `to`, by brute force (every
// sample against every triangle): the check on SurfaceDistance's pruned search.
float brute_force_distance(std::span<const glm::vec3> positions, std::span<const uint32_t> from, std::span<const uint32_t> to) {
    float worst = 0.0f;
    for (size_t f = 0; f + 2 < from.size(); f += 3) {
        const glm::vec3 a = positions[from[f]], b = positions[from[f + 1]], c = positions[from[f + 2]];
        for (const glm::vec3 p : {a, b, c, 0.5f * (a + b), 0.5f * (b + c), 0.5f * (c + a), (a + b + c) / 3.0f}) {
            float best = std::numeric_limits<float>::max();
            for (size_t t = 0; t + 2 < to.size(); t += 3)
                best = std::min(best, point_triangle_distance(p, positions[to[t]], positions[to[t + 1]], positions[to[t + 2]]));
            worst = std::max(worst, best);
        }
    }
    return worst;
}

TEST(SimplifiedIndices, HumanoidSkinStaysClosedAndWithinTheBound) {
    ASSERT_NE(test::humanoid().geometry, nullptr);
    const SkinLayer& skin = test::humanoid().geometry->skin_layer(6, 3);
    const std::span<const glm::vec3> rest = skin.rest_positions;
    const std::span<const uint32_t> full = skin.indices;
    const SurfaceTopology before = analyse_surface(full, rest.size());
    ASSERT_EQ(before.boundary_edges, 0u);
    ASSERT_EQ(before.non_manifold_edges, 0u);
    for (const float target : {0.006f, 0.012f, 0.03f}) {  // the default rules' two levels and a coarse one
        SCOPED_TRACE(target);
        const SimplifiedIndices s = simplify_indices(rest, full, target);
        ASSERT_EQ(s.indices.size() % 3, 0u);
        EXPECT_LT(s.indices.size(), full.size());
        EXPECT_GT(s.indices.size(), 0u);
        for (const uint32_t i : s.indices) ASSERT_LT(i, rest.size());  // the same vertices, none new
        // Still closed (no hole for back-face culling to show through), one piece, no degenerate triangle.
        // meshoptimizer does not promise a manifold result: where a thin part collapses, a few edges end up
        // in four triangles (measured: 5 at 0.006, 11 at 0.012, 7 at 0.03); 12 is a regression guard, not a bound.
        const SurfaceTopology after = analyse_surface(s.indices, rest.size());
        EXPECT_EQ(after.boundary_edges, 0u);
        EXPECT_LE(after.non_manifold_edges, 12u);
        EXPECT_EQ(after.degenerate_triangles, 0u);
        EXPECT_EQ(after.components, before.components);
        // The humanoid stands ~1.8 m tall: the extent the bound is relative to is its height.
        EXPECT_NEAR(s.extent, 1.8f, 0.2f);
        // Both ways within the bound, measured here independently of the rounds' own bookkeeping: points of
        // the new surface near the old one, and points of the old surface (a hand's tip, which meshoptimizer's
        // quadric alone let move 0.025 of the height at 0.008) near the new one.
        const float bound = target * s.extent;
        const float simple_to_full = brute_force_distance(rest, s.indices, full);
        const float full_to_simple = brute_force_distance(rest, full, s.indices);
        EXPECT_LE(simple_to_full, bound);
        EXPECT_LE(full_to_simple, bound);
        EXPECT_FLOAT_EQ(SurfaceDistance(rest, full).from(s.indices).largest, simple_to_full);
        EXPECT_FLOAT_EQ(SurfaceDistance(rest, s.indices).from(full).largest, full_to_simple);
        EXPECT_FLOAT_EQ(s.distance, std::max(simple_to_full, full_to_simple));
    }
}

TEST(SimplifiedIndices, ControllerLevelShowsTheSimplifiedListOverTheSameVertices) {
    ASSERT_NE(test::humanoid().geometry, nullptr);
    const CharacterGeometry& g = *test::humanoid().geometry;
    std::vector<GeomLod> levels = {test::grid_level(GeomMethod::SkinnedMesh, 6, 3), test::grid_level(GeomMethod::SkinnedMesh, 6, 3),
                                   test::grid_level(GeomMethod::Hidden, 6, 3)};
    levels[1].simplify_error = 0.008f;
    for (size_t i = 0; i < levels.size(); ++i) levels[i].level = static_cast<uint8_t>(i);
    GeometryController ctl(g, levels, 2);
    EXPECT_EQ(ctl.vertices_per_character(1), ctl.vertices_per_character(0));
    EXPECT_EQ(ctl.level_indices(0).size(), g.skin_layer(6, 3).indices.size());
    const SimplifiedIndices s = simplify_indices(g.skin_layer(6, 3).rest_positions, g.skin_layer(6, 3).indices, 0.008f);
    EXPECT_TRUE(std::equal(ctl.level_indices(1).begin(), ctl.level_indices(1).end(), s.indices.begin(), s.indices.end()));
    EXPECT_NE(ctl.topology_key(1), ctl.topology_key(0));
    // A change of the error alone rebuilds the level (same_level_shape), keeping the others.
    EXPECT_FALSE(same_level_shape(levels[0], levels[1]));
}

}  // namespace
}  // namespace aloha
