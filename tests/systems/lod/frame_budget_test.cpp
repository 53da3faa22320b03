// FrameBudget against a synthetic cost model: measured time = sum over characters of a cost per
// geometric level + a cost per animation level. The loop each frame: budget.update(last time),
// rules, resolver, measure. Checks convergence under the target, no oscillation, re-convergence
// when the crowd doubles, and that the demoted characters are the least noticeable ones.
#include "systems/lod/frame_budget.hpp"
#include "systems/lod/resolver.hpp"
#include "systems/lod/rule_eval.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

namespace aloha {
namespace {

using lod_test::must_parse;
using lod_test::small_rules;

// Cost in ms per character at each level (rich..hidden, full..clip).
constexpr float kGeomCost[] = {0.020f, 0.006f, 0.001f, 0.0f};
constexpr float kAnimCost[] = {0.010f, 0.003f, 0.0005f};

struct Sim {
    RuleTable table = must_parse(small_rules());
    FrameBudget budget;
    std::vector<LodAttributes> attrs;
    std::vector<LodRequest> req;
    std::vector<LodState> states;
    std::vector<GeomLod> geom;
    std::vector<AnimLod> anim;
    uint32_t seed = 7u;
    float measured = 0.0f;
    std::vector<int> directions;  // non-zero budget steps, in order

