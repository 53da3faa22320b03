// Bad rule files, joint-limit tables and muscle layouts (docs/BAD_INPUT.md, sections "Rules",
// "Joint limits", "Muscles"). Rows R1.., L1.., M1... The regression tests near the end are crashes the fuzzers found (all fixed)
// (an uncaught nlohmann::json::out_of_range escapes the loader and ends the program); they pass once
// the loaders catch it (see the comment on each).
#include "bad_input.hpp"

#include "engine/anim/skeleton.hpp"
#include "engine/assets/humanoid_definition.hpp"
#include "engine/assets/joint_limits.hpp"
#include "systems/geometry/muscle/muscle_loader.hpp"
#include "systems/lod/rule_table.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace aloha {
namespace {

using robustness::refused;
using robustness::TempDir;

const std::string kData = std::string(ALOHA_SOURCE_DIR) + "/data/";

// The project's humanoid skeleton (data/characters/humanoid.json, CMU joint names) for the default body.
Result<Skeleton> humanoid() {
    Result<HumanoidDefinition> def = load_humanoid_definition(kData + "characters/humanoid.json");
    if (!def.ok()) return def.error();
    return build_skeleton(humanoid_skeleton(def.value(), HumanoidBody{}), "humanoid.json");
}

// `text` with the first occurrence of `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

TEST(RulesBadInput, ShippedFileVariants) {
    const std::string rules = robustness::slurp(kData + "rules/default.json");
    ASSERT_TRUE(parse_rules(rules, "default.json").ok());
    auto r = parse_rules(rules.substr(0, rules.size() / 2), "rules.json");
    EXPECT_TRUE(refused(r, "R1 truncated rule file", "rules.json", {"invalid JSON"}));
    if (!r.ok()) {
        EXPECT_GT(r.error().line, 1);
    }
    EXPECT_TRUE(refused(parse_rules(replaced(rules, "\"band\": 0.1", "\"band\": \"wide\""), "rules.json"),
                        "R2 string for a number", "rules.json", {"/hysteresis/band"}));
    EXPECT_TRUE(refused(parse_rules(replaced(rules, "\"band\": 0.1", "\"band\": NaN"), "rules.json"), "R3 NaN literal",
                        "rules.json", {"invalid JSON"}));
    EXPECT_TRUE(refused(parse_rules(replaced(rules, "\"theta_steps\": 24", "\"theta_steps\": 1000000000"), "rules.json"),
                        "R4 theta_steps 1e9", "rules.json", {"/geometric_levels/0/theta_steps"}));
    EXPECT_TRUE(refused(parse_rules(replaced(rules, "\"min_seconds\": 0.2", "\"min_seconds\": -1"), "rules.json"),
                        "R5 negative min_seconds", "rules.json", {"/hysteresis/min_seconds"}));
    EXPECT_TRUE(refused(parse_rules(replaced(rules, "\"update_interval\": 1", "\"update_interval\": 0"), "rules.json"),
                        "R6 update_interval 0", "rules.json", {"/animation_levels/0/update_interval"}));
}

TEST(RulesBadInput, HostileConditionsAndFiles) {
    // 2^20 alternatives from 20 ANDed two-way ORs: refused before expanding them all.
    std::string when = R"({"all": [)";
    for (int i = 0; i < 20; ++i) when += std::string(i ? "," : "") + R"({"any": [{"distance": {"lt": 1}}, {"speed": {"gt": 2}}]})";
    when += "]}";
    const std::string levels = R"("geometric_levels": [{"name": "g", "method": "rigid_proxy"}],
        "animation_levels": [{"name": "a", "walk": "clip"}], )";
    const std::string text = "{" + levels + R"("rules": [{"name": "x", "when": )" + when +
                             R"(, "then": {"geometry": "g", "animation": "a"}}, {"name": "y", "then": {"geometry": "g", "animation": "a"}}]})";
    EXPECT_TRUE(refused(parse_rules(text, "rules.json"), "R8 2^20 condition alternatives", "rules.json",
                        {"/rules/0/when", "too complex"}));
    std::string nots;
    for (int i = 0; i < 40; ++i) nots += R"({"not": )";
    nots += R"({"visible": true})" + std::string(40, '}');
    const std::string deep = "{" + levels + R"("rules": [{"name": "x", "when": )" + nots +
                             R"(, "then": {"geometry": "g", "animation": "a"}}, {"name": "y", "then": {"geometry": "g", "animation": "a"}}]})";
    // not(not(...)) 40 times is valid (= visible); deeper files are refused before parsing by the
    // JSON depth guard (64 levels), so compile_condition's recursion is bounded.
    EXPECT_TRUE(parse_rules(deep, "rules.json").ok()) << "R9 40 nested nots";
    TempDir dir("rules_files");
    EXPECT_TRUE(refused(load_rules(dir.file("nope.json")), "R10 missing rule file", "nope.json", {}));
    std::filesystem::create_directories(dir.file("folder.json"));
    EXPECT_TRUE(refused(load_rules(dir.file("folder.json")), "R11 rule path is a folder", "folder.json", {}));
}

