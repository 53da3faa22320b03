// Motion files in a World: a crowd of body variants of the built-in humanoid idling on a retargeted take. Each
// variant is its own body, so each retargets the take onto itself at load; every variant has the clip under the base
// type's prefix, the crowd plays it, and the motion is the same pelvis travel scaled by each body's legs.
#include "systems/motion/library/motion_library.hpp"
#include "tests/common/bvh_writer.hpp"
#include "tests/common/test_humanoid.hpp"
#include "tests/host/scene/world_test_util.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace aloha {
namespace {

namespace fs = std::filesystem;
using scene_test::make_world;
using scene_test::scene_from_json;

TEST(WorldMotions, CrowdVariantsPlayATakeRetargetedOntoEachBody) {
    const fs::path dir = fs::temp_directory_path() / ("aloha_world_motions_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    // The take: the built-in humanoid's 1.10 m/s walk, two cycles, as a CMU-named BVH in centimetres.
    const Skeleton body = test::humanoid_skeleton_for({1.75f, 0.5f});
    const MotionLibrary lib = make_motion_library(body, test::humanoid_rig(body), "src");
    const AnimationClip walk = build_clip(lib.gaits[2], body, ClipEncoding::Float32).value();
    std::ofstream(dir / "take.bvh") << test::bvh_text_of_clip(body, walk, 100.0f, 60.0f, 2);
    const std::string json = R"({"name": "m", "frames": 20, "camera": {"position": [0, 2, 12], "target": [0, 1, 0]},
      "character_types": [{"name": "humanoid", "humanoid": "builtin:humanoid", "motions": [{"bvh": "take.bvh"}]}],
      "crowds": [{"type": "humanoid", "count": 12, "layout": "grid", "spacing": 2, "mix": {"walk": 0, "idle": 1, "reach": 0},
                  "clip": "humanoid.take", "height": [1.5, 2.0], "build": [0.0, 1.0], "variants": 2}]})";
    const SceneDesc scene = scene_from_json(json, (dir / "scene.json").string());
    auto w = make_world(scene);
    ASSERT_TRUE(w);
    size_t variants = 0;
    std::vector<float> speeds;
    for (size_t t = 0; t < w->type_count(); ++t) {
        const CharacterType& type = w->type(t);
        if (type.name.find('~') == std::string::npos) continue;
        ++variants;
        const int id = find_clip(type, "humanoid.take");
        ASSERT_GE(id, 0) << type.name << ": the take under the base type's prefix";
        speeds.push_back(type.clips.find(static_cast<ClipId>(id))->root_speed());
    }
    EXPECT_EQ(variants, 2u);
    // 1.625 and 1.875 m tall (2 variants over 1.5-2.0 m): the pelvis travel scales with each body's legs, so the variants' takes differ in speed, all
    // near the source's 1.10 m/s (its body 1.75 m tall).
    ASSERT_EQ(speeds.size(), 2u);
    EXPECT_LT(*std::min_element(speeds.begin(), speeds.end()), 1.10f);
    EXPECT_GT(*std::max_element(speeds.begin(), speeds.end()), 1.10f);
    for (int f = 0; f < 20; ++f) w->step();
    auto g = character_group(w->registry());
    size_t playing = 0;
    for (const MotionState& m : g.span<MotionState>()) playing += m.active == RequestKind::PlayClip && m.at_rest == 0;
    EXPECT_EQ(playing, 12u) << "every character plays the take";
    fs::remove_all(dir);
}

}  // namespace
}  // namespace aloha
