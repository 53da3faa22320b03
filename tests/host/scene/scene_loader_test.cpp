#include "host/scene/scene_loader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace aloha {
namespace {

const std::string kScenes = std::string(ALOHA_SOURCE_DIR) + "/data/scenes/";

// A scene placed in the repository's scene folder so builtin and relative paths resolve.
Result<SceneDesc> parse(const std::string& text) { return parse_scene(text, kScenes + "test_inline.json"); }

std::string message_of(const Result<SceneDesc>& r) { return r.ok() ? std::string() : r.error().to_string(); }

TEST(SceneLoader, ShippedScenesLoad) {
    for (const char* name : {"closeup.json", "crowd_1k.json", "crowd_10k.json"}) {
        auto scene = load_scene(kScenes + name);
        ASSERT_TRUE(scene.ok()) << scene.error().to_string();
        EXPECT_FALSE(scene.value().camera.keys.empty());
        EXPECT_FALSE(scene.value().types.empty());
    }
    auto crowd = load_scene(kScenes + "crowd_10k.json");
    ASSERT_TRUE(crowd.ok());
    EXPECT_EQ(character_count(crowd.value()), 10000u);
    EXPECT_EQ(crowd.value().camera.keys.size(), 4u);
}

TEST(SceneLoader, SyntaxErrorNamesLineAndColumn) {
    auto r = parse("{\n  \"camera\": {\n    \"position\": [0, 1, 2,]\n  }\n}");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().line, 3);
    EXPECT_GT(r.error().column, 0);
    EXPECT_NE(r.error().file.find("test_inline.json"), std::string::npos);
}

TEST(SceneLoader, SemanticErrorsNameTheJsonPath) {
    const std::string base = R"({"camera": {"position": [0, 2, 10], "target": [0, 1, 0]}, )";
    struct Case { std::string body; std::string path; std::string words; };
    const std::vector<Case> cases = {
        {R"("crowds": [{"count": 1000000000}]})", "/crowds/0/count", "at most"},
        {R"("crowds": [{"count": -5}]})", "/crowds/0/count", "out of range"},
        {R"("crowds": [{"count": 10, "spacing": -1}]})", "/crowds/0/spacing", "out of range"},
        {R"("crowds": [{"count": 10, "layout": "spiral"}]})", "/crowds/0/layout", "unknown layout"},
        {R"("characters": [{"position": [0, "a", 0]}]})", "/characters/0/position/1", "finite"},
        {R"("characters": [{"type": "robot"}]})", "/characters/0/type", "unknown character type"},
        {R"("characters": [{"requests": [{"type": "fly"}]}]})", "/characters/0/requests/0/type", "unknown request"},
        {R"("characters": [{"requests": [{"type": "walk", "path": "nowhere"}]}]})", "/characters/0/requests/0/path", "unknown path"},
        {R"("characters": [{}], "rules": "../../../etc/passwd"})", "/rules", "escapes"},
        {R"("characters": [{}], "rules": "/etc/passwd"})", "/rules", "absolute"},
        {R"("characters": [{}], "rules": "missing_rules.json"})", "/rules", "does not exist"},
        {R"("characters": [{}], "colour": "red"})", "/colour", "unknown key"},
        {R"("characters": [{}], "frames": 0})", "/frames", "out of range"},
        {R"("characters": [{}], "frames": 1.5})", "/frames", "integer"},
        {R"("characters": [{}], "dt": "fast"})", "/dt", "expected a number"},
        {R"("characters": [{}], "character_types": [{"name": "x"}]})", "/character_types/0", "exactly one"},
        {R"("crowds": []})", "/", "no characters"},
        {R"("characters": [{"overlay": {"type": "walk"}}]})", "/characters/0/overlay", "reach or a look_at"},
        {R"("characters": [{"overlay": {"type": "reach", "target": [0, 1, 1], "weight": 2}}]})", "/characters/0/overlay/weight", "out of range"},
        {R"("characters": [{"overlay": {"type": "look_at"}}]})", "/characters/0/overlay", "missing required key 'target'"},
    };
    for (const Case& c : cases) {
        auto r = parse(base + c.body);
        ASSERT_FALSE(r.ok()) << c.body;
        const std::string msg = message_of(r);
        EXPECT_NE(msg.find(c.path), std::string::npos) << c.body << " -> " << msg;
        EXPECT_NE(msg.find(c.words), std::string::npos) << c.body << " -> " << msg;
        EXPECT_NE(msg.find("test_inline.json"), std::string::npos) << msg;
    }
}

