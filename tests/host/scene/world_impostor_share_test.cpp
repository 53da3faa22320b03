// Height variants sharing impostor atlases in a World (World::build_impostors, systems/frame/impostor_share.hpp): a
// crowd of a file's character with a height range, each variant the file's mesh scaled to its height, draws one
// atlas scaled rather than baking one per variant; the shared ones report where their pictures come from, hold no
// texture memory of their own, and their impostors are drawn at the share's scale.
#include "engine/gpu/context.hpp"
#include "engine/gpu/offscreen_target.hpp"
#include "host/scene/character_runtime.hpp"
#include "host/scene/scene_loader.hpp"
#include "host/scene/world.hpp"
#include "systems/frame/impostor_share.hpp"
#include "tests/common/rig_fixtures.hpp"
#include "tests/host/scene/world_test_util.hpp"
#include "tests/systems/render/render_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

namespace aloha {
namespace {

namespace fs = std::filesystem;

TEST(WorldImpostorShare, HeightVariantsOfAFileCharacterDrawOneAtlasScaled) {
    const fs::path dir = fs::temp_directory_path() / ("aloha_world_impostor_share_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "rig.gltf") << test::gltf_text(test::renamed_humanoid(test::rigify_names("DEF-")), 1, 0.3f, true);
    SceneDesc scene = scene_test::scene_from_json(R"({"name": "v", "frames": 20, "camera": {"position": [0, 2, 40], "target": [0, 1, 0]},
      "character_types": [{"name": "rig", "gltf": "rig.gltf"}],
      "crowds": [{"type": "rig", "count": 9, "layout": "grid", "spacing": 2, "mix": {"walk": 1, "idle": 0, "reach": 0},
                  "height": [1.5, 1.8], "variants": 3}]})",
                                                  (dir / "scene.json").string());
    scene.width = 160;
    scene.height = 120;
    const std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    auto renderer = CrowdRenderer::create(*ctx);
    ASSERT_TRUE(renderer.ok()) << renderer.error().to_string();
    auto target = gpu::OffscreenTarget::create(*ctx, scene.width, scene.height);
    ASSERT_TRUE(target.ok());
    WorldOptions options;
    options.bake_cache = false;  // bake here, whatever an earlier run left
    auto made = World::create(scene, options);
    ASSERT_TRUE(made.ok()) << made.error().to_string();
    World& w = *made.value();
    ASSERT_TRUE(w.attach_renderer(renderer.value().get(), &target.value()).ok());

    std::map<std::string, size_t> type_index;
    for (size_t t = 0; t < w.type_count(); ++t) type_index[w.type(t).name] = t;
    const std::span<const World::ImpostorReport> atlases = w.impostor_atlases();
    ASSERT_EQ(atlases.size(), 3u) << "one report a variant (the base type has no character)";
    EXPECT_TRUE(atlases[0].shared_from.empty()) << "the first variant bakes";
    EXPECT_GT(atlases[0].texture_bytes, 0u);
    size_t shared = 0;
    std::map<std::string, float> scale_of;
    for (const World::ImpostorReport& a : atlases) {
        SCOPED_TRACE(a.type);
        if (a.shared_from.empty()) continue;
        ++shared;
        ASSERT_TRUE(type_index.count(a.shared_from));
        EXPECT_EQ(a.texture_bytes, 0u) << "no texture of its own";
        EXPECT_LE(a.distance_px, kImpostorShareTolerancePx);
        // The mesh is the file's scaled exactly; the walk rows are each body's own gait at one speed, so the rows'
        // heights (the scale's measure) follow the heights' ratio only to within the gaits' difference: 2%.
        const float ratio = w.type(type_index[a.type]).frame.height / w.type(type_index[a.shared_from]).frame.height;
        EXPECT_NEAR(a.scale, ratio, 0.02f * ratio);
        scale_of[a.type] = a.scale;
        std::printf("[ measured ] %s: %s's atlas drawn %.4fx (heights' ratio %.4f), %.3f px apart\n", a.type.c_str(),
                    a.shared_from.c_str(), a.scale, ratio, a.distance_px);
    }
    // Regression guard (measured: both later variants share the first's atlas, 0.26 and 0.51 px apart, at the heights' ratios to 4 digits).
    EXPECT_GE(shared, 1u) << "a scaled copy of one mesh shares";

    // Every character drawn as an impostor: a shared type's quads are its atlas's scaled.
    const auto& levels = w.rules().table().geom_levels;
    const auto impostor_level = static_cast<uint8_t>(
        std::find_if(levels.begin(), levels.end(), [](const GeomLevelDef& l) { return l.method == GeomMethod::Impostor; }) - levels.begin());
    ASSERT_LT(impostor_level, levels.size());
    for (uint32_t c = 0; c < 9; ++c) ASSERT_TRUE(w.pin_geom_level(c, impostor_level).ok());
    for (int i = 0; i < 20; ++i) w.step();
    ASSERT_TRUE(w.render_status().ok()) << w.render_status().error().to_string();
    const RenderLists& lists = w.render_lists();
    ASSERT_FALSE(lists.impostors.empty());
    std::map<float, size_t> seen;  // quad scales drawn
    for (const ImpostorInstance& im : lists.impostors) ++seen[im.position_scale.w];
    for (const auto& [type, scale] : scale_of) EXPECT_TRUE(seen.count(scale)) << type << " drawn at " << scale;
    EXPECT_TRUE(seen.count(1.0f)) << "the baking variant at its own size";
    made.value().reset();
    renderer.value().reset();
    EXPECT_EQ(ctx->validation_message_count(), 0u);
    fs::remove_all(dir);
}

// A crowd of 2 with 8 height variants builds the base type and the variants its members picked, not all 8
// (drop_unused_variants: before, every variant was built, its body, gaits and retargeted takes, for no one).
TEST(WorldImpostorShare, VariantsNoMemberPickedAreNotBuilt) {
    const fs::path dir = fs::temp_directory_path() / ("aloha_world_unpicked_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "rig.gltf") << test::gltf_text(test::renamed_humanoid(test::rigify_names("DEF-")), 1, 0.3f, true);
    const SceneDesc scene = scene_test::scene_from_json(R"({"name": "v", "frames": 2, "camera": {"position": [0, 2, 12], "target": [0, 1, 0]},
      "character_types": [{"name": "rig", "gltf": "rig.gltf"}],
      "crowds": [{"type": "rig", "count": 2, "mix": {"walk": 1, "idle": 0, "reach": 0}, "height": [1.5, 1.8], "variants": 8}]})",
                                                        (dir / "scene.json").string());
    ASSERT_EQ(scene.types.size(), 9u);
    auto made = World::create(scene, {});
    ASSERT_TRUE(made.ok()) << made.error().to_string();
    const World& w = *made.value();
    EXPECT_GE(w.type_count(), 2u);
    EXPECT_LE(w.type_count(), 3u) << "the base type and at most two picked variants";
    EXPECT_EQ(w.scene().types.size(), w.type_count());
    EXPECT_EQ(w.type(0).name, "rig");
    for (size_t t = 1; t < w.type_count(); ++t) EXPECT_EQ(w.runtime(t).count, w.type_count() == 2 ? 2u : 1u) << w.type(t).name;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace aloha
