// Skin: one (T, P) sets muscle vertices, springs and skin vertices together; skin normals.
#include "systems/geometry/spring_skin/fat_spring.hpp"
#include "systems/geometry/spring_skin/skin_mesh.hpp"
#include "tests/systems/geometry/spring_skin/test_grids.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace aloha {
namespace {

// Runs springs (one frame, i.e. at rest) and skin normals for `muscles` ellipsoids at (T, P).
struct SkinRun {
    test::Grids muscles;
    std::vector<float> thickness;
    std::vector<glm::vec3> skin_normals;
    std::vector<uint32_t> indices;
    size_t springs = 0;
    std::vector<glm::vec3> skin_positions;
};

SkinRun run_skin(uint32_t T, uint32_t P, uint32_t muscles, float h) {
    SkinRun run;
    for (uint32_t m = 0; m < muscles; ++m)
        test::append_ellipsoid(run.muscles, T, P, {0.05f, 0.05f, 0.1f},
                               glm::translate(glm::mat4(1.0f), glm::vec3(0.3f * static_cast<float>(m), 0, 0)));
    run.thickness.assign(muscles, h);
    FatSpringPool pool(1, muscles, T, P);
    FatSpringJob springs;
    springs.theta_steps = T;
    springs.phi_steps = P;
    springs.muscle_positions = run.muscles.positions;
    springs.muscle_normals = run.muscles.normals;
    springs.thickness = run.thickness;
    springs.state = pool.view(0, 1);
    EXPECT_TRUE(springs.Validate());
    springs.Run();
    run.springs = pool.springs_per_character();
    run.skin_positions.assign(springs.state.end.begin(), springs.state.end.end());
    run.skin_normals.resize(run.skin_positions.size());
    SkinJob skin;
    skin.theta_steps = T;
    skin.phi_steps = P;
    skin.positions = run.skin_positions;
    skin.fallback_normals = run.muscles.normals;
    skin.normals = run.skin_normals;
    EXPECT_TRUE(skin.Validate());
    skin.Run();
    run.indices = build_skin_indices(T, P, muscles);
    return run;
}

TEST(Skin, OneParameterSetsMuscleSpringAndSkinCounts) {
    const uint32_t muscles = 3;
    for (uint32_t T : {4u, 8u, 16u, 32u}) {
        const uint32_t P = T / 2 + 1;
        const SkinRun run = run_skin(T, P, muscles, 0.01f);
        const size_t muscle_vertices = run.muscles.positions.size();
        EXPECT_EQ(muscle_vertices, size_t{muscles} * grid_vertex_count(T, P));
        // One spring per muscle vertex and one skin vertex per spring: ratio exactly 1.
        EXPECT_EQ(run.springs, muscle_vertices);
        EXPECT_EQ(run.skin_positions.size(), muscle_vertices);
        EXPECT_EQ(run.skin_normals.size(), muscle_vertices);
        EXPECT_EQ(run.indices.size(), size_t{3} * muscles * grid_triangle_count(T, P));
        for (uint32_t index : run.indices) EXPECT_LT(index, muscle_vertices);
    }
}

TEST(Skin, SkinSitsOneThicknessOutAndNormalsPointOutward) {
    const uint32_t T = 24, P = 12;
    const float h = 0.01f;
    const SkinRun run = run_skin(T, P, 2, h);
    // Normal error bound: every triangle around a vertex spans at most one theta step
    // (2 pi / T) and one phi step (pi / P), so its normal is within that angle of the surface normal
    // at the vertex for a smooth convex surface; the weighted average is too. The ellipsoid's
    // curvature varies across a face (axis ratio 2), so allow twice the larger step.
    const float step = std::max(2.0f * std::numbers::pi_v<float> / T, std::numbers::pi_v<float> / P);
    const float min_cos = std::cos(2.0f * step);
    for (size_t i = 0; i < run.skin_positions.size(); ++i) {
        const glm::vec3 rest = run.muscles.positions[i] + h * run.muscles.normals[i];
        EXPECT_NEAR(glm::length(run.skin_positions[i] - rest), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::length(run.skin_normals[i]), 1.0f, 1e-5f);
        EXPECT_GE(glm::dot(run.skin_normals[i], run.muscles.normals[i]), min_cos) << "vertex " << i;
    }
}

TEST(Skin, DegenerateGridFallsBackToMuscleNormals) {
    const uint32_t T = 6, P = 4, V = grid_vertex_count(T, P);
    std::vector<glm::vec3> collapsed(V, glm::vec3(1.0f, 2.0f, 3.0f));
    std::vector<glm::vec3> fallback(V, glm::vec3(0.0f, 1.0f, 0.0f)), normals(V);
    SkinJob skin{T, P, collapsed, fallback, normals};
    ASSERT_TRUE(skin.Validate());
    skin.Run();
    for (const glm::vec3& n : normals) EXPECT_EQ(n, glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(Skin, ValidateRejectsMismatchedSizes) {
    std::vector<glm::vec3> positions(10), normals(9);
    SkinJob skin{6, 4, positions, {}, normals};
    std::vector<std::string> errors;
    EXPECT_FALSE(skin.Validate(&errors));
    EXPECT_EQ(errors.size(), 2u);  // 10 is not a multiple of V(6, 4) = 20; normals size differs
}

}  // namespace
}  // namespace aloha
