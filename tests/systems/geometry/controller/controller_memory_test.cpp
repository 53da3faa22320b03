// GeometryController memory and stages: refined surfaces computed but not kept (runs with no
// renderer), the muscle surface handed from the muscle stage to the skin stage, the two stages
// against the one-call update, and allocating a level's slots at once.
#include "systems/geometry/spring_skin/grid_sample.hpp"
#include "systems/geometry/surface_grid.hpp"
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

using test::humanoid;

constexpr float kDt = 1.0f / 30.0f;

// Runs `frames` clip frames on character 0 of `ctl` at `level`.
void animate(GeometryController& ctl, uint8_t level, int first_frame, int frames) {
    const CharacterGeometry& g = *humanoid().geometry;
    const uint32_t c = 0;
    for (int f = first_frame; f < first_frame + frames; ++f) {
        const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, f);
        ctl.update(level, std::span(&c, 1), PoseSource{pose.data(), 0}, kDt);
    }
}

TEST(GeometryControllerMemory, RefinedSurfacesNotKeptSaveExactlyTheirBytesAndChangeNothingElse) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    const auto levels = test::test_levels();  // level 0: Subdivided (8, 6), one Catmull-Clark step
    GeometryController kept(g, levels, 1), dropped(g, levels, 1, /*keep_refined_surfaces=*/false);
    // The refined surface is two vec3 per refined vertex, and its geomorph offsets one more (a level
    // that keeps no refined surface does not morph); every other level is unaffected.
    EXPECT_EQ(kept.bytes_per_character(0) - dropped.bytes_per_character(0),
              size_t{kept.vertices_per_character(0)} * 3 * sizeof(glm::vec3));
    for (uint8_t l = 1; l < levels.size(); ++l) EXPECT_EQ(kept.bytes_per_character(l), dropped.bytes_per_character(l));
    EXPECT_EQ(kept.vertices_per_character(0), dropped.vertices_per_character(0));

    kept.begin_level(0, 0, -1, 0);
    dropped.begin_level(0, 0, -1, 0);
    animate(kept, 0, 40, 12);
    animate(dropped, 0, 40, 12);
    EXPECT_EQ(kept.surface(0).positions.size(), kept.vertices_per_character(0));
    EXPECT_TRUE(dropped.surface(0).positions.empty());
    EXPECT_TRUE(dropped.surface(0).normals.empty());
    EXPECT_EQ(dropped.surface(0).level, 0);

    // The state behind the skin (springs, control surface) is the same to the bit.
    const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, 51);
    const PoseSource src{pose.data(), 0};
    std::vector<glm::vec3> kept_control, dropped_control, ref;
    kept.deviation_pairs(src, 0, 1, kept_control, ref);
    dropped.deviation_pairs(src, 0, 1, dropped_control, ref);
    ASSERT_FALSE(kept_control.empty());
    ASSERT_EQ(kept_control.size(), dropped_control.size());
    EXPECT_EQ(test::max_distance(kept_control, dropped_control), 0.0f);

    // A morph out of the level starts from that state: both show the same surface afterwards.
    kept.begin_level(0, 1, 0, 6);
    dropped.begin_level(0, 1, 0, 6);
    animate(kept, 1, 52, 3);
    animate(dropped, 1, 52, 3);
    ASSERT_EQ(kept.surface(0).positions.size(), dropped.surface(0).positions.size());
    EXPECT_EQ(test::max_distance(kept.surface(0).positions, dropped.surface(0).positions), 0.0f);
    EXPECT_EQ(test::max_distance(kept.surface(0).normals, dropped.surface(0).normals), 0.0f);
}

TEST(GeometryControllerMemory, MuscleSurfaceIsWhatTheSpringsStandOn) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, test::test_levels(), 1);
    std::vector<glm::vec3> muscles{glm::vec3(1.0f)};
    ctl.muscle_surface(0, muscles);  // no level yet
    EXPECT_TRUE(muscles.empty());
    ctl.begin_level(0, 2, -1, 0);  // Layered (8, 6)
    muscles.assign(3, glm::vec3(1.0f));
    ctl.muscle_surface(0, muscles);  // not updated yet
    EXPECT_TRUE(muscles.empty());
    // One frame at the rest pose: the springs start at their rest ends, which at the bind pose are the
    // skin layer's vertices, and every influence of a vertex sits its bound offset away from its
    // muscle point sampled on the muscle surface the controller reports.
    const uint32_t c = 0;
    ctl.update(2, std::span(&c, 1), PoseSource{g.rest_model().data(), 0}, kDt);
    ctl.muscle_surface(0, muscles);
    const uint32_t V = grid_vertex_count(8, 6);
    ASSERT_EQ(muscles.size(), size_t{g.muscle_count()} * V);
    const SkinLayer& layer = g.skin_layer(8, 6);
    const auto skin = ctl.surface(0).positions;
    ASSERT_EQ(skin.size(), layer.rest_positions.size());
    for (size_t i = 0; i < skin.size(); ++i) {
        ASSERT_LT(glm::length(skin[i] - layer.rest_positions[i]), 1e-5f) << i;
        const BlendBinding& b = layer.bindings[i];
        for (int k = 0; k < kBlendInfluences; ++k) {
            if (b.weight[k] <= 0.0f) continue;
            const glm::vec3 point = sample_grid(std::span<const glm::vec3>(muscles).subspan(size_t{b.muscle[k]} * V, V), 8, 6, b.param[k]);
            ASSERT_NEAR(glm::length(skin[i] - point), glm::length(b.offset[k]), 1e-5f) << i << " influence " << k;
        }
    }
}

