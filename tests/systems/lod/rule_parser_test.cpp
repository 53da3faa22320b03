// Rule-file loading: the default file loads cleanly; each class of bad file gives an error naming
// the file and the place (line/column for syntax, JSON path for meaning) and what is wrong.
#include "systems/lod/rule_table.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace aloha {
namespace {

using lod_test::must_parse;
using lod_test::small_rules;
using nlohmann::json;

// Parses `j` expecting failure; returns every error.
std::vector<Error> errors_of(const json& j, const std::string& name = "bad.json") {
    std::vector<Error> errors;
    Result<RuleTable> r = parse_rules(j.dump(2), name, &errors);
    EXPECT_FALSE(r.ok());
    if (!r.ok()) {
        EXPECT_FALSE(errors.empty());
        EXPECT_EQ(r.error().to_string(), errors.front().to_string());
    }
    return errors;
}

// True when some error has `path` and a message containing `text`, and names bad.json.
bool has_error(const std::vector<Error>& errors, const std::string& path, const std::string& text) {
    for (const Error& e : errors) {
        if (e.file == "bad.json" && e.path == path && e.message.find(text) != std::string::npos) return true;
    }
    return false;
}

TEST(RuleParser, DefaultFileLoadsWithoutWarnings) {
    const std::string path = std::string(ALOHA_SOURCE_DIR) + "/data/rules/default.json";
    std::vector<Error> errors;
    Result<RuleTable> r = load_rules(path, &errors);
    ASSERT_TRUE(r.ok()) << join_errors(errors);
    const RuleTable& t = r.value();
    EXPECT_TRUE(t.warnings.empty()) << join_errors(t.warnings);
    EXPECT_EQ(t.source, path);
    EXPECT_GE(t.rules.size(), 5u);
    EXPECT_TRUE(t.rules.back().unconditional);
    EXPECT_TRUE(t.budget.has_value());
    EXPECT_EQ(t.tiers[t.default_tier], "high");
    // The fallback (most far characters): an impostor (the baked skin), clip playback every 4-8 frames.
    const RuleDef& fb = t.rules.back();
    EXPECT_EQ(t.geom_levels[fb.geom_level].method, GeomMethod::Impostor);
    EXPECT_EQ(t.geom_levels[fb.geom_level].layers, kLayerSkeleton | kLayerSkin);
    EXPECT_GE(t.find_geom_level("proxy"), 0) << "the rigid proxy level stays for rules and the budget";
    EXPECT_EQ(t.anim_levels[fb.anim_level].walk, WalkMethod::ClipPlayback);
    EXPECT_GE(t.anim_levels[fb.anim_level].update_interval, 4);
    EXPECT_LE(t.anim_levels[fb.anim_level].update_interval, 8);
    EXPECT_EQ(t.geom_levels[0].method, GeomMethod::Subdivided);
    EXPECT_EQ(t.anim_levels[0].ik, IkSolver::Dls);
}

TEST(RuleParser, SmallFileCompiles) {
    const RuleTable t = must_parse(small_rules());
    ASSERT_EQ(t.rules.size(), 4u);
    EXPECT_EQ(t.compiled.size(), 4u);
    EXPECT_EQ(t.geom_levels[0].layers, kLayerSkeleton | kLayerMuscle | kLayerFat | kLayerSkin);
    EXPECT_EQ(t.geom_levels[1].layers, kLayerSkeleton | kLayerSkin);
    EXPECT_EQ(t.anim_levels[1].update_interval, 2);
    EXPECT_EQ(t.hysteresis.min_seconds, 0.08f);
    EXPECT_FALSE(t.budget.has_value());
    EXPECT_EQ(t.find_rule("mid"), 2);
    EXPECT_EQ(t.geom_lod(1).geomorph_s, 0.1f);
    EXPECT_EQ(t.anim_lod(200).level, 2);  // clamped to the last level
}

TEST(RuleParser, SyntaxErrorGivesLineAndColumn) {
    // Line 3 lacks the ':' after "rules"; the parser stops at the '[' in column 11.
    const std::string text = "{\n  \"tiers\": [\"a\"],\n  \"rules\" []\n}\n";
    Result<RuleTable> r = parse_rules(text, "broken.json");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().file, "broken.json");
    EXPECT_EQ(r.error().line, 3);
    EXPECT_EQ(r.error().column, 11);
    EXPECT_NE(r.error().message.find("syntax error"), std::string::npos) << r.error().message;
    EXPECT_EQ(r.error().to_string().rfind("broken.json:3:11: ", 0), 0u) << r.error().to_string();
}

TEST(RuleParser, CommentsAreAllowed) {
    std::string text = small_rules().dump(2);
    text.insert(1, "\n  // tuned for the market scene\n");
    EXPECT_TRUE(parse_rules(text, "c.json").ok());
}

TEST(RuleParser, MissingFileNamesThePath) {
    Result<RuleTable> r = load_rules("/nonexistent/rules.json");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().file, "/nonexistent/rules.json");
    EXPECT_NE(r.error().message.find("cannot open"), std::string::npos);
}

TEST(RuleParser, UnknownAttributeIsAnError) {
    json j = small_rules();
    j["rules"][1]["when"] = {{"distanse", {{"lt", 10}}}};
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/rules/1/when/distanse", "unknown attribute 'distanse'")) << join_errors(e);
}

TEST(RuleParser, UnknownComparisonAndBadOperand) {
    json j = small_rules();
    j["rules"][1]["when"] = {{"distance", {{"below", 10}}}};
    j["rules"][2]["when"] = {{"distance", {{"lt", "ten"}}}};
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/rules/1/when/distance/below", "unknown comparison 'below'")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/rules/2/when/distance/lt", "expected a number")) << join_errors(e);
}