TEST(SceneLoader, NumberOverflowNamesLineAndColumn) {
    auto r = parse("{\"camera\": {\"position\": [0, 2, 10], \"target\": [0, 1, 0]},\n \"characters\": [{\"position\": [0, 1e999, 0]}]}");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().line, 2);
    EXPECT_EQ(r.error().column, 34);
    EXPECT_NE(r.error().message.find("overflow"), std::string::npos) << r.error().to_string();
}

TEST(SceneLoader, ReportsEveryProblemNotOnlyTheFirst) {
    auto r = parse(R"({"camera": {"position": [0, 2, 10], "target": [0, 1, 0]}, "frames": -1, "dt": 0, "characters": [{}]})");
    ASSERT_FALSE(r.ok());
    const std::string msg = message_of(r);
    EXPECT_NE(msg.find("/frames"), std::string::npos);
    EXPECT_NE(msg.find("/dt"), std::string::npos);
}

TEST(SceneLoader, MissingCameraAndCoincidentCamera) {
    EXPECT_NE(message_of(parse(R"({"characters": [{}]})")).find("/camera"), std::string::npos);
    EXPECT_NE(message_of(parse(R"({"camera": {"position": [1, 1, 1], "target": [1, 1, 1]}, "characters": [{}]})")).find("coincide"),
              std::string::npos);
}

TEST(SceneLoader, MissingFileAndTruncatedFile) {
    auto missing = load_scene(kScenes + "no_such_scene.json");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().to_string().find("does not exist"), std::string::npos);
    auto truncated = parse(R"({"camera": {"position": [0, 2, 10], "tar)");
    ASSERT_FALSE(truncated.ok());
    EXPECT_EQ(truncated.error().line, 1);
}

TEST(SceneLoader, CameraPathInterpolates) {
    CameraDesc cam;
    cam.keys = {{0.0f, {0, 0, 0}, {0, 0, -1}}, {2.0f, {2, 0, 0}, {2, 0, -1}}};
    EXPECT_FLOAT_EQ(sample_camera(cam, 1.0f).position.x, 1.0f);
    EXPECT_FLOAT_EQ(sample_camera(cam, -1.0f).position.x, 0.0f);
    EXPECT_FLOAT_EQ(sample_camera(cam, 5.0f).position.x, 2.0f);
}

