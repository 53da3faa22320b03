// Walkers seen again after walking unseen (impostor level: their clip pose left stale) keep their feet on the
// ground: a crowd the camera flies into, from far away (every walker an impostor) to among them (skinned and
// layered walkers), must never show a drawn walker with a foot lifted higher than any gait lifts one. Before the
// foot lock started afresh on such characters (systems/motion/foot_lock.hpp), crowd_10k's close pass drew dozens
// of walkers with both legs stretched out behind them at hip height.
#include "host/scene/character_runtime.hpp"
#include "host/scene/motion_sample.hpp"
#include "host/scene/scene_loader.hpp"
#include "host/scene/world.hpp"
#include "tests/host/scene/world_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace aloha {
namespace {

// 150 walkers on a 25 m disc; the camera comes from 120 m away to 8 m from the centre over 3 s, then holds.
SceneDesc fly_in_scene() {
    return scene_test::scene_from_json(R"({
      "name": "fly_in", "rules": "builtin:default", "frames": 360, "dt": 0.0166667,
      "viewport": {"width": 1280, "height": 720},
      "camera": {"fov_deg": 55, "far": 1000, "keys": [
        {"time": 0, "position": [0, 30, 120], "target": [0, 0, 0]},
        {"time": 3, "position": [4, 1.8, 8], "target": [0, 1, 0]}]},
      "crowds": [{"type": "humanoid", "count": 150, "layout": "disc", "radius": 25, "seed": 5,
                  "mix": {"walk": 1.0}, "speed": [0.8, 1.6]}]
    })", "fly_in.json");
}

// The bound: a sole point (under an ankle or a toe) of a drawn walker at most 0.45 m above the ground. The
// generated gait lifts a swinging foot about 0.1-0.2 m at 0.8-1.6 m/s (a run at 2.5 m/s under 0.3 m,
// tests/systems/motion/library/gait_clip_test.cpp); the stretched legs had their soles at 0.6-0.8 m.
TEST(WorldFeet, WalkersSeenAgainAfterWalkingUnseenKeepTheirFeetDown) {
    WorldOptions o;
    o.threads = 1;
    o.budget = false;
    auto world = scene_test::make_world(fly_in_scene(), o);
    ASSERT_TRUE(world);
    MotionSample m;
    float highest = 0.0f;
    size_t drawn = 0, switched_in = 0;
    std::vector<uint8_t> was_mesh(world->character_count(), 0);
    for (int f = 0; f < 300; ++f) {
        world->step();
        for (uint32_t i = 0; i < world->character_count(); ++i) {
            world->motion_sample(i, m);
            const GeometryController& gc = *world->runtime(m.type).geometry;
            const GeomMethod method = gc.level(gc.level_of(m.id)).method;
            const bool mesh = method == GeomMethod::SkinnedMesh || method == GeomMethod::Layered || method == GeomMethod::Subdivided;
            switched_in += mesh && !was_mesh[i] && f > 0;
            was_mesh[i] = mesh ? 1 : 0;
            if (!mesh || !m.walking) continue;
            ++drawn;
            for (const glm::vec3& sole : m.soles) {
                const float height = sole.y - m.root.y;
                highest = std::max(highest, height);
                EXPECT_LE(height, 0.45f) << "frame " << f << ", character " << i << " (" << m.method << ")";
            }
        }
    }
    std::printf("%zu drawn walker-frames, %zu switches into a mesh level, highest sole %.3f m\n", drawn, switched_in,
                static_cast<double>(highest));
    EXPECT_GT(switched_in, 20u) << "walkers must come out of the impostor level for the test to mean anything";
}

}  // namespace
}  // namespace aloha