// Regression (found while fuzzing, fixed): a threshold of 1e39 is a finite double but becomes +inf as the float stored in the box,
// and is accepted silently. Fix: systems/lod/rule_conditions.cpp operand(): refuse values with
// |v| > std::numeric_limits<float>::max() ("value 1e39 does not fit a float").
TEST(RulesBadInput, ThresholdThatOverflowsFloat) {
    const std::string rules = robustness::slurp(kData + "rules/default.json");
    EXPECT_TRUE(refused(parse_rules(replaced(rules, "\"ge\": 0.8", "\"ge\": 1e39"), "rules.json"),
                        "R7 threshold 1e39 (float overflow)", "rules.json", {"/rules/2/when/importance"}));
}

// Regression (found while fuzzing, fixed): a folder given as the rule file or muscle layout reads as an empty file, so the user sees
// "JSON syntax error ... unexpected end of input" at 1:1 instead of "is a folder". Fix:
// systems/lod/rule_parser.cpp load_rules() and systems/geometry/muscle/muscle_loader.cpp
// load_muscle_defs(): read through engine/assets/file_io.hpp read_text_file() (which reports "not a
// regular file" and refuses files over 256 MiB) instead of std::ifstream.
TEST(RulesBadInput, FolderIsNamedAsAFolder) {
    TempDir dir("folders");
    std::filesystem::create_directories(dir.file("folder.json"));
    EXPECT_TRUE(refused(load_rules(dir.file("folder.json")), "R11 rule path is a folder", "folder.json", {"regular file"}));
    Result<Skeleton> skeleton = humanoid();
    ASSERT_TRUE(skeleton.ok()) << skeleton.error().to_string();
    EXPECT_TRUE(refused(load_muscle_set(dir.file("folder.json"), skeleton.value()), "M7 layout path is a folder",
                        "folder.json", {"regular file"}));
}

// Fuzzer crash (fuzz_rules, tests/robustness/crashes/fuzz_rules/number_overflow.json): 1e999 throws
// nlohmann::json::out_of_range (406), which parse_rules does not catch. Fix: systems/lod/rule_parser.cpp
// parse_rules(): add `catch (const json::out_of_range& e)` after the parse_error handler returning
// make_error(source_name, std::string("JSON ") + e.what(), line, column) with the position of the
// literal (as host/scene/json_reader.cpp parse_json_text does), or catch json::exception.
TEST(RulesBadInput, NumberOverflowIsAnError) {
    EXPECT_TRUE(refused(parse_rules(R"({"hysteresis": {"band": 1e999}})", "rules.json"), "R12 1e999", "rules.json",
                        {"number overflow"}));
    const std::string crash = robustness::slurp(std::string(ALOHA_SOURCE_DIR) + "/tests/robustness/crashes/fuzz_rules/number_overflow.json");
    EXPECT_FALSE(parse_rules(crash, "crash.json").ok());
}

TEST(JointLimitsBadInput, BadTables) {
    const std::string limits = robustness::slurp(kData + "characters/humanoid_limits.json");
    ASSERT_TRUE(parse_joint_limits(limits, "limits.json").ok());
    EXPECT_TRUE(refused(parse_joint_limits(limits.substr(0, limits.size() / 2), "limits.json"), "L1 truncated table",
                        "limits.json", {"invalid JSON"}));
    EXPECT_TRUE(refused(parse_joint_limits(R"({"joints": {"A": {"min": [0, 0, 0], "max": [0, "9", 0]}}})", "limits.json"),
                        "L2 string for an angle", "limits.json", {"/joints/A/max/1"}));
    EXPECT_TRUE(refused(parse_joint_limits(R"({"joints": {"A": {"min": [0, 0, -400], "max": [0, 0, 0]}}})", "limits.json"),
                        "L3 angle beyond 180 degrees", "limits.json", {"/joints/A/min/2"}));
    EXPECT_TRUE(refused(parse_joint_limits(R"({"joints": {"A": {"min": [10, 0, 0], "max": [0, 0, 0]}}})", "limits.json"),
                        "L4 min above max", "limits.json", {"/joints/A", "min exceeds max"}));
    EXPECT_TRUE(refused(parse_joint_limits(R"({"joints": {"A": {"min": [0, 0], "max": [0, 0, 0]}}})", "limits.json"),
                        "L5 two angles", "limits.json", {"/joints/A/min"}));
    EXPECT_TRUE(refused(parse_joint_limits(R"({"units": "grads", "joints": {}})", "limits.json"), "L6 unknown units",
                        "limits.json", {"/units"}));
    Result<Skeleton> skeleton = humanoid();
    ASSERT_TRUE(skeleton.ok()) << skeleton.error().to_string();
    auto unknown = parse_joint_limits(R"({"joints": {"Tail": {"min": [0, 0, 0], "max": [1, 1, 1]}}})", "limits.json");
    ASSERT_TRUE(unknown.ok());
    EXPECT_TRUE(refused(apply_joint_limits(skeleton.value(), unknown.value()), "L7 joint not in the skeleton",
                        "limits.json", {"/joints/Tail", "not in the skeleton"}));
    TempDir dir("limits_files");
    EXPECT_TRUE(refused(load_joint_limits(dir.file("nope.json")), "L8 missing table", "nope.json", {}));
}

