// Body field, marching tetrahedra, simplification and surface correspondence on shapes with known
// answers (spheres and a dumbbell).
#include "systems/geometry/body_skin/skin_field.hpp"
#include "systems/geometry/body_skin/skin_remesh.hpp"
#include "systems/geometry/body_skin/surface_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
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
