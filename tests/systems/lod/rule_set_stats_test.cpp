// Live reload (RuleSet): a changed file is picked up mid-run, states are preserved (clamped when the
// new file has fewer levels), new thresholds take effect, a broken edit keeps the old table.
// Explainability: LodStats histograms and explain() as struct and JSON.
#include "systems/lod/attributes.hpp"
#include "systems/lod/resolver.hpp"
#include "systems/lod/rule_eval.hpp"
#include "systems/lod/rule_set.hpp"
#include "systems/lod/stats.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <unistd.h>

namespace aloha {
namespace {

using lod_test::at_distance;
using lod_test::must_parse;
using lod_test::small_rules;
namespace fs = std::filesystem;

// Writes `text` to `path` and moves its modification time forward by `seconds` from `base`, so a
// poll sees a change even on file systems with coarse time stamps.
void write_file(const fs::path& path, const std::string& text, fs::file_time_type base, int seconds) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    fs::last_write_time(path, base + std::chrono::seconds(seconds));
}

struct Pipeline {
    std::vector<LodAttributes> attrs;
    std::vector<LodRequest> req;
    std::vector<LodState> states;
    std::vector<GeomLod> geom;
    std::vector<AnimLod> anim;
    explicit Pipeline(std::vector<LodAttributes> a)
        : attrs(std::move(a)), req(attrs.size()), states(attrs.size()), geom(attrs.size()), anim(attrs.size()) {}
    void frame(const RuleTable& t, bool snap = false) {
        RuleEvalJob{&t, attrs, states, t.default_tier, req}.Run();
        LodResolveJob{&t, req, states, geom, anim, {}, {}, 0, snap ? 0.0f : lod_test::kFrameDt, snap}.Run();
    }
};

TEST(RuleSet, ReloadMidRunKeepsStatesAndAppliesNewThresholds) {
    const fs::path path = fs::temp_directory_path() / ("lod_reload_" + std::to_string(::getpid()) + ".json");
    const auto base = fs::file_time_type::clock::now();
    write_file(path, small_rules().dump(2), base, 0);
    RuleSet set;
    ASSERT_TRUE(set.load(path.string()).ok());
    EXPECT_EQ(set.generation(), 1u);
    Result<bool> unchanged = set.poll();
    ASSERT_TRUE(unchanged.ok());
    EXPECT_FALSE(unchanged.value());

    Pipeline p({at_distance(15.0f), at_distance(30.0f)});
    p.frame(set.table(), true);
    for (int f = 0; f < 20; ++f) p.frame(set.table());
    EXPECT_EQ(p.states[0].geom_level, 1);  // mid (distance < 20)
    EXPECT_EQ(p.states[1].geom_level, 2);  // far
    const LodState before = p.states[0];

    // New thresholds: "near" now reaches 16 m, "mid" 40 m.
    auto j = small_rules();
    j["rules"][1]["when"]["distance"]["lt"] = 16;
    j["rules"][2]["when"]["distance"]["lt"] = 40;
    write_file(path, j.dump(2), base, 10);
    Result<bool> changed = set.poll();
    ASSERT_TRUE(changed.ok()) << changed.error().to_string();
    EXPECT_TRUE(changed.value());
    EXPECT_EQ(set.generation(), 2u);
    // Nothing was reset by the reload itself.
    EXPECT_EQ(p.states[0].geom_level, before.geom_level);
    EXPECT_EQ(p.states[0].seconds_at_geom, before.seconds_at_geom);
    p.frame(set.table());
    EXPECT_EQ(p.states[0].geom_level, 0);  // 15 < 16: near (held > min_seconds, so it switches at once)
    EXPECT_EQ(p.states[1].geom_level, 1);  // 30 < 40: mid
    EXPECT_EQ(p.states[0].prev_geom_level, 1);  // a normal transition from the kept level
    EXPECT_GT(p.states[0].geomorph_left_s, 0.0f);

    // A broken edit: the error names the file and the old table stays.
    write_file(path, "{ \"rules\": [ }", base, 20);
    Result<bool> broken = set.poll();
    ASSERT_FALSE(broken.ok());
    EXPECT_EQ(broken.error().file, path.string());
    EXPECT_EQ(broken.error().line, 1);
    EXPECT_EQ(set.generation(), 2u);
    EXPECT_FALSE(set.last_errors().empty());
    EXPECT_EQ(set.table().rules.size(), 4u);

    // Fewer levels: states are clamped, not reset.
    auto k = small_rules();
    k["geometric_levels"] = nlohmann::json::parse(R"([{"name": "rich", "method": "layered"}, {"name": "mid", "method": "skinned_mesh"}])");
    k["rules"][0]["then"]["geometry"] = "mid";
    k["rules"][3]["then"]["geometry"] = "mid";
    write_file(path, k.dump(2), base, 30);
    ASSERT_TRUE(set.reload_from_file().ok());
    p.states[1].geom_level = 3;
    clamp_lod_states(set.table(), p.states);
    EXPECT_EQ(p.states[1].geom_level, 1);
    EXPECT_EQ(p.states[0].geom_level, 0);
    fs::remove(path);
}

TEST(LodStats, HistogramsAndJson) {
    const RuleTable t = must_parse(small_rules());
    LodAttributes off = at_distance(5.0f);
    off.visible = 0;
    Pipeline p({at_distance(5.0f), at_distance(15.0f), at_distance(16.0f), at_distance(50.0f), off});
    p.frame(t, true);
    p.states[3].budget_demotion = 1;
    LodStats s;
    LodStatsJob job{&t, p.states, p.attrs, &s};
    ASSERT_TRUE(job.Validate());
    job.Run();
    EXPECT_EQ(s.characters, 5u);
    EXPECT_EQ(s.visible, 4u);
    EXPECT_EQ(s.demoted, 1u);
    EXPECT_EQ(s.per_geom_level, (std::vector<uint32_t>{1, 2, 1, 1}));
    EXPECT_EQ(s.per_anim_level, (std::vector<uint32_t>{1, 2, 2}));
    EXPECT_EQ(s.per_rule, (std::vector<uint32_t>{1, 1, 2, 1}));
    EXPECT_EQ(s.per_walk_method[static_cast<size_t>(WalkMethod::Kinematic)], 2u);
    EXPECT_EQ(s.per_geom_method[static_cast<size_t>(GeomMethod::Hidden)], 1u);
    const nlohmann::json j = to_json(s, t);
    EXPECT_EQ(j["geometry_levels"]["mid"], 2);
    EXPECT_EQ(j["rules"]["off"], 1);
    EXPECT_EQ(j["walk_methods"]["clip"], 2);
}

TEST(LodStats, ExplainOneCharacter) {
    const RuleTable t = must_parse(small_rules());
    Pipeline p({at_distance(15.0f)});
    p.states[0].budget_demotion = 1;
    p.states[0].anim_demotion = 1;
    p.frame(t, true);
    const LodExplanation e = explain(t, 0, p.attrs, p.states);
    EXPECT_EQ(e.rule_name, "mid");
    EXPECT_EQ(e.rule_geom_level, 1);
    EXPECT_EQ(e.budget_demotion, 1);
    EXPECT_EQ(e.geom.level, 2);  // mid demoted by one: proxy
    EXPECT_EQ(e.geom_level_name, "proxy");
    EXPECT_EQ(e.anim_level_name, "clip");
    EXPECT_FLOAT_EQ(e.attributes.distance, 15.0f);
    const nlohmann::json j = to_json(e);
    EXPECT_EQ(j["rule"]["name"], "mid");
    EXPECT_EQ(j["geometry"]["method"], "rigid_proxy");
    EXPECT_EQ(j["animation"]["walk"], "clip");
    EXPECT_EQ(j["budget_demotion"], 1);
    EXPECT_EQ(j["anim_budget_demotion"], 1);
    EXPECT_EQ(j["attributes"]["visible"], true);
}

}  // namespace
}  // namespace aloha

