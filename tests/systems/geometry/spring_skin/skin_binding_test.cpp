// Mesh binding: a synthetic mesh around a synthetic muscle follows the muscle's bulge.
#include "systems/geometry/spring_skin/skin_binding.hpp"
#include "tests/systems/geometry/spring_skin/test_grids.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace aloha {
namespace {

constexpr uint32_t kT = 16, kP = 10;
constexpr float kR = 0.1f;

// A mesh shell (different tessellation, tilted) 3 cm outside a sphere muscle, plus a second muscle.
struct BindScene {
    test::Grids muscles;
    std::vector<glm::vec3> mesh;
    std::vector<SkinBinding> bindings;
};

BindScene bind_setup() {
    BindScene s;
    test::append_ellipsoid(s.muscles, kT, kP, glm::vec3(kR));
    test::append_ellipsoid(s.muscles, kT, kP, glm::vec3(kR), glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0, 0)));
    const test::Grids shell = test::ellipsoid(21, 9, glm::vec3(kR + 0.03f), glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(1, 1, 0)));
    s.mesh = shell.positions;
    s.bindings.resize(s.mesh.size());
    SkinBindJob bind{kT, kP, s.muscles.positions, s.muscles.normals, s.mesh, s.bindings};
    std::vector<std::string> errors;
    EXPECT_TRUE(bind.Validate(&errors)) << (errors.empty() ? "" : errors.front());
    bind.Run();
    return s;
}

std::vector<glm::vec3> place(const BindScene& s, const test::Grids& muscles, uint32_t T, uint32_t P) {
    std::vector<glm::vec3> out(s.bindings.size());
    BoundSkinJob job{T, P, 2, muscles.positions, muscles.normals, s.bindings, out};
    std::vector<std::string> errors;
    EXPECT_TRUE(job.Validate(&errors)) << (errors.empty() ? "" : errors.front());
    job.Run();
    return out;
}

TEST(SkinBinding, BindPoseReproducesTheMesh) {
    const BindScene s = bind_setup();
    for (const SkinBinding& b : s.bindings) EXPECT_EQ(b.muscle, 0u);  // the far muscle is never nearest
    const std::vector<glm::vec3> out = place(s, s.muscles, kT, kP);
    // The offset is expressed in the same frame it is evaluated in: exact up to float rounding
    // of ~0.13 m coordinates through a 3x3 change of basis.
    for (size_t i = 0; i < out.size(); ++i) EXPECT_NEAR(glm::length(out[i] - s.mesh[i]), 0.0f, 2e-6f) << i;
}

TEST(SkinBinding, UniformBulgeMovesEveryVertexOutward) {
    const BindScene s = bind_setup();
    test::Grids bulged;
    test::append_ellipsoid(bulged, kT, kP, glm::vec3(1.2f * kR));
    test::append_ellipsoid(bulged, kT, kP, glm::vec3(kR), glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0, 0)));
    const std::vector<glm::vec3> out = place(s, bulged, kT, kP);
    // Scaling the sphere by 1.2 scales the sampled point q by 1.2 and leaves normals and tangent
    // directions unchanged, so each vertex moves by exactly 0.2 q. q is a convex combination of one
    // grid cell's corners, so |q| >= R cos(cell diagonal) >= 0.85 R here (diagonal
    // sqrt((2 pi / 16)^2 + (pi / 10)^2) = 0.50 rad), and q points within that angle of the vertex.
    for (size_t i = 0; i < out.size(); ++i) {
        const glm::vec3 move = out[i] - s.mesh[i];
        const float outward = glm::dot(move, glm::normalize(s.mesh[i]));
        EXPECT_GE(outward, 0.2f * 0.85f * 0.85f * kR) << i;
        EXPECT_LE(glm::length(move), 0.2f * kR * (1.0f + 1e-4f)) << i;
    }
}

TEST(SkinBinding, VolumePreservingBulgeSwellsTheBellyAndPullsInThePoles) {
    const BindScene s = bind_setup();
    test::Grids bulged;
    test::append_ellipsoid(bulged, kT, kP, {1.25f * kR, 1.25f * kR, kR / (1.25f * 1.25f)});
    test::append_ellipsoid(bulged, kT, kP, glm::vec3(kR), glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0, 0)));
    const std::vector<glm::vec3> out = place(s, bulged, kT, kP);
    int belly = 0, poles = 0;
    for (size_t i = 0; i < out.size(); ++i) {
        const glm::vec3 v = s.mesh[i];
        const float sin_lat = v.z / glm::length(v);
        if (std::abs(sin_lat) < 0.3f) {  // near the equator: pushed outward radially in x-y
            ++belly;
            EXPECT_GT(glm::length(glm::vec2(out[i])), glm::length(glm::vec2(v)) + 0.01f) << i;
        } else if (std::abs(sin_lat) > 0.95f) {  // near the poles: pulled in along z
            ++poles;
            EXPECT_LT(std::abs(out[i].z), std::abs(v.z) - 0.01f) << i;
        }
    }
    EXPECT_GT(belly, 10);
    EXPECT_GT(poles, 1);
}

TEST(SkinBinding, EvaluatesOnAnotherTessellation) {
    const BindScene s = bind_setup();
    test::Grids fine;
    test::append_ellipsoid(fine, 40, 24, glm::vec3(kR));
    test::append_ellipsoid(fine, 40, 24, glm::vec3(kR), glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0, 0)));
    const std::vector<glm::vec3> out = place(s, fine, 40, 24);
    // The two tessellations of the sphere differ by at most the coarse chord sag,
    // R (1 - cos(0.5 / 2)) = 3.1 mm, plus the 3 cm offset turned by the normal difference
    // (< 0.25 rad -> 7.5 mm): 11 mm.
    for (size_t i = 0; i < out.size(); ++i) EXPECT_LT(glm::length(out[i] - s.mesh[i]), 0.011f) << i;
}

TEST(SkinBinding, ValidateNamesBadInput) {
    const test::Grids m = test::ellipsoid(kT, kP, glm::vec3(kR));
    std::vector<glm::vec3> mesh{{0, 0, 0}, {std::nanf(""), 0, 0}};
    std::vector<SkinBinding> bindings(1);
    SkinBindJob bind{kT, kP, m.positions, {}, mesh, bindings};
    std::vector<std::string> errors;
    EXPECT_FALSE(bind.Validate(&errors));
    ASSERT_EQ(errors.size(), 3u);  // normals, bindings size, vertex 1 not finite
    EXPECT_NE(errors[2].find("vertex 1"), std::string::npos);
}

}  // namespace
}  // namespace aloha