TEST(RuleParser, UnknownLevelNamesAreErrors) {
    json j = small_rules();
    j["rules"][1]["then"]["geometry"] = "ultra";
    j["rules"][2]["then"]["animation"] = "ballet";
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/rules/1/then/geometry", "unknown geometric level 'ultra'")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/rules/2/then/animation", "unknown animation level 'ballet'")) << join_errors(e);
}

TEST(RuleParser, ImpossibleRangeIsUnreachable) {
    json j = small_rules();
    j["rules"][1]["when"] = {{"distance", {{"min", 30}, {"max", 10}}}};
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/rules/1/when/distance", "impossible range")) << join_errors(e);
}

TEST(RuleParser, ContradictoryCombinationIsUnreachable) {
    json j = small_rules();
    // distance < 5 and not (distance < 10): empty.
    j["rules"][1]["when"] = json::parse(R"({"distance": {"lt": 5}, "not": {"distance": {"lt": 10}}})");
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/rules/1/when", "unreachable rule")) << join_errors(e);
}

TEST(RuleParser, RuleAfterUnconditionalIsUnreachable) {
    json j = small_rules();
    j["rules"].insert(j["rules"].begin() + 1, json::parse(R"({"name": "all", "then": {"geometry": "mid", "animation": "kin"}})"));
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/rules/2", "unreachable rule 'near'")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/rules/4", "unreachable rule 'far'")) << join_errors(e);
}

TEST(RuleParser, MissingFallbackIsAnError) {
    json j = small_rules();
    j["rules"].erase(3);
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/rules/2", "no fallback")) << join_errors(e);
}

TEST(RuleParser, ShadowedRuleIsAWarning) {
    json j = small_rules();
    // distance < 8 is wholly inside "near" (distance < 10) which comes first.
    j["rules"].insert(j["rules"].begin() + 2, json::parse(
        R"({"name": "closer", "when": {"distance": {"lt": 8}}, "then": {"geometry": "rich", "animation": "full"}})"));
    const RuleTable t = must_parse(j);
    ASSERT_EQ(t.warnings.size(), 1u);
    EXPECT_EQ(t.warnings[0].path, "/rules/2");
    EXPECT_NE(t.warnings[0].message.find("rule 'closer' never fires"), std::string::npos) << t.warnings[0].message;
}

TEST(RuleParser, LayersPeelOnlyTheFatSprings) {
    json j = small_rules();
    j["geometric_levels"][0]["layers"] = {"skeleton", "muscle", "skin"};  // layered without fat springs
    j["geometric_levels"][1]["layers"] = {"skeleton", "skin"};            // skin by LBS only (the default)
    const RuleTable t = must_parse(j);
    EXPECT_EQ(t.geom_levels[0].layers, kLayerSkeleton | kLayerMuscle | kLayerSkin);
    EXPECT_EQ(t.geom_levels[1].layers, kLayerSkeleton | kLayerSkin);
    j["geometric_levels"][0]["layers"] = {"skeleton", "fat", "skin"};     // no muscles to hang the fat on
    j["geometric_levels"][1]["layers"] = {"skeleton", "muscle", "skin"};  // LBS runs no muscles
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/geometric_levels/0/layers", "need skeleton, muscle and skin")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/geometric_levels/1/layers", "layers are fixed")) << join_errors(e);
}

TEST(RuleParser, LevelFieldErrors) {
    json j = small_rules();
    j["geometric_levels"][0]["method"] = "voxels";
    j["geometric_levels"][1]["theta_steps"] = 2;
    j["geometric_levels"][2]["layers"] = {"bones"};
    j["animation_levels"][0]["walk"] = "run";
    j["animation_levels"][1]["update_interval"] = 0;
    j["animation_levels"][2]["name"] = "kin";
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/geometric_levels/0/method", "unknown value \"voxels\"")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/geometric_levels/1/theta_steps", "out of range")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/geometric_levels/2/layers/0", "unknown layer")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/animation_levels/0/walk", "unknown value \"run\"")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/animation_levels/1/update_interval", "out of range")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/animation_levels/2/name", "duplicate animation level name 'kin'")) << join_errors(e);
}

TEST(RuleParser, SimplifyErrorOnlyOnSkinnedMeshAndInRange) {
    json j = small_rules();
    j["geometric_levels"][0]["simplify_error"] = 0.01;  // not a skinned_mesh level
    j["geometric_levels"][1]["simplify_error"] = 0.5;   // above the 0.25 limit
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/geometric_levels/0/simplify_error", "only a 'skinned_mesh' level")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/geometric_levels/1/simplify_error", "out of range")) << join_errors(e);
}

TEST(RuleParser, UnknownKeysAndTiersAreErrors) {
    json j = small_rules();
    j["hysteresis"]["min_frame"] = 3;
    j["rules"][1]["when"] = {{"tier", "ultra"}};
    j["rule"] = json::array();
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/hysteresis/min_frame", "unknown key 'min_frame'")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/rules/1/when/tier", "unknown tier 'ultra'")) << join_errors(e);
    EXPECT_TRUE(has_error(e, "/rule", "unknown key 'rule'")) << join_errors(e);
}

TEST(RuleParser, MissingSectionsAreErrors) {
    json j = small_rules();
    j.erase("animation_levels");
    const auto e = errors_of(j);
    EXPECT_TRUE(has_error(e, "/animation_levels", "missing or empty array")) << join_errors(e);
}

}  // namespace
}  // namespace aloha
