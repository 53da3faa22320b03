// LodBudget: the rule file's budget section is honoured with no host overrides, the host's overrides
// win, and configuring again with a reloaded table applies its budget (targets, on/off, mode).
// Also the budget section's parsing and its errors.
#include "systems/lod/budget_driver.hpp"
#include "systems/lod/rule_set.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace aloha {
namespace {

using lod_test::must_parse;
using lod_test::small_rules;
using nlohmann::json;
using Mode = BudgetStatus::Mode;

json with_parts(double anim_ms, double geom_ms) {
    json j = small_rules();
    j["budget"] = {{"settle_frames", 3},
                   {"animation", {{"target_ms", anim_ms}, {"tolerance", 0.04}}},
                   {"geometry", {{"target_ms", geom_ms}, {"gain", 0.5}, {"max_demotion", 2}}}};
    return j;
}

TEST(BudgetDriver, TheFilesBudgetRunsWithoutOverrides) {
    const RuleTable t = must_parse(with_parts(1.5, 6.0));
    ASSERT_TRUE(t.budget.has_value());
    EXPECT_TRUE(t.budget->has_parts());
    EXPECT_EQ(t.budget->settle_frames, 3);
    EXPECT_FLOAT_EQ(t.budget->animation.tolerance, 0.04f);
    EXPECT_FLOAT_EQ(t.budget->geometry.gain, 0.5f);
    EXPECT_EQ(t.budget->geometry.max_demotion, 2);
    EXPECT_EQ(t.budget->animation.max_demotion, 3);  // the section's default
    EXPECT_FLOAT_EQ(t.budget->trim_smoothing, 0.0f);  // trimming off unless the file turns it on
    EXPECT_FLOAT_EQ(t.budget->animation.react_tolerance, 0.25f);
    EXPECT_FLOAT_EQ(t.budget->dwell, 0.0f);  // no dwell unless the file asks for one
    EXPECT_FLOAT_EQ(t.budget->confidence, 0.0f);  // the band test unless the file asks for the confidence test
    json trimmed = with_parts(1.5, 6.0);
    trimmed["budget"]["trim_smoothing"] = 0.02;
    trimmed["budget"]["dwell"] = 1.5;
    trimmed["budget"]["animation"]["react_tolerance"] = 0.3;
    const RuleTable tt = must_parse(trimmed);
    EXPECT_FLOAT_EQ(tt.budget->trim_smoothing, 0.02f);
    EXPECT_FLOAT_EQ(tt.budget->dwell, 1.5f);
    EXPECT_FLOAT_EQ(tt.budget->animation.react_tolerance, 0.3f);
    EXPECT_FLOAT_EQ(tt.budget->geometry.react_tolerance, 0.25f);
    LodBudget b;
    std::vector<LodState> states(4);
    b.configure(t, {}, states);
    const BudgetStatus s = b.status();
    EXPECT_EQ(s.mode, Mode::Parts);
    EXPECT_TRUE(b.active());
    EXPECT_FLOAT_EQ(s.animation.target_ms, 1.5f);
    EXPECT_FLOAT_EQ(s.geometry.target_ms, 6.0f);

    // One total, the original controller.
    json one = small_rules();
    one["budget"] = {{"target_ms", 9.0}};
    b.configure(must_parse(one), {}, states);
    EXPECT_EQ(b.status().mode, Mode::Total);
    EXPECT_FLOAT_EQ(b.status().params.target_ms, 9.0f);

    // A budget written but switched off, and no budget at all.
    json off = with_parts(1.5, 6.0);
    off["budget"]["enabled"] = false;
    b.configure(must_parse(off), {}, states);
    EXPECT_EQ(b.status().mode, Mode::Off);
    b.configure(must_parse(small_rules()), {}, states);
    EXPECT_EQ(b.status().mode, Mode::Off);
}

TEST(BudgetDriver, OverridesWin) {
    const RuleTable t = must_parse(with_parts(2.0, 6.0));
    std::vector<LodState> states(2);
    LodBudget b;
    BudgetOverrides o;
    o.total_ms = 4.0;  // the file's 1:3 split kept, scaled to 4 ms
    b.configure(t, o, states);
    EXPECT_EQ(b.status().mode, Mode::Parts);
    EXPECT_FLOAT_EQ(b.status().animation.target_ms, 1.0f);
    EXPECT_FLOAT_EQ(b.status().geometry.target_ms, 3.0f);
    o = {};
    o.geometry_ms = 5.0;
    b.configure(t, o, states);
    EXPECT_FLOAT_EQ(b.status().animation.target_ms, 2.0f);
    EXPECT_FLOAT_EQ(b.status().geometry.target_ms, 5.0f);
    o = {};
    o.single_total_ms = 7.0;  // the single-total controller, whatever the file says
    b.configure(t, o, states);
    EXPECT_EQ(b.status().mode, Mode::Total);
    EXPECT_FLOAT_EQ(b.status().params.target_ms, 7.0f);
    o = {};
    o.enabled = false;
    b.configure(t, o, states);
    EXPECT_EQ(b.status().mode, Mode::Off);
    json off = with_parts(2.0, 6.0);
    off["budget"]["enabled"] = false;
    o.enabled = true;
    b.configure(must_parse(off), o, states);
    EXPECT_EQ(b.status().mode, Mode::Parts);
    // A file without a budget and only a total from the host: one total.
    o = {};
    o.total_ms = 3.0;
    b.configure(must_parse(small_rules()), o, states);
    EXPECT_EQ(b.status().mode, Mode::Total);
    EXPECT_FLOAT_EQ(b.status().params.target_ms, 3.0f);
}

TEST(BudgetDriver, ReloadAppliesTheNewBudget) {
    // Through a RuleSet and its file, as a host reloading live would.
    namespace fs = std::filesystem;
    const fs::path path = fs::temp_directory_path() / ("budget_reload_" + std::to_string(::getpid()) + ".json");
    auto write = [&](const json& j, int seconds) {
        std::ofstream(path) << j.dump(2);
        fs::last_write_time(path, fs::file_time_type::clock::now() + std::chrono::seconds(seconds));
    };
    write(with_parts(1.0, 4.0), 0);
    RuleSet set;
    ASSERT_TRUE(set.load(path.string()).ok());
    LodBudget b;
    std::vector<LodState> states(3);
    b.configure(set.table(), {}, states);
    EXPECT_FLOAT_EQ(b.status().geometry.target_ms, 4.0f);
    states[0].budget_demotion = 2;  // as if the controllers had demoted
    states[1].anim_demotion = 1;

    write(with_parts(1.0, 8.0), 10);  // new geometry target
    ASSERT_TRUE(set.poll().value());
    b.configure(set.table(), {}, states);
    EXPECT_FLOAT_EQ(b.status().geometry.target_ms, 8.0f);
    EXPECT_EQ(states[0].budget_demotion, 2);  // same mode: what the controllers did is kept

    json no_anim = with_parts(1.0, 8.0);
    no_anim["budget"].erase("animation");
    write(no_anim, 20);  // the animation part dropped: its demotions are given back
    ASSERT_TRUE(set.poll().value());
    b.configure(set.table(), {}, states);
    EXPECT_FALSE(b.status().animation.active);
    EXPECT_EQ(states[1].anim_demotion, 0);
    EXPECT_EQ(states[0].budget_demotion, 2);

    json off = no_anim;
    off["budget"]["enabled"] = false;
    write(off, 30);  // switched off: everyone back to the rules' levels
    ASSERT_TRUE(set.poll().value());
    b.configure(set.table(), {}, states);
    EXPECT_EQ(b.status().mode, Mode::Off);
    EXPECT_EQ(states[0].budget_demotion, 0);
    fs::remove(path);
}

TEST(BudgetDriver, BadBudgetSectionsAreRefusedWithTheirPath) {
    auto errors_of = [](const json& j) {
        std::vector<Error> errors;
        EXPECT_FALSE(parse_rules(j.dump(2), "budget.json", &errors).ok());
        return join_errors(errors);
    };
    json both = with_parts(1.0, 2.0);
    both["budget"]["target_ms"] = 3.0;
    EXPECT_NE(errors_of(both).find("/budget/target_ms"), std::string::npos);
    json none = small_rules();
    none["budget"] = {{"smoothing", 0.3}};
    EXPECT_NE(errors_of(none).find("missing 'target_ms'"), std::string::npos);
    json typo = with_parts(1.0, 2.0);
    typo["budget"]["geometry"]["target"] = 1.0;
    EXPECT_NE(errors_of(typo).find("/budget/geometry/target: unknown key"), std::string::npos);
    json no_target = small_rules();
    no_target["budget"] = {{"animation", {{"gain", 0.5}}}};
    EXPECT_NE(errors_of(no_target).find("/budget/animation: missing required key 'target_ms'"), std::string::npos);
    json range = with_parts(1.0, 2.0);
    range["budget"]["animation"]["gain"] = 0.0;
    EXPECT_NE(errors_of(range).find("/budget/animation/gain"), std::string::npos);
    json react = with_parts(1.0, 2.0);
    react["budget"]["geometry"]["react_tolerance"] = 1.5;
    EXPECT_NE(errors_of(react).find("/budget/geometry/react_tolerance"), std::string::npos);
    json trim = with_parts(1.0, 2.0);
    trim["budget"]["trim_smoothing"] = -0.1;
    EXPECT_NE(errors_of(trim).find("/budget/trim_smoothing"), std::string::npos);
    // The dwell (time constants) and the confidence (standard errors), each 0-10: the file, the key's
    // JSON path (as for every budget key) and the range.
    for (const char* key : {"dwell", "confidence"}) {
        for (double bad : {-0.5, 11.0}) {
            json budget = with_parts(1.0, 2.0);
            budget["budget"][key] = bad;
            const std::string e = errors_of(budget);
            std::printf("%s\n", e.c_str());
            EXPECT_NE(e.find("budget.json:"), std::string::npos) << e;
            EXPECT_NE(e.find(std::string("/budget/") + key), std::string::npos) << e;
            EXPECT_NE(e.find("out of range [0.0, 10.0]"), std::string::npos) << e;
        }
    }
    json flag = with_parts(1.0, 2.0);
    flag["budget"]["enabled"] = "yes";
    EXPECT_NE(errors_of(flag).find("expected true or false"), std::string::npos);
}

}  // namespace
}  // namespace aloha
