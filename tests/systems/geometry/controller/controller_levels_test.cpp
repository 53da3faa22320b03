// GeometryController on the built-in humanoid: counts per level, every method's output, slot reuse,
// rule reload.
#include "systems/geometry/surface_grid.hpp"
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

using test::humanoid;

TEST(GeometryController, HumanoidLoads) {
    ASSERT_NE(humanoid().geometry, nullptr);
    EXPECT_EQ(humanoid().geometry->joint_count(), 31u);
    EXPECT_EQ(humanoid().geometry->muscle_count(), 54u);
}

TEST(GeometryController, CountsFollowTheOneParameter) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    const auto levels = test::test_levels();
    GeometryController ctl(g, levels, 4);
    const uint32_t M = g.muscle_count();
    // The continuous skin at (T, P) has M * V(T, P) triangles (the simplification's target, reached
    // exactly: both counts are even). The edge collapses keep the dense surface's topology, so every
    // resolution has the same Euler characteristic chi = V - E + F = V - F/2 (E = 3F/2 on a closed
    // surface); the skinned level at the same (T, P) shows the same skin.
    const uint32_t f16 = M * grid_vertex_count(16, 12), f8 = M * grid_vertex_count(8, 6);
    EXPECT_EQ(ctl.level_indices(1).size(), 3u * f16);
    EXPECT_EQ(ctl.level_indices(2).size(), 3u * f8);
    const int chi = static_cast<int>(ctl.vertices_per_character(1)) - static_cast<int>(f16 / 2);
    EXPECT_EQ(static_cast<int>(ctl.vertices_per_character(2)) - static_cast<int>(f8 / 2), chi);
    EXPECT_EQ(chi % 2, 0);
    EXPECT_LE(chi, 2);  // one connected closed surface: chi = 2 - 2 genus
    EXPECT_EQ(ctl.vertices_per_character(3), ctl.vertices_per_character(2));
    EXPECT_EQ(ctl.level_indices(3).size(), ctl.level_indices(2).size());
    // One Catmull-Clark step of a closed triangle mesh adds a point per edge and per face:
    // V + 3F/2 + F = 3F + chi, each triangle becoming three quads (six triangles).
    EXPECT_EQ(static_cast<int>(ctl.vertices_per_character(0)), static_cast<int>(3u * f8) + chi);
    EXPECT_EQ(ctl.level_indices(0).size(), 18u * f8);
    EXPECT_EQ(ctl.vertices_per_character(4), 0u);
    EXPECT_EQ(ctl.vertices_per_character(5), 0u);
    EXPECT_TRUE(ctl.level_indices(4).empty());
    // Memory is affine in the counts: per muscle grid vertex a Layered level stores muscle position +
    // normal (muscle -> spring_skin, 24 bytes); per skin vertex spring end + velocity + previous rest,
    // morph position + offset and a skin normal = 6 vec3 = 72 bytes; the per-muscle and per-joint
    // parts are the same at both levels.
    const size_t dv = size_t{M} * (grid_vertex_count(16, 12) - grid_vertex_count(8, 6));
    const size_t dn = size_t{ctl.vertices_per_character(1)} - ctl.vertices_per_character(2);
    EXPECT_EQ(ctl.bytes_per_character(1) - ctl.bytes_per_character(2), 24u * dv + 72u * dn);
    EXPECT_GT(ctl.bytes_per_character(2), ctl.bytes_per_character(3));  // peeling drops muscles and springs
    EXPECT_GT(ctl.bytes_per_character(3), ctl.bytes_per_character(4));
    EXPECT_EQ(ctl.bytes_per_character(4), 31u * sizeof(glm::mat4) + 7u);  // boxes + morph counters/flags
}

TEST(GeometryController, EveryMethodGivesFiniteOutputOfTheRightSize) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    const auto levels = test::test_levels();
    GeometryController ctl(g, levels, levels.size());
    for (uint8_t l = 0; l < levels.size(); ++l) ctl.begin_level(l, l, -1, 0);
    for (size_t frame = 0; frame < 4; ++frame) {
        const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, 100 + 10 * frame);
        const PoseSource src{pose.data(), 0};  // every character shares the pose
        for (uint8_t l = 0; l < levels.size(); ++l) {
            const uint32_t c = l;
            ctl.update(l, std::span(&c, 1), src, 1.0f / 30.0f);
        }
    }
    for (uint8_t l = 0; l < levels.size(); ++l) {
        SCOPED_TRACE(static_cast<int>(l));
        const SurfaceView view = ctl.surface(l);
        EXPECT_EQ(view.level, l);
        EXPECT_EQ(view.topology_key, (3u << 16) | l);
        ASSERT_EQ(view.positions.size(), ctl.vertices_per_character(l));
        ASSERT_EQ(view.normals.size(), view.positions.size());
        for (size_t i = 0; i < view.positions.size(); ++i) {
            ASSERT_TRUE(test::finite(view.positions[i])) << i;
            // Unit normals: normalised in float, |n| = 1 within a few ulp (1e-5).
            ASSERT_NEAR(glm::length(view.normals[i]), 1.0f, 1e-5f) << i;
        }
        for (const uint32_t i : ctl.level_indices(l)) ASSERT_LT(i, view.positions.size());
    }
    // Rigid proxies: one box per joint, centred between the joint and its parent.
    const auto boxes = ctl.proxy_boxes(4);
    ASSERT_EQ(boxes.size(), 31u);
    const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, 130);
    for (size_t j = 1; j < boxes.size(); ++j) {
        const auto parent = static_cast<size_t>(g.skeleton().parents()[j]);
        const glm::vec3 mid = 0.5f * (glm::vec3(pose[j][3]) + glm::vec3(pose[parent][3]));
        EXPECT_LT(glm::length(glm::vec3(boxes[j][3]) - mid), 1e-5f) << j;  // float rounding at ~1 m
    }
    EXPECT_TRUE(ctl.proxy_boxes(2).empty());
    EXPECT_TRUE(ctl.surface(4).positions.empty());
    EXPECT_TRUE(ctl.surface(5).positions.empty());
    std::vector<glm::vec3> muscles;
    ctl.muscle_surface(1, muscles);
    EXPECT_EQ(muscles.size(), g.muscle_count() * grid_vertex_count(16, 12));
}