    explicit Sim(float target_ms) {
        BudgetParams p;
        p.target_ms = target_ms;
        p.max_demotion = 3;
        budget = FrameBudget(p);
    }
    float rnd() {
        seed = seed * 1664525u + 1013904223u;
        return static_cast<float>(seed >> 8) / 16777216.0f;
    }
    // Adds n characters: distances 2..40 m, importance 0..1, eccentricity 0..1.2, visible if ecc <= 1.
    void add(size_t n) {
        for (size_t i = 0; i < n; ++i) {
            LodAttributes a = lod_test::at_distance(2.0f + 38.0f * rnd());
            a.importance = rnd();
            a.eccentricity = 1.2f * rnd();
            a.visible = a.eccentricity <= 1.0f ? 1 : 0;
            attrs.push_back(a);
        }
        const size_t total = attrs.size();
        req.resize(total);
        states.resize(total);
        geom.resize(total);
        anim.resize(total);
        RuleEvalJob{&table, attrs, states, 1, req}.Run();
        std::vector<LodState> fresh(states.end() - static_cast<std::ptrdiff_t>(n), states.end());
        LodResolveJob{&table, std::span<const LodRequest>(req).last(n), fresh,
                      std::span<GeomLod>(geom).last(n), std::span<AnimLod>(anim).last(n), {}, {}, 0, 0.0f, true}.Run();
        std::copy(fresh.begin(), fresh.end(), states.end() - static_cast<std::ptrdiff_t>(n));
    }
    void frame() {
        const BudgetStep s = budget.update(measured, attrs, states, table);
        if (s.direction != 0) directions.push_back(s.direction);
        RuleEvalJob{&table, attrs, states, 1, req}.Run();
        LodResolveJob{&table, req, states, geom, anim, {}, {}, 0, lod_test::kFrameDt, false}.Run();
        measured = 0.0f;
        for (const LodState& st : states) measured += kGeomCost[st.geom_level] + kAnimCost[st.anim_level];
    }
    int direction_changes(size_t from) const {
        int changes = 0;
        for (size_t i = from + 1; i < directions.size(); ++i) changes += directions[i] != directions[i - 1];
        return changes;
    }
};

TEST(FrameBudget, NoticeabilityOrdersWhatIsLeastSeen) {
    LodAttributes big = lod_test::at_distance(2.0f);
    LodAttributes small = lod_test::at_distance(20.0f);
    LodAttributes edge = big;
    edge.eccentricity = 1.0f;  // halves the score: 1 / (1 + 1^2)
    LodAttributes hidden = big;
    hidden.visible = 0;
    EXPECT_GT(noticeability(big), noticeability(small));
    EXPECT_FLOAT_EQ(noticeability(edge), 0.5f * noticeability(big));
    EXPECT_EQ(noticeability(hidden), 0.0f);
    LodAttributes hero = small;
    hero.importance = 1.0f;
    EXPECT_GT(noticeability(hero), noticeability(small));
}

TEST(FrameBudget, ConvergesUnderTargetWithoutOscillationAndReconverges) {
    Sim sim(0.0f);
    sim.add(2000);
    sim.frame();
    const float full_cost = sim.measured;
    ASSERT_GT(full_cost, 0.0f);
    // Aim at 75% of the undemoted cost.
    BudgetParams p = sim.budget.params();
    p.target_ms = 0.75f * full_cost;
    sim.budget.set_params(p);
    for (int f = 0; f < 300; ++f) sim.frame();
    EXPECT_LE(sim.measured, p.target_ms);
    // Settled: the last 100 frames stay under the target (measured exactly by the cost model).
    const size_t steps_before = sim.directions.size();
    for (int f = 0; f < 100; ++f) {
        sim.frame();
        EXPECT_LE(sim.measured, p.target_ms) << "frame " << f;
    }
    EXPECT_LE(sim.direction_changes(0), 4);
    EXPECT_LE(sim.directions.size() - steps_before, 2u);  // at most a couple of small corrections once settled

    // Demoted characters are the least noticeable: among the characters the budget could demote
    // (visible, rule level above the lowest), the mean score of the demoted ones is below that of
    // the kept ones, and none of the 10% most noticeable of them is demoted.
    std::vector<float> scores;
    double demoted_sum = 0.0, kept_sum = 0.0;
    int demoted = 0, kept = 0;
    const uint8_t last_geom_visible = 2;
    const uint8_t last_anim = 2;
    auto could_demote = [&](size_t i) {
        return sim.attrs[i].visible && (sim.req[i].geom_level < last_geom_visible || sim.req[i].anim_level < last_anim);
    };
    for (size_t i = 0; i < sim.states.size(); ++i) {
        if (!could_demote(i)) continue;
        const float s = noticeability(sim.attrs[i]);
        scores.push_back(s);
        if (sim.states[i].budget_demotion > 0) { demoted_sum += s; ++demoted; }
        else { kept_sum += s; ++kept; }
    }
    ASSERT_GT(demoted, 0);
    ASSERT_GT(kept, 0);
    EXPECT_LT(demoted_sum / demoted, kept_sum / kept);
    std::sort(scores.begin(), scores.end());
    const float top10 = scores[scores.size() * 9 / 10];
    for (size_t i = 0; i < sim.states.size(); ++i) {
        if (could_demote(i) && noticeability(sim.attrs[i]) > top10) {
            EXPECT_EQ(sim.states[i].budget_demotion, 0);
        }
    }
    std::printf("full %.3f ms, target %.3f ms, settled %.3f ms, demoted %d of %d demotable, steps %zu\n",
                full_cost, p.target_ms, sim.measured, demoted, demoted + kept, sim.directions.size());

    // The crowd doubles: the controller demotes more and re-converges under the same target.
    const size_t before = sim.directions.size();
    sim.add(2000);
    for (int f = 0; f < 400; ++f) sim.frame();
    EXPECT_LE(sim.measured, p.target_ms);
    EXPECT_LE(sim.direction_changes(before), 4);
    std::printf("doubled crowd: settled %.3f ms, steps %zu\n", sim.measured, sim.directions.size() - before);
}

TEST(FrameBudget, PromotesBackWhenThereIsRoom) {
    Sim sim(0.0f);
    sim.add(1000);
    sim.frame();
    const float full_cost = sim.measured;
    BudgetParams p = sim.budget.params();
    p.target_ms = 0.5f * full_cost;
    sim.budget.set_params(p);
    for (int f = 0; f < 300; ++f) sim.frame();
    int demoted = 0;
    for (const LodState& s : sim.states) demoted += s.budget_demotion > 0;
    ASSERT_GT(demoted, 0);
    p.target_ms = 2.0f * full_cost;  // plenty of room: everyone goes back to the rules' levels
    sim.budget.set_params(p);
    for (int f = 0; f < 400; ++f) sim.frame();
    for (const LodState& s : sim.states) EXPECT_EQ(s.budget_demotion, 0);
    EXPECT_NEAR(sim.measured, full_cost, 1e-3f * full_cost);  // float sum order is the same; slack for rounding
}

}  // namespace
}  // namespace aloha