namespace aloha {
namespace {

// The default rules on a 10,000-character crowd spread over 200 m x 200 m in front of a 60 degree,
// 1280x720 camera: most characters are cheap (impostor, proxy or hidden, clip playback) and the richest level
// is rare. Thresholds are generous fractions of the counts, not tuned to the exact layout.
TEST(DefaultRules, TenThousandCrowdIsMostlyCheap) {
    Result<RuleTable> r = load_rules(std::string(ALOHA_SOURCE_DIR) + "/data/rules/default.json");
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const RuleTable& t = r.value();
    constexpr size_t n = 10000;
    std::vector<Transform> tr(n);
    std::vector<Importance> imp(n);
    uint32_t seed = 3u;
    auto rnd = [&seed] { seed = seed * 1664525u + 1013904223u; return static_cast<float>(seed >> 8) / 16777216.0f; };
    for (size_t i = 0; i < n; ++i) {
        tr[i].position = {rnd() * 200.0f - 100.0f, 0.0f, -rnd() * 200.0f};
        imp[i].value = rnd();
    }
    Pipeline p{std::vector<LodAttributes>(n)};
    LodAttributesJob{tr, {}, {}, imp, make_lod_camera({0, 1.7f, 2}, {0, 1.7f, -10}, 1.0472f, {1280, 720}, 0.1f, 1000.0f),
                     p.attrs}.Run();
    p.frame(t, true);
    LodStats s;
    LodStatsJob{&t, p.states, p.attrs, &s}.Run();
    const uint32_t cheap = s.per_geom_method[static_cast<size_t>(GeomMethod::RigidProxy)] +
                           s.per_geom_method[static_cast<size_t>(GeomMethod::Impostor)] +
                           s.per_geom_method[static_cast<size_t>(GeomMethod::Hidden)];
    EXPECT_GT(cheap, n * 8 / 10) << to_json(s, t).dump();
    EXPECT_GT(s.per_walk_method[static_cast<size_t>(WalkMethod::ClipPlayback)], n * 8 / 10);
    EXPECT_LT(s.per_geom_method[static_cast<size_t>(GeomMethod::Subdivided)], n / 100);
    EXPECT_GT(s.per_geom_method[static_cast<size_t>(GeomMethod::Layered)], 0u);  // near ones are richer
    std::printf("%s\n", to_json(s, t).dump().c_str());
}

}  // namespace
}  // namespace aloha
