// Layer peeling as data: a Layered level without the `fat` layer runs no fat springs (no spring state
// is kept and none is stepped: GeometryController::work counts them) and shows the skin at the springs'
// rest ends, while the same level with all four layers shows the springs' lag after a sudden move.
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

TEST(GeometryControllerLayers, WithoutFatNoSpringsAreRunAndTheSkinSitsAtRest) {
    const auto& h = test::humanoid();
    ASSERT_NE(h.geometry, nullptr);
    const CharacterGeometry& g = *h.geometry;
    std::vector<GeomLod> levels = {test::grid_level(GeomMethod::Layered, 8, 6), test::grid_level(GeomMethod::Layered, 8, 6)};
    levels[1].layers = kLayerSkeleton | kLayerMuscle | kLayerSkin;  // fat peeled off
    levels[1].level = 1;
    GeometryController ctl(g, levels, 2);
    ctl.begin_level(0, 0, -1, 0);
    ctl.begin_level(1, 1, -1, 0);
    // What is computed: the spring state (end, velocity, previous rest: 3 vec3 per skin vertex, plus
    // one flag, and the placement they last stepped at with its flag) exists only with the fat layer.
    const size_t vertices = ctl.vertices_per_character(0);
    ASSERT_EQ(ctl.vertices_per_character(1), vertices);
    EXPECT_EQ(ctl.bytes_per_character(0) - ctl.bytes_per_character(1), vertices * 3 * sizeof(glm::vec3) + 1 + sizeof(Transform) + 1);

    // What is displayed: walk a few frames, then jump the pose far ahead in the clip (a sudden change).
    const uint32_t both[2] = {0, 1};
    for (size_t key = 0; key < 10; ++key) {
        const auto pose = test::clip_pose(g.skeleton(), h.clip, key);
        std::vector<glm::mat4> two(pose);
        two.insert(two.end(), pose.begin(), pose.end());
        const PoseSource src{two.data(), pose.size()};
        ctl.update(0, std::span(both, 1), src, 1.0f / 30.0f);
        ctl.update(1, std::span(both + 1, 1), src, 1.0f / 30.0f);
    }
    // What is computed, counted: over those 10 frames the level with fat updated one spring per skin
    // vertex per frame, the level without none; both placed every skin vertex every frame.
    const GeometryWork with = ctl.work(0), without = ctl.work(1);
    EXPECT_EQ(with.characters, 10u);
    EXPECT_EQ(without.characters, 10u);
    EXPECT_EQ(with.springs_stepped, 10u * vertices);
    EXPECT_EQ(without.springs_stepped, 0u);
    EXPECT_EQ(with.skin_vertices, 10u * vertices);
    EXPECT_EQ(without.skin_vertices, 10u * vertices);
    ctl.reset_work();
    EXPECT_EQ(ctl.work(0).springs_stepped, 0u);
    const auto jump = test::clip_pose(g.skeleton(), h.clip, 25);
    const PoseSource src{jump.data(), 0};
    ctl.update(0, std::span(both, 1), src, 1.0f / 30.0f);
    ctl.update(1, std::span(both + 1, 1), src, 1.0f / 30.0f);
    std::vector<glm::vec3> rest_ends;
    ctl.reference_surface(src, 1, 1, rest_ends);
    // Without fat the skin is exactly the rest ends (same computation, same order: bit-equal).
    EXPECT_EQ(test::max_distance(ctl.surface(1).positions, rest_ends), 0.0f);
    // With fat the springs lag behind the jump: the skin is off its rest ends, by at most the strain
    // limit max_strain * h, where a spring's rest length h = |sum_k w_k F_k o_k| <= sum_k w_k |o_k|
    // (the blended offsets of its binding, frames orthonormal).
    float h_max = 0.0f;
    for (const BlendBinding& b : g.skin_layer(8, 6).bindings) {
        float length = 0.0f;
        for (int k = 0; k < kBlendInfluences; ++k) length += b.weight[k] * glm::length(b.offset[k]);
        h_max = std::max(h_max, length);
    }
    const float lag = test::max_distance(ctl.surface(0).positions, rest_ends);
    EXPECT_GT(lag, 1e-4f);
    EXPECT_LE(lag, ctl.spring_params().max_strain * h_max * (1.0f + 1e-4f));
}

}  // namespace
}  // namespace aloha
