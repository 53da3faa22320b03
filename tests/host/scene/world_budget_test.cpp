// The World and its rule file's budget, caps, tiers and always_full: the file's budget runs with no
// command-line flag, a live reload re-applies it (targets, switched off, switched on), always_full
// characters are never demoted while everyone else is, and the scene's tier is used (or refused).
#include "host/scene/scene_loader.hpp"
#include "host/scene/world.hpp"
#include "tests/host/scene/world_test_util.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

namespace aloha {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Mode = BudgetStatus::Mode;
using scene_test::make_world;

const std::string kSource = ALOHA_SOURCE_DIR;

// The plaza (characters close to the camera, so most are at rich levels) with `count` characters.
SceneDesc plaza(uint32_t count) {
    auto scene = load_scene(kSource + "/data/scenes/plaza_budget.json");
    EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().to_string());
    SceneDesc s = scene.value();
    s.crowds[0].count = count;
    return s;
}

// A rule file: the default one with `budget` as its budget section (comments are not JSON: the
// default file has none).
json rules_with_budget(const json& budget) {
    std::ifstream in(kSource + "/data/rules/default.json");
    json j = json::parse(in);
    j["budget"] = budget;
    return j;
}

// Targets no crowd reaches: the controllers demote everyone they may.
json tiny_budget(bool enabled = true, double geometry_ms = 0.001) {
    return {{"enabled", enabled},
            {"animation", {{"target_ms", 0.001}}},
            {"geometry", {{"target_ms", geometry_ms}}}};
}

// Writes `j` to `path` with a modification time `seconds` ahead, so poll() sees a change.
void write_rules(const fs::path& path, const json& j, int seconds) {
    std::ofstream(path) << j.dump(2);
    fs::last_write_time(path, fs::file_time_type::clock::now() + std::chrono::seconds(seconds));
}

// A rule file with a budget no crowd reaches in a temporary folder (removed at the end), and the plaza
// scene with 60 characters using it.
struct TinyBudgetPlaza {
    fs::path dir, rules;
    SceneDesc scene;
    explicit TinyBudgetPlaza(const std::string& name)
        : dir(fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()))), rules(dir / "rules.json") {
        fs::create_directories(dir);
        write_rules(rules, rules_with_budget(tiny_budget()), 0);
        scene = plaza(60);
        scene.rules = rules.string();
    }
    ~TinyBudgetPlaza() { fs::remove_all(dir); }
};

TEST(WorldBudget, FileBudgetRunsWithoutFlagsAndReloadReappliesIt) {
    const TinyBudgetPlaza t("aloha_world_budget");
    const fs::path& rules = t.rules;
    const SceneDesc& s = t.scene;
    auto w = make_world(s);  // no budget option of any kind
    ASSERT_TRUE(w);
    EXPECT_EQ(w->budget_status().mode, Mode::Parts);
    EXPECT_FLOAT_EQ(w->budget_status().geometry.target_ms, 0.001f);
    for (int f = 0; f < 40; ++f) w->step();
    EXPECT_GT(w->lod_stats().demoted, 10u);  // the file's budget really ran

    write_rules(rules, rules_with_budget(tiny_budget(false)), 10);  // switched off in the file
    w->step();
    EXPECT_EQ(w->budget_status().mode, Mode::Off);
    EXPECT_EQ(w->lod_stats().demoted, 0u);  // everyone back to the rules' levels

    write_rules(rules, rules_with_budget(tiny_budget(true, 2.5)), 20);  // on again, a new target
    w->step();
    EXPECT_EQ(w->budget_status().mode, Mode::Parts);
    EXPECT_FLOAT_EQ(w->budget_status().geometry.target_ms, 2.5f);
    const uint32_t generation = w->rules().generation();
    EXPECT_GE(generation, 3u);

    // A host override still wins over the reloaded file.
    WorldOptions off;
    off.budget = false;
    auto quiet = make_world(s, off);
    ASSERT_TRUE(quiet);
    EXPECT_EQ(quiet->budget_status().mode, Mode::Off);
}

TEST(WorldBudget, AlwaysFullCharactersAreNeverDemoted) {
    const TinyBudgetPlaza t("aloha_world_full");
    SceneDesc s = t.scene;
    for (int i = 0; i < 6; ++i) {  // six heroes among the crowd, at rest
        CharacterDesc c;
        c.position = glm::vec3(-3.0f + 1.2f * float(i), 0.0f, 1.0f);
        c.always_full = true;
        s.characters.push_back(c);
    }
    auto w = make_world(s);
    ASSERT_TRUE(w);
    for (int f = 0; f < 60; ++f) {
        w->step();
        auto g = character_group(w->registry());
        const auto states = g.span<LodState>();
        const auto requests = g.span<LodRequest>();
        size_t heroes = 0;
        for (size_t i = 0; i < states.size(); ++i) {
            if (!states[i].always_full) continue;
            ++heroes;
            ASSERT_EQ(states[i].budget_demotion, 0) << "frame " << f;
            ASSERT_EQ(states[i].anim_demotion, 0) << "frame " << f;
            // Nor held below their rule's levels by a cap (six heroes fit under every cap).
            ASSERT_LE(states[i].cap_geom_level, requests[i].geom_level) << "frame " << f;
            ASSERT_LE(states[i].cap_anim_level, requests[i].anim_level) << "frame " << f;
        }
        ASSERT_EQ(heroes, 6u);
    }
    EXPECT_GT(w->lod_stats().demoted, 10u);  // while the others were pushed down
}

TEST(WorldBudget, SceneTierIsUsedAndUnknownTiersAreRefused) {
    SceneDesc s = plaza(10);
    s.tier = "low";
    auto w = make_world(s);
    ASSERT_TRUE(w);
    EXPECT_EQ(w->tier().tier, 0);
    EXPECT_EQ(w->tier().reason, "named by the scene");
    WorldOptions o;
    o.tier = "medium";  // the host's wins over the scene's
    auto h = make_world(s, o);
    ASSERT_TRUE(h);
    EXPECT_EQ(h->tier().tier, 1);
    s.tier = "ultra";
    auto bad = World::create(s, {});
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().file, s.file);
    EXPECT_EQ(bad.error().path, "/tier");
    EXPECT_NE(bad.error().message.find("tier 'ultra'"), std::string::npos) << bad.error().to_string();
}

}  // namespace
}  // namespace aloha
