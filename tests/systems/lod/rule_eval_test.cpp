// RuleEvalJob: first matching rule fires; strict/inclusive bounds; combinators; tiers; value
// hysteresis widens only the character's current rule.
#include "systems/lod/rule_eval.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace aloha {
namespace {

using lod_test::at_distance;
using lod_test::must_parse;
using lod_test::small_rules;
using nlohmann::json;

std::vector<LodRequest> eval(const RuleTable& t, const std::vector<LodAttributes>& a,
                             const std::vector<LodState>& states = {}, uint8_t tier = 0) {
    std::vector<LodRequest> out(a.size());
    RuleEvalJob job{&t, a, states, tier, out};
    std::vector<std::string> errors;
    EXPECT_TRUE(job.Validate(&errors));
    job.Run();
    return out;
}

TEST(RuleEval, FirstMatchingRuleFires) {
    const RuleTable t = must_parse(small_rules());
    LodAttributes hidden = at_distance(5.0f);
    hidden.visible = 0;
    const auto r = eval(t, {at_distance(5.0f), at_distance(15.0f), at_distance(50.0f), hidden});
    EXPECT_EQ(r[0].rule_id, 1);  // near
    EXPECT_EQ(r[0].geom_level, 0);
    EXPECT_EQ(r[0].anim_level, 0);
    EXPECT_EQ(r[1].rule_id, 2);  // mid
    EXPECT_EQ(r[1].geom_level, 1);
    EXPECT_EQ(r[1].anim_level, 1);
    EXPECT_EQ(r[2].rule_id, 3);  // far (fallback)
    EXPECT_EQ(r[2].geom_level, 2);
    EXPECT_EQ(r[3].rule_id, 0);  // off, even though near
    EXPECT_EQ(r[3].geom_level, 3);
}

TEST(RuleEval, StrictAndInclusiveBounds) {
    json j = small_rules();
    j["rules"][2]["when"] = {{"distance", {{"le", 20}}}};
    const RuleTable t = must_parse(j);
    const float just_below_10 = std::nextafter(10.0f, 0.0f);
    const auto r = eval(t, {at_distance(just_below_10), at_distance(10.0f), at_distance(20.0f),
                            at_distance(std::nextafter(20.0f, 100.0f))});
    EXPECT_EQ(r[0].rule_id, 1);  // lt 10 holds just below 10
    EXPECT_EQ(r[1].rule_id, 2);  // lt 10 fails at exactly 10
    EXPECT_EQ(r[2].rule_id, 2);  // le 20 holds at exactly 20
    EXPECT_EQ(r[3].rule_id, 3);
}

TEST(RuleEval, NanFallsBackToTheLastRule) {
    const RuleTable t = must_parse(small_rules());
    const auto r = eval(t, {at_distance(std::numeric_limits<float>::quiet_NaN())});
    EXPECT_EQ(r[0].rule_id, 3);
}

TEST(RuleEval, AnyNotAndTier) {
    json j = small_rules();
    // near: (distance < 10 or importance >= 0.9) and not speed > 5, only on tier "high".
    j["rules"][1]["when"] = json::parse(R"({
        "any": [ {"distance": {"lt": 10}}, {"importance": {"ge": 0.9}} ],
        "not": {"speed": {"gt": 5}},
        "tier": "high" })");
    const RuleTable t = must_parse(j);
    LodAttributes far_hero = at_distance(50.0f);
    far_hero.importance = 0.95f;
    LodAttributes near_fast = at_distance(5.0f);
    near_fast.speed = 6.0f;
    LodAttributes near_at_5 = at_distance(5.0f);
    near_at_5.speed = 5.0f;  // not (speed > 5) holds at exactly 5
    const auto high = eval(t, {at_distance(5.0f), far_hero, near_fast, near_at_5}, {}, 1);
    EXPECT_EQ(high[0].rule_id, 1);
    EXPECT_EQ(high[1].rule_id, 1);
    EXPECT_EQ(high[2].rule_id, 2);  // falls to mid (distance < 20)
    EXPECT_EQ(high[3].rule_id, 1);
    const auto low = eval(t, {at_distance(5.0f)}, {}, 0);
    EXPECT_EQ(low[0].rule_id, 2);
}

TEST(RuleEval, ActiveRuleIsWidenedByTheBand) {
    const RuleTable t = must_parse(small_rules());  // band 0.1: mid's "lt 20" becomes "< 22"
    std::vector<LodState> states(3);
    for (LodState& s : states) s.rule_id = 2;  // currently on "mid"
    const auto with = eval(t, {at_distance(21.0f), at_distance(22.5f), at_distance(9.5f)}, states);
    EXPECT_EQ(with[0].rule_id, 2);  // stays: 21 < 22
    EXPECT_EQ(with[1].rule_id, 3);  // leaves: crossed the threshold by more than the band
    EXPECT_EQ(with[2].rule_id, 1);  // an earlier rule still fires at its own threshold
    const auto without = eval(t, {at_distance(21.0f)});
    EXPECT_EQ(without[0].rule_id, 3);
}

TEST(RuleEval, OccludedEstimateGetsABandCertainlyHiddenDoesNot) {
    json j = small_rules();  // band 0.1
    j["rules"][1]["when"] = {{"occluded", {{"ge", 1}}}};    // certainly hidden
    j["rules"][2]["when"] = {{"occluded", {{"ge", 0.7}}}};  // mostly hidden (estimate): stays down to 0.63
    const RuleTable t = must_parse(j);
    auto occluded = [](float o) {
        LodAttributes a = at_distance(5.0f);
        a.occluded = o;
        return a;
    };
    std::vector<LodState> on_mostly(3), on_hidden(1);
    for (LodState& s : on_mostly) s.rule_id = 2;
    on_hidden[0].rule_id = 1;
    const auto stay = eval(t, {occluded(0.65f), occluded(0.62f), occluded(1.0f)}, on_mostly);
    EXPECT_EQ(stay[0].rule_id, 2);  // within the band
    EXPECT_EQ(stay[1].rule_id, 3);  // below 0.63
    EXPECT_EQ(stay[2].rule_id, 1);  // the earlier rule at its own bound
    EXPECT_EQ(eval(t, {occluded(0.65f)})[0].rule_id, 3);               // entering needs 0.7
    EXPECT_EQ(eval(t, {occluded(0.99f)}, on_hidden)[0].rule_id, 2);  // leaves hidden as soon as a part shows
}

TEST(RuleEval, ValidateChecksTableSizesAndTier) {
    const RuleTable t = must_parse(small_rules());
    std::vector<LodAttributes> a(2);
    std::vector<LodRequest> out(1);
    std::vector<LodState> states(3);
    RuleEvalJob job{&t, a, states, 7, out};
    std::vector<std::string> errors;
    EXPECT_FALSE(job.Validate(&errors));
    EXPECT_EQ(errors.size(), 3u);
    RuleEvalJob no_table{nullptr, a, {}, 0, out};
    EXPECT_FALSE(no_table.Validate());
}

}  // namespace
}  // namespace aloha
