// Motion files in a World: a crowd of body variants of the built-in humanoid idling on a retargeted take. Each
// variant is its own body, so each retargets the take onto itself at load; every variant has the clip under the base
// type's prefix, the crowd plays it, and the motion is the same pelvis travel scaled by each body's legs.
#include "host/scene/motion_sample.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "tests/common/bvh_writer.hpp"
#include "tests/common/rig_fixtures.hpp"
#include "tests/common/test_humanoid.hpp"
#include "tests/host/scene/world_test_util.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace aloha {
namespace {

namespace fs = std::filesystem;
using scene_test::make_world;
using scene_test::scene_from_json;

// Writes dir/take.bvh (creating dir): the built-in humanoid's 1.10 m/s walk, two cycles, as a CMU-named BVH in
// centimetres at 60 frames a second.
void write_walking_take(const fs::path& dir) {
    fs::create_directories(dir);
    const Skeleton body = test::humanoid_skeleton_for({1.75f, 0.5f});
    const MotionLibrary lib = make_motion_library(body, test::humanoid_rig(body), "src");
    const AnimationClip walk = build_clip(lib.gaits[2], body, ClipEncoding::Float32).value();
    std::ofstream(dir / "take.bvh") << test::bvh_text_of_clip(body, walk, 100.0f, 60.0f, 2);
}

TEST(WorldMotions, CrowdVariantsPlayATakeRetargetedOntoEachBody) {
    const fs::path dir = fs::temp_directory_path() / ("aloha_world_motions_" + std::to_string(::getpid()));
    write_walking_take(dir);
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

// A crowd of a file's character with a height range: each variant is the file's character scaled uniformly to stand
// as tall as its share of the range says (its skeleton, mesh and clips alike) and walks its own generated gaits, made
// for its legs: one speed, a shorter cycle for shorter legs; a build range is refused for it, naming the crowd's key.
TEST(WorldMotions, FileCharacterCrowdVariesInHeight) {
    const fs::path dir = fs::temp_directory_path() / ("aloha_world_file_variants_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "rig.gltf") << test::gltf_text(test::renamed_humanoid(test::rigify_names("DEF-")), 1, 0.3f, true);
    const std::string head = R"({"name": "v", "frames": 20, "camera": {"position": [0, 2, 12], "target": [0, 1, 0]},
      "character_types": [{"name": "rig", "gltf": "rig.gltf"}],
      "crowds": [{"type": "rig", "count": 9, "layout": "grid", "spacing": 2, "mix": {"walk": 1, "idle": 0, "reach": 0}, )";
    const SceneDesc scene = scene_from_json(head + R"("height": [1.5, 1.8], "variants": 3}]})", (dir / "scene.json").string());
    auto w = make_world(scene);
    ASSERT_TRUE(w);
    const float own = w->type(0).frame.height;
    std::vector<float> heights, cycles;
    for (size_t t = 0; t < w->type_count(); ++t) {
        const CharacterType& type = w->type(t);
        if (type.name.find('~') == std::string::npos) continue;
        heights.push_back(type.frame.height);
        const int id = find_clip(type, "rig.walk_1.40");
        ASSERT_GE(id, 0) << type.name << ": the generated gaits under the base type's prefix";
        const AnimationClip& gait = *type.clips.find(static_cast<ClipId>(id));
        // Made for this body (k = 1 to float rounding): 1.40 m/s within the stored root's quantisation at both ends.
        EXPECT_NEAR(gait.root_speed(), 1.4f, 2.0f * gait.error_bound().translation / gait.duration() + 1e-5f) << type.name;
        cycles.push_back(gait.duration());
        // Uniform scale: the hips stand at the base's hips height times the height ratio (float rounding: 1e-5 m).
        const float ratio = type.frame.height / own;
        const auto hips = [](const CharacterType& c) {
            return glm::vec3(skeleton_rest_model(c.skeleton)[static_cast<size_t>(c.map.find("Hips"))][3]).y;
        };
        EXPECT_NEAR(hips(type), hips(w->type(0)) * ratio, 1e-5f) << type.name;
        ASSERT_TRUE(type.mesh.has_value());
        EXPECT_NEAR(type.mesh->positions[0].y, w->type(0).mesh->positions[0].y * ratio, 1e-5f) << type.name << ": the mesh scales with it";
    }
    ASSERT_EQ(heights.size(), 3u);
    for (size_t v = 0; v < 3; ++v) EXPECT_NEAR(heights[v], 1.55f + 0.1f * static_cast<float>(v), 1e-5f) << v;
    // At one speed, longer legs take longer strides, fewer a second.
    EXPECT_LT(cycles[0], cycles[1]);
    EXPECT_LT(cycles[1], cycles[2]);
    for (int f = 0; f < 20; ++f) w->step();
    auto g = character_group(w->registry());
    size_t walking = 0;
    for (const MotionState& m : g.span<MotionState>()) walking += m.active == RequestKind::Walk;
    EXPECT_EQ(walking, 9u);

    Result<SceneDesc> built = parse_scene(head + R"("build": [0, 1], "variants": 3}]})", (dir / "scene.json").string());
    ASSERT_FALSE(built.ok());
    EXPECT_NE(built.error().to_string().find("/crowds/0/build: build variety needs a 'humanoid' character type"), std::string::npos)
        << built.error().to_string();

    // A height range on a file's character that is no humanoid: the error is at the range and names the type as the
    // scene does (not the variant's internal name, found by scripts/scene_soak.py).
    std::ofstream(dir / "dog.bvh") << test::bvh_text(test::quadruped(), 30, glm::vec3(0, 0, 1), 1.0f);
    const SceneDesc dogs = scene_from_json(R"({"name": "d", "frames": 1, "camera": {"position": [0, 2, 12], "target": [0, 1, 0]},
      "character_types": [{"name": "dog", "bvh": "dog.bvh"}],
      "crowds": [{"type": "dog", "count": 2, "mix": {"walk": 0, "idle": 1, "reach": 0}, "height": [0.5, 0.7], "variants": 2}]})",
                                           (dir / "scene.json").string());
    ASSERT_EQ(dogs.types.size(), 3u) << "the type and its two variants";
    const Result<CharacterType> variant = load_character_type(dogs.types[1]);
    ASSERT_FALSE(variant.ok());
    EXPECT_NE(variant.error().to_string().find("/crowds/0/height: type 'dog' from "), std::string::npos) << variant.error().to_string();
    EXPECT_NE(variant.error().to_string().find("is no mapped humanoid: it has no standing height to vary (give it a 'humanoid_map', or drop"),
              std::string::npos)
        << variant.error().to_string();
    fs::remove_all(dir);
}

// A take that walks, played looping by a scene's `play` request: its root motion moves the character on, repeat
// after repeat, the pelvis in the world never jumping (systems/motion/root_motion.hpp); with "root_motion": false the
// character's placement stays and the pelvis goes back to where the take starts at each repeat.
TEST(WorldMotions, APlayedWalkingTakeCarriesTheCharacterOn) {
    const fs::path dir = fs::temp_directory_path() / ("aloha_world_root_motion_" + std::to_string(::getpid()));
    write_walking_take(dir);  // 2.12 s
    const std::string json = R"({"name": "m", "frames": 300, "camera": {"position": [0, 2, 12], "target": [0, 1, 0]},
      "character_types": [{"name": "humanoid", "humanoid": "builtin:humanoid", "motions": [{"bvh": "take.bvh"}]}],
      "characters": [{"position": [-2, 0, 0], "requests": [{"type": "play", "clip": "humanoid.take"}]},
                     {"position": [2, 0, 0], "requests": [{"type": "play", "clip": "humanoid.take", "root_motion": false}]}]})";
    auto w = make_world(scene_from_json(json, (dir / "scene.json").string()));
    ASSERT_TRUE(w);
    const CharacterType& type = w->type(0);
    const AnimationClip* take = type.clips.find(static_cast<ClipId>(find_clip(type, "humanoid.take")));
    ASSERT_TRUE(take && take->root_motion().moves());
    const float speed = take->root_motion().net_travel() / take->duration();
    MotionSample m;
    std::vector<glm::vec3> pelvis[2], placed[2];
    constexpr int kFrames = 200;  // 3.3 s at the scene's 60 frames a second: a wrap at 2.12 s
    for (int f = 0; f < kFrames; ++f) {
        w->step();
        for (uint32_t c = 0; c < 2; ++c) {
            w->motion_sample(c, m);
            pelvis[c].push_back(m.joints[0]);
            placed[c].push_back(m.root);
        }
    }
    auto largest_step = [](const std::vector<glm::vec3>& v) {
        float worst = 0.0f;
        for (size_t i = 1; i < v.size(); ++i) worst = std::max(worst, glm::length(v[i] - v[i - 1]));
        return worst;
    };
    // With root motion the placement goes the take's way at its speed (the pelvis's travel to the frame and float
    // rounding aside), and the pelvis never steps further in a frame than three times the walk's mean speed (its
    // own sway and the stride's speed changes; the wrap, without root motion, jumps 2.3 m).
    const float dt = 1.0f / 60.0f;
    EXPECT_NEAR(glm::length(placed[0].back() - placed[0].front()), speed * dt * (kFrames - 1), 0.05f);
    EXPECT_LE(largest_step(pelvis[0]), 3.0f * speed * dt);
    EXPECT_EQ(placed[1].back(), placed[1].front());
    EXPECT_GT(largest_step(pelvis[1]), 1.0f) << "without root motion the take goes back to its start";
    std::printf("[figure] take %.2f m/s: largest pelvis step a frame %.4f m with root motion, %.4f m without\n",
                static_cast<double>(speed), static_cast<double>(largest_step(pelvis[0])), static_cast<double>(largest_step(pelvis[1])));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace aloha
