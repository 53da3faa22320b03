// SwitchCauseJob: a switch the rules made (the request moved, the demotion as at the last switch), a
// switch the budget made (its demotion moved), the way of each, an undo within the window and one
// after it, and Validate's errors.
#include "systems/lod/switch_causes.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

using lod_test::must_parse;
using lod_test::small_rules;

struct Fixture {
    RuleTable table = must_parse(small_rules());  // geometry rich, mid, proxy, hidden; animation full, kin, clip
    std::vector<LodRequest> req = std::vector<LodRequest>(1);
    std::vector<LodState> states = std::vector<LodState>(1);
    std::vector<SwitchRecord> records = std::vector<SwitchRecord>(1);
    std::vector<uint32_t> changed = {0}, keys = {0};

    // Character 0 switches both levels to (geom, anim) with `demotion` in force, at `frame`.
    SwitchCauseCounts switch_to(uint8_t geom, uint8_t anim, uint8_t demotion, uint64_t frame) {
        LodState& s = states[0];
        s.geom_level = geom, s.anim_level = anim;
        s.budget_demotion = s.anim_demotion = demotion;
        s.seconds_at_geom = s.seconds_at_anim = 0.0f;  // the resolver zeroes them on a switch
        SwitchCauseCounts c;
        SwitchCauseJob job{&table, req, states, changed, keys, records, frame, 60, &c};
        std::vector<std::string> errors;
        EXPECT_TRUE(job.Validate(&errors));
        job.Run();
        return c;
    }
};

TEST(SwitchCauses, RulesAndBudgetApartWithTheirWayAndUndos) {
    Fixture f;
    f.req[0] = LodRequest{1, 1, 0};  // the rules ask for mid / kin; no demotion: the rules' switch
    SwitchCauseCounts c = f.switch_to(1, 1, 0, 10);
    EXPECT_EQ(c.rules[0], 1u);
    EXPECT_EQ(c.rules[1], 1u);
    EXPECT_EQ(c.budget_down[0] + c.budget_up[0] + c.budget_down[1] + c.budget_up[1], 0u);
    c = f.switch_to(2, 2, 1, 20);  // the budget demotes one level: proxy / clip
    EXPECT_EQ(c.budget_down[0], 1u);
    EXPECT_EQ(c.budget_down[1], 1u);
    EXPECT_EQ(c.rules[0] + c.rules[1], 0u);
    c = f.switch_to(1, 1, 0, 50);  // promoted back 30 frames later: undone
    EXPECT_EQ(c.budget_up[0], 1u);
    EXPECT_EQ(c.undone[0], 1u);
    EXPECT_EQ(c.undone[1], 1u);
    f.req[0] = LodRequest{0, 0, 0};  // the rules ask for rich / full, demotion still 0: the rules'
    c = f.switch_to(0, 0, 0, 60);
    EXPECT_EQ(c.rules[0], 1u);
    c = f.switch_to(1, 1, 1, 70);  // demoted again: it reverses the promotion of frame 50, an undo
    EXPECT_EQ(c.budget_down[1], 1u);
    EXPECT_EQ(c.undone[1], 1u);
    c = f.switch_to(2, 2, 2, 80);  // demoted once more: the same way as its last budget switch, no undo
    EXPECT_EQ(c.budget_down[0], 1u);
    EXPECT_EQ(c.undone[0], 0u);
    c = f.switch_to(1, 1, 1, 200);  // promoted after more than the 60-frame window: not an undo
    EXPECT_EQ(c.budget_up[1], 1u);
    EXPECT_EQ(c.undone[1], 0u);
}

TEST(SwitchCauses, OnlyTheKindThatSwitchedIsCounted) {
    Fixture f;
    f.req[0] = LodRequest{1, 0, 0};
    f.states[0].seconds_at_anim = 1.0f;  // the animation level did not switch
    LodState& s = f.states[0];
    s.geom_level = 1;
    s.seconds_at_geom = 0.0f;
    SwitchCauseCounts c;
    SwitchCauseJob job{&f.table, f.req, f.states, f.changed, f.keys, f.records, 5, 60, &c};
    ASSERT_TRUE(job.Validate());
    job.Run();
    EXPECT_EQ(c.rules[0], 1u);
    EXPECT_EQ(c.rules[1], 0u);
}

TEST(SwitchCauses, ValidateNamesWhatIsWrong) {
    Fixture f;
    SwitchCauseCounts c;
    std::vector<uint32_t> out_of_range = {3};
    std::vector<std::string> errors;
    SwitchCauseJob bad{&f.table, f.req, f.states, out_of_range, f.keys, f.records, 0, 60, &c};
    EXPECT_FALSE(bad.Validate(&errors));
    ASSERT_FALSE(errors.empty());
    EXPECT_NE(errors.front().find("changed index 3 out of range"), std::string::npos) << errors.front();
    errors.clear();
    std::vector<uint32_t> far_key = {9};
    SwitchCauseJob bad_key{&f.table, f.req, f.states, f.changed, far_key, f.records, 0, 60, &c};
    EXPECT_FALSE(bad_key.Validate(&errors));
    EXPECT_NE(errors.front().find("key 9 out of range"), std::string::npos) << errors.front();
    SwitchCauseJob no_out{&f.table, f.req, f.states, f.changed, f.keys, f.records, 0, 60, nullptr};
    EXPECT_FALSE(no_out.Validate());
}

}  // namespace
}  // namespace aloha