// `generated_motion` (bvh and gltf types: true unless turned off) is read, and refused where it means nothing: on a
// 'humanoid' type, whose motion is generated anyway, and as anything but a boolean.
TEST(SceneLoader, GeneratedMotionKey) {
    const std::string head = R"({"camera": {"position": [0, 2, 10], "target": [0, 1, 0]}, "characters": [{"type": "b"}], )";
    auto on = parse(head + R"("character_types": [{"name": "b", "gltf": "closeup.json"}]})");
    ASSERT_TRUE(on.ok()) << message_of(on);
    EXPECT_TRUE(on.value().types.at(0).generated_motion) << "on by default";
    auto off = parse(head + R"("character_types": [{"name": "b", "gltf": "closeup.json", "generated_motion": false, "idle": "Idle"}]})");
    ASSERT_TRUE(off.ok()) << message_of(off);
    EXPECT_FALSE(off.value().types.at(0).generated_motion);
    EXPECT_EQ(off.value().types.at(0).idle, "Idle") << "any type's 'idle' is read as written";
    auto walks = parse(head + R"("character_types": [{"name": "b", "gltf": "closeup.json", "walks": ["Walk", "Run"]}]})");
    ASSERT_TRUE(walks.ok()) << message_of(walks);
    EXPECT_EQ(walks.value().types.at(0).walks, (std::vector<std::string>{"Walk", "Run"}));
    for (const auto& [bad, where] : {std::pair{R"("walks": "Walk")", "/character_types/0/walks: expected an array"},
                                    {R"("walks": ["Walk", ""])", "/character_types/0/walks/1: expected the name"},
                                    {R"("walks": ["Walk", "Walk"])", "/character_types/0/walks/1: 'Walk' is named twice"}}) {
        auto r = parse(head + R"("character_types": [{"name": "b", "gltf": "closeup.json", )" + bad + "}]}");
        ASSERT_FALSE(r.ok()) << bad;
        EXPECT_NE(message_of(r).find(where), std::string::npos) << message_of(r);
    }
    auto on_humanoid = parse(head + R"("character_types": [{"name": "b", "humanoid": "builtin:humanoid", "walks": ["Walk"]}]})");
    ASSERT_FALSE(on_humanoid.ok());
    EXPECT_NE(message_of(on_humanoid).find("/character_types/0/walks: 'walks' applies to 'bvh' and 'gltf' types only"), std::string::npos)
        << message_of(on_humanoid);
    auto humanoid = parse(head + R"("character_types": [{"name": "b", "humanoid": "builtin:humanoid", "generated_motion": false}]})");
    ASSERT_FALSE(humanoid.ok());
    EXPECT_NE(message_of(humanoid).find("/character_types/0/generated_motion"), std::string::npos) << message_of(humanoid);
    EXPECT_NE(message_of(humanoid).find("applies to 'bvh' and 'gltf' types only"), std::string::npos) << message_of(humanoid);
    auto text = parse(head + R"("character_types": [{"name": "b", "gltf": "closeup.json", "generated_motion": "no"}]})");
    ASSERT_FALSE(text.ok());
    EXPECT_NE(message_of(text).find("/character_types/0/generated_motion"), std::string::npos) << message_of(text);
    EXPECT_NE(message_of(text).find("expected true or false"), std::string::npos) << message_of(text);
}

}  // namespace
}  // namespace aloha

namespace aloha {
namespace {

// Crowd body variety: a height/build range makes `variants` humanoid types with heights spread
// evenly over the range and builds inside theirs; each character is one of them; clip names stay
// the base type's. Misuse is refused with the JSON path.
TEST(SceneLoader, CrowdBodyVariants) {
    const std::string base = R"({"camera": {"position": [0, 2, 10], "target": [0, 1, 0]}, )";
    auto r = parse(base + R"("crowds": [{"count": 200, "height": [1.6, 1.9], "build": [0.2, 0.8], "variants": 4}]})");
    ASSERT_TRUE(r.ok()) << message_of(r);
    const SceneDesc& s = r.value();
    ASSERT_EQ(s.types.size(), 5u);  // the default humanoid and its four variants
    for (size_t v = 1; v < 5; ++v) {
        EXPECT_FALSE(s.types[v].humanoid.empty());
        EXPECT_NEAR(s.types[v].height, 1.6f + 0.3f * (static_cast<float>(v) - 0.5f) / 4.0f, 1e-5f);
        EXPECT_GE(s.types[v].build, 0.2f);
        EXPECT_LE(s.types[v].build, 0.8f);
        EXPECT_EQ(s.types[v].clip_prefix, "humanoid");
    }
    std::vector<int> used(5, 0);
    for (const CharacterDesc& c : expand_characters(s)) used[static_cast<size_t>(c.type)]++;
    EXPECT_EQ(used[0], 0);
    for (size_t v = 1; v < 5; ++v) EXPECT_GT(used[v], 20) << "every variant is drawn";

    auto no_range = parse(base + R"("crowds": [{"count": 5, "variants": 3}]})");
    ASSERT_FALSE(no_range.ok());
    EXPECT_NE(message_of(no_range).find("/crowds/0/variants"), std::string::npos) << message_of(no_range);
    auto bad_height = parse(base + R"("crowds": [{"count": 5, "height": [1.9, 1.6]}]})");
    ASSERT_FALSE(bad_height.ok());
    EXPECT_NE(message_of(bad_height).find("/crowds/0/height"), std::string::npos) << message_of(bad_height);
    // A file's character varies in height (scaled uniformly: standing_height), not in build.
    auto file_height = parse(base + R"("character_types": [{"name": "b", "gltf": "closeup.json"}],
                                        "crowds": [{"type": "b", "count": 5, "height": [1.6, 1.9], "variants": 2}]})");
    ASSERT_TRUE(file_height.ok()) << message_of(file_height);
    ASSERT_EQ(file_height.value().types.size(), 3u);
    EXPECT_FLOAT_EQ(file_height.value().types[1].standing_height, 1.675f);
    EXPECT_FLOAT_EQ(file_height.value().types[2].standing_height, 1.825f);
    EXPECT_EQ(file_height.value().types[0].standing_height, 0.0f) << "the base type stands as its file makes it";
    auto file_build = parse(base + R"("character_types": [{"name": "b", "gltf": "closeup.json"}],
                                       "crowds": [{"type": "b", "count": 5, "build": [0, 1]}]})");
    ASSERT_FALSE(file_build.ok());
    EXPECT_NE(message_of(file_build).find("/crowds/0/build: build variety needs a 'humanoid' character type"), std::string::npos)
        << message_of(file_build);
    auto height_on_bvh = parse(base + R"("character_types": [{"name": "b", "bvh": "closeup.json", "height": 1.7}],
                                          "crowds": [{"type": "b", "count": 5}]})");
    ASSERT_FALSE(height_on_bvh.ok());
    EXPECT_NE(message_of(height_on_bvh).find("apply to 'humanoid' types only"), std::string::npos);
}

}  // namespace
}  // namespace aloha

