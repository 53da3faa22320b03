// Strain limiting of the skin: edges back within [lo, hi] x bind length, seams kept closed, nothing
// moved on a surface already within the limits.
#include "systems/geometry/spring_skin/strain_limit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace aloha {
namespace {

// A strip of `n` unit squares (two triangles each) along x, vertices 0..n on y = 0 and n+1..2n+1 on y = 1.
struct Strip {
    std::vector<glm::vec3> bind;
    std::vector<uint32_t> indices;
    explicit Strip(uint32_t n) {
        for (uint32_t i = 0; i <= n; ++i) bind.emplace_back(float(i), 0.0f, 0.0f);
        for (uint32_t i = 0; i <= n; ++i) bind.emplace_back(float(i), 1.0f, 0.0f);
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t a = i, b = i + 1, c = n + 1 + i, d = n + 2 + i;
            indices.insert(indices.end(), {a, b, d, a, d, c});
        }
    }
};

// Largest and smallest edge length / bind length over `edges`.
std::pair<float, float> ratio_range(const SkinEdges& edges, const std::vector<glm::vec3>& p) {
    float lo = 1e9f, hi = 0.0f;
    for (size_t e = 0; e < edges.rest.size(); ++e) {
        const float r = glm::length(p[edges.ends[2 * e + 1]] - p[edges.ends[2 * e]]) / edges.rest[e];
        lo = std::min(lo, r), hi = std::max(hi, r);
    }
    return {lo, hi};
}

TEST(StrainLimit, EdgesOfAStripAreCountedOnce) {
    const Strip s(4);
    const SkinEdges e = build_skin_edges(s.indices, s.bind);
    // 4 squares: 5 rungs, 2 x 4 rails, 4 diagonals.
    EXPECT_EQ(e.rest.size(), 17u);
    EXPECT_TRUE(e.copies.empty());
}

// One corner pulled 3 units out (edges up to ~4x) and another pushed onto its neighbour (a collapsed
// edge): after the job (accepting only the limits themselves) every edge is within them (Gauss-Seidel on 17 edges settles well within
// 64 passes: each pass at least halves the worst excess here).
TEST(StrainLimit, StretchedAndCollapsedEdgesReturnWithinTheLimits) {
    const Strip s(4);
    const SkinEdges e = build_skin_edges(s.indices, s.bind);
    std::vector<glm::vec3> p = s.bind;
    p[4] += glm::vec3(3.0f, 0.0f, 0.0f);
    p[1] = p[0] + glm::vec3(0.05f, 0.0f, 0.0f);
    EXPECT_GT(ratio_range(e, p).second, 2.0f);
    EXPECT_LT(ratio_range(e, p).first, 0.5f);
    const StrainLimits limits{0.55f, 1.8f, 64, 0.55f, 1.8f};  // accepted only within the limits themselves
    const StrainLimitJob job{&e, limits, p};
    ASSERT_TRUE(job.Validate());
    const StrainLimitResult r = job.Run();
    EXPECT_GT(r.projected, 0u);
    EXPECT_EQ(r.outside, 0u);
    const auto [lo, hi] = ratio_range(e, p);
    // Converged: within the limits up to float rounding of the lengths (1e-5 relative).
    EXPECT_GE(lo, 0.55f * (1.0f - 1e-5f));
    EXPECT_LE(hi, 1.8f * (1.0f + 1e-5f));
}

TEST(StrainLimit, ASurfaceWithinTheLimitsIsLeftAsItIs) {
    const Strip s(3);
    const SkinEdges e = build_skin_edges(s.indices, s.bind);
    std::vector<glm::vec3> p = s.bind;
    for (glm::vec3& v : p) v = 1.5f * v + glm::vec3(0.0f, 0.0f, 0.1f * v.x);  // 1.5x scale, within [0.55, 1.8]
    const std::vector<glm::vec3> before = p;
    const StrainLimitResult r = StrainLimitJob{&e, StrainLimits{}, p}.Run();
    EXPECT_EQ(r.projected, 0u);
    EXPECT_EQ(p, before);
}

// Two triangles that share a seam point by value but not by index (an authored mesh's texture seam):
// the seam vertices are welded, so after a projection that moves them they stay on one point.
TEST(StrainLimit, SeamsStayClosed) {
    // Triangle A (0, 1, 2) and triangle B (3, 4, 5); 3 duplicates 1 and 4 duplicates 2.
    std::vector<glm::vec3> bind = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    const std::vector<uint32_t> indices = {0, 1, 2, 3, 5, 4};
    const SkinEdges e = build_skin_edges(indices, bind);
    EXPECT_EQ(e.rest.size(), 5u);  // the shared edge once
    EXPECT_EQ(e.copies.size(), 4u);
    std::vector<glm::vec3> p = bind;
    p[5] = glm::vec3(6.0f, 6.0f, 0.0f);  // B's far corner pulled: B's edges stretched ~5x
    p[3] += glm::vec3(0.0f, 0.0f, 0.01f);  // the duplicates placed a little apart, as blending may
    const StrainLimitResult r = StrainLimitJob{&e, StrainLimits{0.55f, 1.8f, 64}, p}.Run();
    EXPECT_GT(r.projected, 0u);
    EXPECT_EQ(p[3], p[1]);
    EXPECT_EQ(p[4], p[2]);
}

TEST(StrainLimit, ValidateListsEveryProblem) {
    const Strip s(1);
    const SkinEdges e = build_skin_edges(s.indices, s.bind);
    std::vector<glm::vec3> too_few(2);
    std::vector<std::string> errors;
    EXPECT_FALSE((StrainLimitJob{&e, StrainLimits{0.0f, 0.5f, 4}, too_few}.Validate(&errors)));
    EXPECT_EQ(errors.size(), 5u);  // an end outside, adjacency for another surface, lo, hi, accepted bounds
    errors.clear();
    EXPECT_FALSE((StrainLimitJob{nullptr, StrainLimits{}, too_few}.Validate(&errors)));
    EXPECT_EQ(errors.size(), 1u);
}

}  // namespace
}  // namespace aloha
