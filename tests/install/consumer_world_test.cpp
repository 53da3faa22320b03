// The install consumer's frame path (tests/install/consumer/main.cpp: a game with its own entity store
// calling the frame glue) against the World on the same scene: the same per-character levels and the
// same skin vertices, frame after frame. Both run the same jobs on the same data; the World's parallel
// chunks are bit-identical to serial (scheduler contract), so the comparison is exact.
#define MINI_GAME_NO_MAIN
#include "tests/install/consumer/main.cpp"

#include "host/scene/world.hpp"

#include <gtest/gtest.h>

#include <set>

namespace aloha {
namespace {

const std::string kScene = std::string(ALOHA_SOURCE_DIR) + "/tests/install/consumer/mini_game.json";

TEST(InstallConsumer, SameLevelsAndSkinAsTheWorld) {
    MiniGame game;
    const Status loaded = game.load(kScene);
    ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
    WorldOptions o;
    o.threads = 2;
    o.occlusion = false;  // the consumer runs no occlusion estimate
    // Nor the World's pose-use saving (poses nobody reads, e.g. impostors', are left stale and posed
    // fresh when seen again): the consumer poses every character every frame, so the World does too.
    o.pose_every_character = true;
    auto made = World::create(game.scene, o);
    ASSERT_TRUE(made.ok()) << made.error().to_string();
    World& world = *made.value();
    ASSERT_EQ(world.character_count(), game.refs.size());
    ASSERT_EQ(world.type_count(), game.types.size());
    ASSERT_GE(game.types.size(), 2u);  // two body variants: grouping by type is exercised

    std::set<uint8_t> levels_seen;
    size_t vertices_compared = 0;
    for (uint32_t f = 0; f < game.scene.frames; ++f) {
        game.step();
        world.step();
        auto group = character_group(world.registry());
        const auto states = group.span<LodState>();
        for (size_t e = 0; e < game.refs.size(); ++e) {
            const CharacterRef ref = game.refs[e];
            const CharacterRuntime& rt = world.runtime(ref.type);
            const LodState& w = states[rt.element_of_character[ref.id]];
            ASSERT_EQ(game.lod[e].geom_level, w.geom_level) << "frame " << f << " character " << e;
            ASSERT_EQ(game.lod[e].anim_level, w.anim_level) << "frame " << f << " character " << e;
            levels_seen.insert(w.geom_level);
            const SurfaceView mine = game.types[ref.type]->geometry->surface(ref.id);
            const SurfaceView theirs = rt.geometry->surface(ref.id);
            ASSERT_EQ(mine.positions.size(), theirs.positions.size()) << "frame " << f << " character " << e;
            for (size_t v = 0; v < mine.positions.size(); ++v)
                ASSERT_EQ(mine.positions[v], theirs.positions[v]) << "frame " << f << " character " << e << " vertex " << v;
            vertices_compared += mine.positions.size();
        }
    }
    EXPECT_GE(levels_seen.size(), 4u) << "the scene should show several geometric levels";
    EXPECT_TRUE(levels_seen.count(0) || levels_seen.count(1)) << "and a layered (muscle, spring) level";
    EXPECT_GT(vertices_compared, 0u);
}

}  // namespace
}  // namespace aloha
