// OpenSubdiv refinement: refined counts, Catmull-Clark shrinkage bound on a sphere, cache reuse.
#include "systems/geometry/spring_skin/subdivision.hpp"
#include "tests/systems/geometry/spring_skin/test_grids.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

namespace aloha {
namespace {

// Unique undirected edges of a face list.
size_t edge_count(const GridFaces& faces) {
    std::set<std::pair<int, int>> edges;
    size_t at = 0;
    for (int n : faces.vertex_counts) {
        for (int k = 0; k < n; ++k) {
            const int a = faces.vertex_indices[at + static_cast<size_t>(k)];
            const int b = faces.vertex_indices[at + static_cast<size_t>((k + 1) % n)];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
        at += static_cast<size_t>(n);
    }
    return edges.size();
}

TEST(Subdivision, RefinedCountsFollowCatmullClark) {
    SubdivisionCache cache;
    for (uint32_t T : {3u, 6u, 8u, 16u}) {
        for (uint32_t P : {2u, 4u, 7u}) {
            const uint32_t muscles = 3;
            GridFaces faces;
            const uint32_t V = grid_vertex_count(T, P);
            for (uint32_t m = 0; m < muscles; ++m) append_grid_faces(T, P, static_cast<int>(m * V), faces);
            const size_t F = faces.vertex_counts.size(), E = edge_count(faces), Vc = size_t{V} * muscles;
            // Closed genus-0 grids: Euler characteristic 2 per muscle.
            EXPECT_EQ(Vc + F, E + 2 * muscles);
            const SubdivisionTopology& l1 = cache.get({T, P, muscles, 1});
            EXPECT_EQ(l1.control_vertex_count, Vc);
            // Level 1: one new vertex per old vertex, edge and face.
            EXPECT_EQ(l1.refined_vertex_count, Vc + E + F);
            // Each n-gon becomes n quads.
            size_t corners = 0;
            for (int n : faces.vertex_counts) corners += static_cast<size_t>(n);
            EXPECT_EQ(l1.refined_face_count, corners);
            EXPECT_EQ(l1.triangles.size(), 6 * corners);
            // Level 2 from level 1 (all quads): V2 = V1 + E1 + F1 with E1 = 2E + corners, F1 = corners.
            const SubdivisionTopology& l2 = cache.get({T, P, muscles, 2});
            EXPECT_EQ(l2.refined_vertex_count, l1.refined_vertex_count + 2 * E + corners + corners);
            for (uint32_t index : l2.triangles) ASSERT_LT(index, l2.refined_vertex_count);
        }
    }
}

// Catmull-Clark points are convex combinations (non-negative weights summing to 1) of control
// vertices. At level 1 every new point (face, edge or vertex point) depends only on the faces
// around one control vertex v (its star). For control points on a sphere of radius R, such a
// combination p satisfies p . v_hat >= R cos(beta_v), beta_v = largest angle between v and a vertex
// of its star, so R cos(beta) <= |p| <= R (the ball is convex), beta = max over v.
TEST(Subdivision, RefinedSpherePointsStayWithinTheShrinkageBound) {
    const uint32_t T = 12, P = 8;
    const float R = 0.1f;
    const test::Grids sphere = test::ellipsoid(T, P, glm::vec3(R));
    GridFaces faces;
    append_grid_faces(T, P, 0, faces);
    float min_cos = 1.0f;
    size_t at = 0;
    for (int n : faces.vertex_counts) {
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) {
                const glm::vec3 pa = sphere.positions[static_cast<size_t>(faces.vertex_indices[at + static_cast<size_t>(a)])];
                const glm::vec3 pb = sphere.positions[static_cast<size_t>(faces.vertex_indices[at + static_cast<size_t>(b)])];
                min_cos = std::min(min_cos, glm::dot(pa, pb) / (R * R));
            }
        at += static_cast<size_t>(n);
    }
    SubdivisionCache cache;
    const SubdivisionTopology& topo = cache.get({T, P, 1, 1});
    std::vector<glm::vec3> refined(topo.refined_vertex_count), normals(topo.refined_vertex_count);
    SubdivideJob job{&topo, sphere.positions, refined, normals};
    std::vector<std::string> errors;
    ASSERT_TRUE(job.Validate(&errors)) << errors.front();
    job.Run();
    float min_r = R, max_r = 0.0f;
    for (size_t i = 0; i < refined.size(); ++i) {
        const float r = glm::length(refined[i]);
        min_r = std::min(min_r, r);
        max_r = std::max(max_r, r);
        // Outward normals: the refined mesh is convex and centred on the origin.
        EXPECT_GT(glm::dot(normals[i], refined[i] / r), 0.9f) << i;
    }
    // Tolerance 1e-6 relative: float rounding of stencil sums with ~20 terms.
    EXPECT_LE(max_r, R * (1.0f + 1e-6f));
    EXPECT_GE(min_r, R * min_cos * (1.0f - 1e-6f));
    EXPECT_LT(min_r, R) << "Catmull-Clark shrinks a coarse sphere";
}

TEST(Subdivision, CacheBuildsEachKeyOnce) {
    SubdivisionCache cache;
    const SubdivisionTopology& a = cache.get({8, 6, 4, 1});
    EXPECT_EQ(cache.build_count(), 1u);
    const SubdivisionTopology& b = cache.get({8, 6, 4, 1});
    EXPECT_EQ(cache.build_count(), 1u);
    EXPECT_EQ(&a, &b);
    cache.get({8, 6, 4, 2});
    cache.get({8, 6, 5, 1});
    EXPECT_EQ(cache.build_count(), 3u);
}

TEST(Subdivision, JobEvaluatesSeveralCharactersAndLevelZeroIsIdentity) {
    const uint32_t T = 8, P = 6;
    test::Grids two = test::ellipsoid(T, P, glm::vec3(0.1f));
    const size_t V = two.positions.size();
    for (size_t i = 0; i < V; ++i) two.positions.push_back(two.positions[i] + glm::vec3(1.0f, 0.0f, 0.0f));
    SubdivisionCache cache;
    const SubdivisionTopology& l1 = cache.get({T, P, 1, 1});
    std::vector<glm::vec3> refined(2 * l1.refined_vertex_count);
    SubdivideJob job{&l1, two.positions, refined, {}};
    ASSERT_TRUE(job.Validate());
    job.Run();
    // Stencil weights sum to 1, so translating the control mesh translates the refined mesh.
    for (size_t i = 0; i < l1.refined_vertex_count; ++i)
        EXPECT_NEAR(glm::length(refined[l1.refined_vertex_count + i] - refined[i] - glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
    const SubdivisionTopology& l0 = cache.get({T, P, 1, 0});
    std::vector<glm::vec3> same(V);
    SubdivideJob identity{&l0, std::span(two.positions).first(V), same, {}};
    ASSERT_TRUE(identity.Validate());
    identity.Run();
    for (size_t i = 0; i < V; ++i) EXPECT_EQ(same[i], two.positions[i]);

    std::vector<glm::vec3> wrong(3);
    SubdivideJob bad{&l1, two.positions, wrong, wrong};
    std::vector<std::string> errors;
    EXPECT_FALSE(bad.Validate(&errors));
    EXPECT_EQ(errors.size(), 1u);  // refined size (normals match refined, so only one failure)
}

}  // namespace
}  // namespace aloha