namespace aloha {
namespace {

TEST(SceneLoader, CharacterOverlayIsReadWithItsWeight) {
    auto r = parse(R"({"camera": {"position": [0, 2, 10], "target": [0, 1, 0]}, "characters": [
        {"requests": [{"type": "walk", "speed": 1.4}],
         "overlay": {"type": "look_at", "target": [3, 1.6, 6], "weight": 0.8, "crossfade": 0.4}}]})");
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const CharacterDesc& c = r.value().characters.at(0);
    ASSERT_TRUE(c.overlay.has_value());
    EXPECT_EQ(c.overlay->request.kind, RequestKind::LookAt);
    EXPECT_EQ(c.overlay->effector, "Head");
    EXPECT_FLOAT_EQ(c.overlay_weight, 0.8f);
    EXPECT_FLOAT_EQ(c.overlay->request.crossfade_s, 0.4f);
    EXPECT_EQ(c.requests.size(), 1u);
}

TEST(SceneLoader, AlwaysFullIsReadPerCharacterAndMustBeABoolean) {
    const std::string head = R"({"camera": {"position": [0, 2, 10], "target": [0, 1, 0]}, "characters": [)";
    auto r = parse(head + R"({"always_full": true}, {"importance": 0.5}]})");
    ASSERT_TRUE(r.ok()) << message_of(r);
    EXPECT_TRUE(r.value().characters.at(0).always_full);
    EXPECT_FALSE(r.value().characters.at(1).always_full);  // documented default: false
    auto bad = parse(head + R"({"always_full": "yes"}]})");
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(message_of(bad).find("/characters/0/always_full"), std::string::npos) << message_of(bad);
}

}  // namespace
}  // namespace aloha

