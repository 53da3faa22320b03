// Impostor draw order (systems/render/impostor_order.hpp): each atlas's run stays in place, nearest first.
#include "systems/render/impostor_order.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace aloha {
namespace {

TEST(ImpostorOrder, EachAtlasRunIsSortedNearestFirstInPlace) {
    // Camera at the origin looking down -Z: the distance ahead is -z. Runs: atlas 3 (three quads), atlas 1 (two).
    const glm::mat4 view = glm::lookAt(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    const float z[5] = {-30.0f, -10.0f, -30.0f, -5.0f, -50.0f};
    const uint32_t atlas[5] = {3, 3, 3, 1, 1};
    std::vector<ImpostorInstance> in(5);
    for (uint32_t i = 0; i < 5; ++i) {
        in[i].position_scale = glm::vec4(float(i), 0.0f, z[i], 1.0f);  // x tells the input position
        in[i].atlas = atlas[i];
    }
    std::vector<uint32_t> order;
    std::vector<float> depth;
    sort_impostors_nearest_first(in, view, order, depth);
    ASSERT_EQ(order.size(), 5u);
    for (uint32_t i = 0; i < 5; ++i) EXPECT_EQ(depth[i], -z[i]) << "distance ahead of input " << i;
    std::vector<ImpostorInstance> out(5);
    for (uint32_t k = 0; k < 5; ++k) out[k] = in[order[k]];
    // Atlas 3: 10 m (input 1), then the two at 30 m in input order (0, 2); atlas 1: 5 m (3), 50 m (4).
    const float expected_x[5] = {1.0f, 0.0f, 2.0f, 3.0f, 4.0f};
    for (uint32_t k = 0; k < 5; ++k) {
        EXPECT_EQ(out[k].position_scale.x, expected_x[k]) << "position " << k;
        EXPECT_EQ(out[k].atlas, atlas[k]) << "runs stay where they were";
    }
}

}  // namespace
}  // namespace aloha
