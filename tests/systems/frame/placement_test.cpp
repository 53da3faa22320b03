// world_matrix: translation * rotation * uniform scale, the placement every draw item uses.
#include "systems/frame/placement.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

TEST(Placement, WorldMatrixScalesThenRotatesThenTranslates) {
    Transform t;
    t.position = glm::vec3(1.0f, 0.0f, -2.0f);
    t.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0));  // +X -> -Z
    t.scale = 1.5f;
    const glm::vec3 p = glm::vec3(world_matrix(t) * glm::vec4(2.0f, 1.0f, 0.0f, 1.0f));
    // (2, 1, 0) * 1.5 = (3, 1.5, 0); rotated to (0, 1.5, -3); moved to (1, 1.5, -5). Single-precision
    // trigonometry of a right angle: 1e-5 covers cos(pi/2) ~ 4e-8 times the 3 m lever.
    EXPECT_NEAR(p.x, 1.0f, 1e-5f);
    EXPECT_NEAR(p.y, 1.5f, 1e-5f);
    EXPECT_NEAR(p.z, -5.0f, 1e-5f);
}

}  // namespace
}  // namespace aloha
