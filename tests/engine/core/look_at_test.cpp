// look_at_y_up: glm::lookAt with +Y up wherever that is defined, and a finite view straight up and down, the limit of
// tilting a camera that faces -Z.
#include "engine/core/look_at.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// Largest difference between two matrices' entries.
float max_difference(const glm::mat4& a, const glm::mat4& b) {
    float d = 0.0f;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) d = std::max(d, std::abs(a[c][r] - b[c][r]));
    return d;
}

// The rotation part is orthonormal and right-handed and the target lies on the view's -Z axis. Tolerance: a few float
// roundings of unit vectors (1e-6) with margin.
void expect_view_of(const glm::mat4& view, glm::vec3 eye, glm::vec3 target) {
    ASSERT_TRUE(finite(view));
    const glm::mat3 r(view);
    EXPECT_NEAR(glm::determinant(r), 1.0f, 1e-5f);
    const glm::mat3 rrt = r * glm::transpose(r);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(rrt[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
    const glm::vec4 t = view * glm::vec4(target, 1.0f);
    const float distance = glm::length(target - eye);
    EXPECT_NEAR(t.x, 0.0f, 1e-5f * distance);
    EXPECT_NEAR(t.y, 0.0f, 1e-5f * distance);
    EXPECT_NEAR(t.z, -distance, 1e-5f * distance);
}

TEST(LookAtYUp, EqualsGlmLookAtWhereThatIsDefined) {
    const glm::vec3 eye{3.0f, 6.0f, 42.0f}, target{-1.0f, 0.5f, 0.0f};
    // The direction is normalised first, so entries differ by rounding: a few ulp of the 42 m translation (4e-6 each).
    EXPECT_LT(max_difference(look_at_y_up(eye, target), glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f))), 3e-5f);
    expect_view_of(look_at_y_up(eye, target), eye, target);
}

TEST(LookAtYUp, StraightDownIsFiniteWithWorldMinusZUpOnScreen) {
    const glm::vec3 eye{2.0f, 30.0f, -5.0f}, target{2.0f, 0.0f, -5.0f};
    EXPECT_FALSE(finite(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f))));  // what a top-down camera got
    const glm::mat4 view = look_at_y_up(eye, target);
    expect_view_of(view, eye, target);
    // Screen right is world +X, screen up world -Z.
    EXPECT_NEAR(view[0][0], 1.0f, 1e-6f);
    EXPECT_NEAR(view[2][1], -1.0f, 1e-6f);
}

TEST(LookAtYUp, StraightUpIsFiniteWithWorldPlusZUpOnScreen) {
    const glm::vec3 eye{0.0f, 0.5f, 0.0f}, target{0.0f, 30.0f, 0.0f};
    const glm::mat4 view = look_at_y_up(eye, target);
    expect_view_of(view, eye, target);
    EXPECT_NEAR(view[0][0], 1.0f, 1e-6f);
    EXPECT_NEAR(view[2][1], 1.0f, 1e-6f);
}

// A camera tilted from facing -Z towards vertical ends in the vertical view: no roll jump where the up hint changes.
// The entries of the tilted view differ from the vertical one's by O(angle off vertical) (sin and 1 - cos of it).
TEST(LookAtYUp, TiltingTowardsVerticalConvergesToTheVerticalView) {
    const glm::vec3 target{0.0f};
    const glm::mat4 down = look_at_y_up({0.0f, 30.0f, 0.0f}, target), up = look_at_y_up({0.0f, -30.0f, 0.0f}, target);
    for (float angle : {1e-1f, 1e-2f, 2e-3f}) {  // radians off vertical, on the side the camera comes from (+Z)
        const glm::vec3 above{0.0f, 30.0f * std::cos(angle), 30.0f * std::sin(angle)};
        const glm::vec3 below{0.0f, -30.0f * std::cos(angle), 30.0f * std::sin(angle)};
        // Rotation entries move by at most the angle; the translation (eye in view space, 30 m) by 30 x the angle.
        EXPECT_LT(max_difference(look_at_y_up(above, target), down), 30.0f * angle * 1.01f + 1e-4f) << angle;
        EXPECT_LT(max_difference(look_at_y_up(below, target), up), 30.0f * angle * 1.01f + 1e-4f) << angle;
    }
}

TEST(LookAtYUp, TargetAtTheEyeLooksAlongMinusZ) {
    const glm::vec3 eye{1.0f, 2.0f, 3.0f};
    const glm::mat4 view = look_at_y_up(eye, eye);
    expect_view_of(view, eye, eye + glm::vec3(0.0f, 0.0f, -1.0f));
}

}  // namespace
}  // namespace aloha