// Fuzzer crash (fuzz_joint_limits, tests/robustness/crashes/fuzz_joint_limits/number_overflow.json: "1e999"):
// nlohmann::json::out_of_range escapes. Fix: engine/assets/joint_limits.cpp parse_joint_limits(): also
// catch json::out_of_range (or json::exception) around json::parse and return
// make_error(source_name, "invalid JSON: " + what, line, column).
TEST(JointLimitsBadInput, NumberOverflowIsAnError) {
    EXPECT_TRUE(refused(parse_joint_limits(R"({"joints": {"A": {"min": [0, 0, 1e999], "max": [0, 0, 0]}}})", "limits.json"),
                        "L9 1e999", "limits.json", {"number overflow"}));
    const std::string crash = robustness::slurp(std::string(ALOHA_SOURCE_DIR) + "/tests/robustness/crashes/fuzz_joint_limits/number_overflow.json");
    EXPECT_FALSE(parse_joint_limits(crash, "crash.json").ok());
}

class MusclesBadInput : public ::testing::Test {
protected:
    void SetUp() override {
        Result<Skeleton> s = humanoid();
        ASSERT_TRUE(s.ok()) << s.error().to_string();
        skeleton_ = std::move(s.value());
    }
    // Writes `text` as muscles.json and loads it against the humanoid skeleton.
    Result<MuscleSet> load(const std::string& text) { return load_muscle_set(dir_.write("muscles.json", text), skeleton_); }

    TempDir dir_{"muscles"};
    Skeleton skeleton_;
    const std::string one_ = R"({"muscles": [{"name": "m", "origin": {"joint": "LeftShoulder", "offset": [0, -0.02, 0.02]},
        "insertion": {"joint": "LeftElbow", "along": 0.1}, "radii": [0.03, 0.02]}]})";
};

TEST_F(MusclesBadInput, BadLayouts) {
    ASSERT_TRUE(load(one_).ok()) << load(one_).error().to_string();
    const std::string shipped = robustness::slurp(kData + "characters/humanoid_muscles.json");
    EXPECT_TRUE(refused(load(shipped.substr(0, shipped.size() / 2)), "M1 truncated layout", "muscles.json", {"invalid JSON"}));
    EXPECT_TRUE(refused(load(replaced(one_, "LeftElbow", "LeftElbo")), "M2 unknown joint", "muscles.json",
                        {"/muscles/0/insertion/joint", "unknown joint"}));
    EXPECT_TRUE(refused(load(replaced(one_, "[0.03, 0.02]", "[0.03, -0.02]")), "M3 negative radius", "muscles.json",
                        {"/muscles/0/radii"}));
    EXPECT_TRUE(refused(load(replaced(one_, "\"along\": 0.1", "\"along\": \"far\"")), "M4 string for a number",
                        "muscles.json", {"/muscles/0/insertion/along"}));
    EXPECT_TRUE(refused(load(replaced(one_, "[0, -0.02, 0.02]", "[0, 1e39, 0.02]")), "M5 offset 1e39 (float overflow)",
                        "muscles.json", {"/muscles/0/origin", "NaN or infinite"}));
    EXPECT_TRUE(refused(load_muscle_set(dir_.file("nope.json"), skeleton_), "M6 missing layout", "nope.json", {}));
    std::filesystem::create_directories(dir_.file("folder.json"));
    EXPECT_TRUE(refused(load_muscle_set(dir_.file("folder.json"), skeleton_), "M7 layout path is a folder", "folder.json", {}));
}

// Same fuzzer finding as the rule and joint-limit loaders (not fuzzed directly: no memory entry point
// for text). Fix: systems/geometry/muscle/muscle_loader.cpp load_muscle_defs(): catch
// json::out_of_range (or json::exception) next to json::parse_error.
TEST_F(MusclesBadInput, NumberOverflowIsAnError) {
    EXPECT_TRUE(refused(load(replaced(one_, "0.1", "1e999")), "M8 1e999", "muscles.json", {"number overflow"}));
}

}  // namespace
}  // namespace aloha