TEST(GeometryController, SlotReuseKeepsMemoryFlat) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    const auto levels = test::test_levels();
    GeometryController ctl(g, levels, 16);
    const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, 0);
    const PoseSource src{pose.data(), 0};
    std::vector<uint32_t> slots_after_first;
    size_t memory_after_first = 0;
    for (int cycle = 0; cycle < 40; ++cycle) {
        // Every character walks through levels 1 -> 2 -> 3 -> 4 -> 2, staggered so levels mix.
        for (uint32_t c = 0; c < 16; ++c) {
            const uint8_t seq[5] = {1, 2, 3, 4, 2};
            const uint8_t l = seq[(static_cast<uint32_t>(cycle) + c) % 5];
            ctl.begin_level(c, l, static_cast<int8_t>(ctl.level_of(c) == GeometryController::kNoLevel ? -1 : ctl.level_of(c)), 4);
            ctl.update(l, std::span(&c, 1), src, 1.0f / 30.0f);
        }
        if (cycle % 7 == 3) ctl.end_character(5);  // despawns and respawns too
        // A cycle lasts longer than a switch's fade (mesh <-> mesh switches of different surfaces keep the left
        // level's slot while fading, over the 4 frames given): the kept slots are released before counting.
        for (int frame = 0; frame < 4; ++frame) ctl.advance_fades();
        uint32_t total = 0;
        for (uint8_t l = 0; l < levels.size(); ++l) total += ctl.characters_at(l);
        EXPECT_EQ(total, cycle % 7 == 3 ? 15u : 16u);
        if (cycle == 4) {  // every character has visited every level of the cycle once
            for (uint8_t l = 0; l < levels.size(); ++l) slots_after_first.push_back(ctl.slot_capacity(l));
            memory_after_first = ctl.memory_bytes();
        }
        if (cycle > 4) {
            for (uint8_t l = 0; l < levels.size(); ++l) EXPECT_EQ(ctl.slot_capacity(l), slots_after_first[l]) << int(l);
            EXPECT_EQ(ctl.memory_bytes(), memory_after_first);
        }
    }
    // No level ever needs more slots than characters it held at once (16, rounded up to its page).
    for (uint8_t l = 0; l < levels.size(); ++l) {
        const uint32_t page = ctl.slots_per_page(l);
        EXPECT_LE(ctl.slot_capacity(l), (16u + page - 1) / page * page) << int(l);
    }
}

TEST(GeometryController, SetLevelsKeepsCharactersAndRebuildsWhatChanged) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    auto levels = test::test_levels();
    GeometryController ctl(g, levels, 6);
    for (uint8_t l = 0; l < levels.size(); ++l) ctl.begin_level(l, l, -1, 0);
    const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, 50);
    const PoseSource src{pose.data(), 0};
    for (uint32_t c = 0; c < levels.size(); ++c) ctl.update(static_cast<uint8_t>(c), std::span(&c, 1), src, 1.0f / 30.0f);
    const std::vector<glm::vec3> before(ctl.surface(1).positions.begin(), ctl.surface(1).positions.end());
    const uint32_t key1 = ctl.topology_key(1), key2 = ctl.topology_key(2);

    levels[2].theta_steps = 12;   // changes storage and topology
    levels[1].geomorph_s = 0.15f; // does not
    levels.pop_back();            // Hidden level removed: its character moves to the new last level
    ctl.set_levels(levels);
    EXPECT_EQ(ctl.topology_key(1), key1);
    EXPECT_NE(ctl.topology_key(2), key2);
    EXPECT_EQ(ctl.level(1).geomorph_s, 0.15f);
    EXPECT_EQ(ctl.level_of(2), 2);
    EXPECT_EQ(ctl.level_of(5), 4);
    EXPECT_EQ(ctl.vertices_per_character(2), g.skin_layer(12, 6).rest_positions.size());
    EXPECT_EQ(ctl.level_indices(2).size(), 3u * g.muscle_count() * grid_vertex_count(12, 6));
    // The kept level keeps the character's surface untouched.
    const auto after = ctl.surface(1).positions;
    ASSERT_EQ(after.size(), before.size());
    EXPECT_EQ(test::max_distance(after, before), 0.0f);
    // The rebuilt level works with its new size.
    const uint32_t c2 = 2;
    ctl.update(2, std::span(&c2, 1), src, 1.0f / 30.0f);
    EXPECT_EQ(ctl.surface(2).positions.size(), ctl.vertices_per_character(2));
}

}  // namespace
}  // namespace aloha
