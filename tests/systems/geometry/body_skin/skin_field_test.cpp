// Body field, marching tetrahedra, simplification and surface correspondence on shapes with known
// answers (spheres and a dumbbell).
#include "systems/geometry/body_skin/skin_field.hpp"
#include "systems/geometry/body_skin/skin_remesh.hpp"
#include "systems/geometry/body_skin/surface_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace aloha {
namespace {

// Volume enclosed by a closed, outward-oriented triangle list (divergence theorem).
double enclosed_volume(const TriangleSurface& s) {
    double v = 0.0;
    for (size_t f = 0; f < s.indices.size(); f += 3) {
        const glm::dvec3 a(s.positions[s.indices[f]]), b(s.positions[s.indices[f + 1]]), c(s.positions[s.indices[f + 2]]);
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return v;
}

BodyField sphere(float r) {
    BodyField f;
    f.ellipsoids.push_back({glm::vec3(0.1f, 0.2f, -0.3f), glm::quat(1, 0, 0, 0), glm::vec3(r), glm::vec2(1.0f)});
    return f;
}

TEST(SkinField, EllipsoidDistanceIsExactForASphere) {
    const FieldEllipsoid e{glm::vec3(0.0f), glm::quat(1, 0, 0, 0), glm::vec3(0.1f), glm::vec2(1.0f)};
    EXPECT_NEAR(ellipsoid_distance(e, glm::vec3(0.3f, 0.0f, 0.0f)), 0.2f, 1e-6f);
    EXPECT_NEAR(ellipsoid_distance(e, glm::vec3(0.0f, 0.05f, 0.0f)), -0.05f, 1e-6f);
    EXPECT_NEAR(capsule_distance({glm::vec3(0.0f), glm::vec3(1, 0, 0), 0.1f}, glm::vec3(0.5f, 0.3f, 0.0f)), 0.2f, 1e-6f);
}

TEST(SkinField, SphereIsClosedOrientedAndHasItsVolume) {
    const float r = 0.1f, cell = 0.01f;
    const SampledField field = sample_body_field(sphere(r), cell);
    const TriangleSurface s = polygonise(field);
    const SurfaceTopology t = analyse_surface(s.indices, s.positions.size());
    EXPECT_TRUE(t.closed_connected()) << t.boundary_edges << " " << t.non_manifold_edges << " " << t.components;
    // Vertices lie on the sphere up to the linear interpolation error of a cell (~cell^2 / (2 r)).
    for (const glm::vec3& p : s.positions) EXPECT_NEAR(glm::length(p - glm::vec3(0.1f, 0.2f, -0.3f)), r, cell * cell / r);
    // Positive volume (outward orientation) close to 4/3 pi r^3 (the inscribed polyhedron loses a few %).
    const double exact = 4.0 / 3.0 * M_PI * r * r * r;
    EXPECT_NEAR(enclosed_volume(s) / exact, 1.0, 0.05);
}

TEST(SkinField, DumbbellJoinsIntoOneSurfaceAndSimplifies) {
    BodyField f = sphere(0.08f);
    f.ellipsoids.push_back({glm::vec3(0.4f, 0.2f, -0.3f), glm::quat(1, 0, 0, 0), glm::vec3(0.08f), glm::vec2(1.0f)});
    f.capsules.push_back({glm::vec3(0.1f, 0.2f, -0.3f), glm::vec3(0.4f, 0.2f, -0.3f), 0.03f});
    const SampledField field = sample_body_field(f, 0.008f);
    const TriangleSurface dense = polygonise(field);
    EXPECT_TRUE(analyse_surface(dense.indices, dense.positions.size()).closed_connected());
    const TriangleSurface coarse = simplify_and_relax(dense, field, 800);
    const SurfaceTopology t = analyse_surface(coarse.indices, coarse.positions.size());
    EXPECT_TRUE(t.closed_connected()) << t.boundary_edges << " " << t.non_manifold_edges << " " << t.components;
    EXPECT_LE(coarse.indices.size() / 3, 800u);
    EXPECT_GE(coarse.indices.size() / 3, 600u);
    // Relaxed vertices sit on the zero set (Newton projection on the trilinear field: within 1 mm).
    for (const glm::vec3& p : coarse.positions) EXPECT_LT(std::abs(field.sample(p)), 1e-3f);
    EXPECT_NEAR(enclosed_volume(coarse) / enclosed_volume(dense), 1.0, 0.03);
}

// A cubic grid of side 0.6 m, 1 cm cells, centred on the origin, holding `f` at its points.
template <class F>
SampledField grid_of(F f) {
    SampledField g;
    g.origin = glm::vec3(-0.3f);
    g.cell = 0.01f;
    g.nx = g.ny = g.nz = 61;
    for (uint32_t z = 0; z < g.nz; ++z)
        for (uint32_t y = 0; y < g.ny; ++y)
            for (uint32_t x = 0; x < g.nx; ++x) g.values.push_back(f(g.origin + g.cell * glm::vec3(x, y, z)));
    return g;
}

// Whether grid point i lies `margin` cells or more inside the grid (the blur repeats border values beyond it).
bool interior(const SampledField& g, size_t i, uint32_t margin) {
    const uint32_t x = static_cast<uint32_t>(i % g.nx), y = static_cast<uint32_t>(i / g.nx % g.ny), z = static_cast<uint32_t>(i / (size_t{g.nx} * g.ny));
    return x >= margin && y >= margin && z >= margin && x + margin < g.nx && y + margin < g.ny && z + margin < g.nz;
}

// Filling concavities: the blur of a plane's distance is the plane's (a symmetric kernel averages a linear function
// to its centre value), a sphere's distance is convex so its blur is higher (Jensen) and the lower of the two is the
// distance itself; where two spheres meet the union's distance is not convex, and the crease between them fills.
TEST(SkinField, FillingConcavitiesKeepsPlanesAndConvexShapesAndFillsCreases) {
    const float sigma = 0.03f;
    const uint32_t margin = 9;  // the kernel's reach, 3 sigma in cells
    SampledField plane = grid_of([](glm::vec3 p) { return 0.3f * p.x + 0.9f * p.y - 0.02f; });
    const std::vector<float> plane_before = plane.values;
    fill_concavities(plane.values, plane, sigma);
    float plane_change = 0.0f;
    for (size_t i = 0; i < plane.values.size(); ++i)
        if (interior(plane, i, margin)) plane_change = std::max(plane_change, std::abs(plane.values[i] - plane_before[i]));
    EXPECT_LT(plane_change, 1e-6f) << "float rounding of a 19-tap sum per axis";

    SampledField ball = grid_of([](glm::vec3 p) { return glm::length(p) - 0.1f; });
    const std::vector<float> ball_before = ball.values;
    fill_concavities(ball.values, ball, sigma);
    for (size_t i = 0; i < ball.values.size(); ++i)
        if (interior(ball, i, margin)) {
            ASSERT_EQ(ball.values[i], ball_before[i]) << "point " << i;
        }

    // Two balls of radius 0.1 m, centres 0.18 m apart: their surfaces meet on a ring of radius sqrt(0.1^2 - 0.09^2)
    // in the plane x = 0, at an angle; a point on that ring is on the union's surface before and inside after.
    const auto two = [](glm::vec3 p) { return std::min(glm::length(p - glm::vec3(0.09f, 0, 0)), glm::length(p + glm::vec3(0.09f, 0, 0))) - 0.1f; };
    SampledField pair = grid_of(two);
    fill_concavities(pair.values, pair, sigma);
    const float ring = std::sqrt(0.1f * 0.1f - 0.09f * 0.09f);
    EXPECT_NEAR(two(glm::vec3(0.0f, ring, 0.0f)), 0.0f, 1e-6f);
    const float filled = pair.sample(glm::vec3(0.0f, ring, 0.0f));
    std::printf("the crease point is %.1f mm inside once filled\n", static_cast<double>(-1000.0f * filled));
    EXPECT_LT(filled, -0.005f) << "the crease is filled (regression guard: measured 10.6 mm)";
    // The balls' far sides are convex: unchanged (the trilinear sample reads the grid's own values).
    EXPECT_NEAR(pair.sample(glm::vec3(0.19f, 0.0f, 0.0f)), two(glm::vec3(0.19f, 0.0f, 0.0f)), 1e-6f);
}

// The levels of a body are simplified in one pass: stopping at a larger target and going on pops the
// same collapses as going straight to the smaller one, so every snapshot equals its own collapse, bit
// for bit, whatever order the targets are given in.
TEST(SkinField, ProgressiveCollapseEqualsEachCollapseOnItsOwn) {
    BodyField f = sphere(0.08f);
    f.capsules.push_back({glm::vec3(0.1f, 0.2f, -0.3f), glm::vec3(0.4f, 0.2f, -0.3f), 0.03f});
    const SampledField field = sample_body_field(f, 0.01f);
    const TriangleSurface dense = polygonise(field);
    const std::vector<uint32_t> targets = {600, 2400, 150, 1200};
    const std::vector<TriangleSurface> all = simplify_and_relax_all(dense, field, targets);
    ASSERT_EQ(all.size(), targets.size());
    for (size_t i = 0; i < targets.size(); ++i) {
        const TriangleSurface alone = simplify_and_relax(dense, field, targets[i]);
        EXPECT_LE(all[i].indices.size() / 3, targets[i]);
        EXPECT_EQ(all[i].indices, alone.indices) << "target " << targets[i];
        ASSERT_EQ(all[i].positions.size(), alone.positions.size()) << "target " << targets[i];
        for (size_t v = 0; v < alone.positions.size(); ++v) EXPECT_EQ(all[i].positions[v], alone.positions[v]);
    }
}

TEST(SurfaceMap, MapsAVertexOntoItsTriangle) {
    const std::vector<glm::vec3> src = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    const std::vector<uint32_t> idx = {0, 1, 2, 1, 3, 2};
    const std::vector<glm::vec3> dst = {{0.25f, 0.25f, 0.1f}, {0.9f, 0.8f, -0.2f}};
    const SurfaceMap map = map_surface(src, idx, dst);
    std::vector<glm::vec3> out(2);
    map.apply(src, out);
    EXPECT_NEAR(glm::length(out[0] - glm::vec3(0.25f, 0.25f, 0.0f)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(out[1] - glm::vec3(0.9f, 0.8f, 0.0f)), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace aloha