namespace aloha {
namespace {

TEST(SceneLoader, HumanoidMapAndScaleOfFileCharacterTypes) {
    const std::string head = R"({"camera": {"position": [0, 2, 10], "target": [0, 1, 0]}, "characters": [{"type": "b"}], )";
    auto good = parse(head + R"("character_types": [{"name": "b", "gltf": "closeup.json", "scale": 0.01,
        "humanoid_map": {"LeftKnee": "knee_l"}}]})");
    ASSERT_TRUE(good.ok()) << message_of(good);
    EXPECT_FLOAT_EQ(good.value().types.at(0).scale, 0.01f);
    EXPECT_EQ(good.value().types.at(0).humanoid_map.at("LeftKnee"), "knee_l");
    EXPECT_EQ(good.value().types.at(0).pointer, "/character_types/0");
    EXPECT_NE(good.value().types.at(0).canonical.find("humanoid.json"), std::string::npos);
    auto not_object = parse(head + R"("character_types": [{"name": "b", "gltf": "closeup.json", "humanoid_map": ["x"]}]})");
    ASSERT_FALSE(not_object.ok());
    EXPECT_NE(message_of(not_object).find("/character_types/0/humanoid_map"), std::string::npos) << message_of(not_object);
    auto not_string = parse(head + R"("character_types": [{"name": "b", "gltf": "closeup.json", "humanoid_map": {"Hips": 3}}]})");
    ASSERT_FALSE(not_string.ok());
    EXPECT_NE(message_of(not_string).find("/character_types/0/humanoid_map/Hips"), std::string::npos) << message_of(not_string);
    auto bad_scale = parse(head + R"("character_types": [{"name": "b", "gltf": "closeup.json", "scale": -1}]})");
    ASSERT_FALSE(bad_scale.ok());
    EXPECT_NE(message_of(bad_scale).find("/character_types/0/scale"), std::string::npos) << message_of(bad_scale);
    auto on_humanoid = parse(head + R"("character_types": [{"name": "b", "humanoid": "builtin:humanoid", "scale": 2}]})");
    ASSERT_FALSE(on_humanoid.ok());
    EXPECT_NE(message_of(on_humanoid).find("apply to 'bvh' and 'gltf' types only"), std::string::npos) << message_of(on_humanoid);
}

// Motion files on a type (parsed here; loaded and retargeted by tests/host/scene/character_motions_test.cpp).
TEST(SceneLoader, MotionFilesOfACharacterType) {
    const std::string head = R"({"camera": {"position": [0, 2, 10], "target": [0, 1, 0]}, "characters": [{"type": "b"}], )";
    auto good = parse(head + R"("character_types": [{"name": "b", "humanoid": "builtin:humanoid", "motions": [
        {"bvh": "closeup.json", "name": "take", "scale": 0.01, "humanoid_map": {"Hips": "pelvis"}},
        {"gltf": "closeup.json", "clip": "Run"}]}]})");
    ASSERT_TRUE(good.ok()) << message_of(good);
    const std::vector<MotionFileDesc>& m = good.value().types.at(0).motions;
    ASSERT_EQ(m.size(), 2u);
    EXPECT_NE(m[0].bvh.find("closeup.json"), std::string::npos) << "resolved against the scene's folder";
    EXPECT_EQ(m[0].name, "take");
    EXPECT_FLOAT_EQ(m[0].scale, 0.01f);
    EXPECT_EQ(m[0].humanoid_map.at("Hips"), "pelvis");
    EXPECT_EQ(m[0].pointer, "/character_types/0/motions/0");
    EXPECT_EQ(m[1].clip, "Run");
    const struct {
        const char* motions;
        const char* where;
        const char* what;
    } bad[] = {
        {R"({"bvh": "closeup.json"})", "/character_types/0/motions", "expected an array of 1 to 256 motion files"},
        {R"([{"bvh": "closeup.json", "gltf": "closeup.json"}])", "/character_types/0/motions/0", "give exactly one of 'bvh' and 'gltf'"},
        {R"([{}])", "/character_types/0/motions/0", "give exactly one of 'bvh' and 'gltf'"},
        {R"([{"bvh": "closeup.json", "clip": "Run"}])", "/character_types/0/motions/0/clip", "picks one animation of a 'gltf' file"},
        {R"([{"bvh": "closeup.json", "name": "a.b"}])", "/character_types/0/motions/0/name", "has no '.'"},
        {R"([{"bvh": "/etc/passwd"}])", "/character_types/0/motions/0/bvh", "absolute"},
        {R"([{"bvh": "closeup.json", "speed": 2}])", "/character_types/0/motions/0", "speed"},
    };
    for (const auto& b : bad) {
        auto r = parse(head + R"("character_types": [{"name": "b", "humanoid": "builtin:humanoid", "motions": )" + b.motions + "}]}");
        ASSERT_FALSE(r.ok()) << b.motions;
        EXPECT_NE(message_of(r).find(b.where), std::string::npos) << message_of(r);
        EXPECT_NE(message_of(r).find(b.what), std::string::npos) << message_of(r);
    }
}

}  // namespace
}  // namespace aloha