// update() is update_muscles() then update_skin(); running the stages as two passes over a list of
// characters (as the muscle and spring_skin systems do) gives the same bits.
TEST(GeometryControllerMemory, TwoStagesEqualOneUpdate) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    const auto levels = test::test_levels();
    GeometryController one(g, levels, levels.size()), two(g, levels, levels.size());
    for (uint8_t l = 0; l < levels.size(); ++l) {
        one.begin_level(l, l, -1, 0);
        two.begin_level(l, l, -1, 0);
    }
    for (int f = 0; f < 5; ++f) {
        const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, 30 + 3 * f);
        // Every character uses the same pose (PoseSource stride 0).
        const PoseSource src{pose.data(), 0};
        for (uint8_t l = 0; l < levels.size(); ++l) {
            const uint32_t c = l;
            one.update(l, std::span(&c, 1), src, kDt);
        }
        for (uint8_t l = 0; l < levels.size(); ++l) {
            const uint32_t c = l;
            two.update_muscles(l, std::span(&c, 1), src);
        }
        for (uint8_t l = 0; l < levels.size(); ++l) {
            const uint32_t c = l;
            two.update_skin(l, std::span(&c, 1), src, kDt);
        }
    }
    for (uint32_t c = 0; c < levels.size(); ++c) {
        const SurfaceView a = one.surface(c), b = two.surface(c);
        ASSERT_EQ(a.positions.size(), b.positions.size()) << c;
        EXPECT_EQ(test::max_distance(a.positions, b.positions), 0.0f) << c;
        EXPECT_EQ(test::max_distance(a.normals, b.normals), 0.0f) << c;
        const auto ba = one.proxy_boxes(c), bb = two.proxy_boxes(c);
        ASSERT_EQ(ba.size(), bb.size());
        for (size_t j = 0; j < ba.size(); ++j) EXPECT_EQ(ba[j], bb[j]) << c << " " << j;
    }
    // A muscle level shows nothing until its skin stage has run.
    GeometryController fresh(g, levels, 1);
    fresh.begin_level(0, 1, -1, 0);
    const uint32_t c = 0;
    const PoseSource rest{g.rest_model().data(), 0};
    fresh.update_muscles(1, std::span(&c, 1), rest);
    EXPECT_TRUE(fresh.surface(0).positions.empty());
    fresh.update_skin(1, std::span(&c, 1), rest, kDt);
    EXPECT_EQ(fresh.surface(0).positions.size(), fresh.vertices_per_character(1));
}

TEST(GeometryControllerMemory, ReserveAllocatesALevelOnce) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, test::test_levels(), 100);
    ctl.reserve(2, 100);
    const uint32_t page = ctl.slots_per_page(2);
    const uint32_t reserved = (100 + page - 1) / page * page;  // whole pages
    EXPECT_EQ(ctl.slot_capacity(2), reserved);
    const size_t bytes = ctl.memory_bytes();
    for (uint32_t c = 0; c < 100; ++c) ctl.begin_level(c, 2, -1, 0);
    EXPECT_EQ(ctl.slot_capacity(2), reserved);  // no growth past what was asked for
    // At most one spare page, prepared in the background once the free slots run low: a page is
    // `page` records, each a character's bytes padded to 16 bytes per buffer (16 buffers) and to 64.
    EXPECT_LE(ctl.memory_bytes(), bytes + size_t{page} * (ctl.bytes_per_character(2) + 16 * 15 + 63));
    ctl.reserve(2, 50);  // already room: nothing changes
    EXPECT_EQ(ctl.slot_capacity(2), reserved);
    EXPECT_EQ(ctl.characters_at(2), 100u);
}

}  // namespace
}  // namespace aloha
