// PartBudget (separate animation and geometry budgets) against a synthetic cost model with
// measurement noise: each part settles within 10% of its own target in a few steps and stays
// there without oscillating, learns the per-level costs, never demotes always_full characters,
// re-converges when the crowd doubles and gives everything back when there is room.
#include "systems/lod/part_budget.hpp"
#include "tests/systems/lod/part_budget_sim.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace aloha {
namespace {

using lod_test::BudgetSim;
using lod_test::direction_changes;
using lod_test::kAnimCost;
using lod_test::kGeomCost;

TEST(PartBudget, EachPartSettlesWithinTenPercentOfItsTarget) {
    BudgetSim sim;
    sim.add(1000);
    sim.frame();
    const double anim_full = sim.anim_truth, geom_full = sim.geom_truth;
    const double anim_target = 0.6 * anim_full, geom_target = 0.5 * geom_full;
    sim.set_targets(anim_target, geom_target);
    int settled_at = -1;
    for (int f = 0; f < 300; ++f) {
        sim.frame();
        const bool in = std::fabs(sim.anim_truth - anim_target) <= 0.1 * anim_target &&
                        std::fabs(sim.geom_truth - geom_target) <= 0.1 * geom_target;
        if (in && settled_at < 0) settled_at = f;
        if (!in) settled_at = -1;
    }
    // Settled early and stayed: the last frame outside the band was within the first 40 frames.
    ASSERT_GE(settled_at, 0);
    EXPECT_LE(settled_at, 40);
    // A few steps, no oscillation: mostly demotions; at most one turn-around per part.
    EXPECT_LE(direction_changes(sim.geom_steps), 1);
    EXPECT_LE(direction_changes(sim.anim_steps), 1);
    EXPECT_LE(sim.geom_steps.size(), 8u);
    EXPECT_LE(sim.anim_steps.size(), 8u);
    std::printf("animation %.3f -> %.3f ms (target %.3f, %zu steps); geometry %.3f -> %.3f ms (target %.3f, %zu steps)\n",
                anim_full, sim.anim_truth, anim_target, sim.anim_steps.size(), geom_full, sim.geom_truth, geom_target,
                sim.geom_steps.size());

    // Geometry learns each populated level's cost from per-level times: within the noise (2%) plus
    // the moving average's lag, 5%. Animation learns from totals only: its prediction of the total is
    // what must be right (5%).
    const auto& costs = sim.geom.costs().costs();
    for (size_t l = 0; l < 3; ++l) EXPECT_NEAR(costs[l], kGeomCost[l], 0.05 * kGeomCost[l]) << "level " << l;
    std::vector<uint32_t> counts(3, 0);
    for (const LodState& s : sim.crowd.states) ++counts[s.anim_level];
    EXPECT_NEAR(sim.anim.costs().predict(counts), sim.anim_truth, 0.05 * sim.anim_truth);
}

TEST(PartBudget, AlwaysFullCharactersAreNeverDemoted) {
    BudgetSim sim;
    sim.add(600);
    for (size_t i = 0; i < sim.crowd.states.size(); i += 5) sim.crowd.states[i].always_full = 1;
    sim.frame();
    // Targets no demotion of the others can reach: the controllers demote everyone else they can.
    sim.set_targets(0.05 * sim.anim_truth, 0.05 * sim.geom_truth);
    for (int f = 0; f < 300; ++f) {
        sim.frame();
        for (size_t i = 0; i < sim.crowd.states.size(); i += 5) {
            const LodState& s = sim.crowd.states[i];
            ASSERT_EQ(s.budget_demotion, 0) << "character " << i << " frame " << f;
            ASSERT_EQ(s.anim_demotion, 0) << "character " << i << " frame " << f;
            ASSERT_EQ(s.geom_level, sim.crowd.req[i].geom_level) << "character " << i << " frame " << f;
            ASSERT_EQ(s.anim_level, sim.crowd.req[i].anim_level) << "character " << i << " frame " << f;
        }
    }
    size_t demoted = 0;
    for (const LodState& s : sim.crowd.states) demoted += s.budget_demotion > 0;
    EXPECT_GT(demoted, 100u);  // the others really were pushed down
}

TEST(PartBudget, ReconvergesWhenTheCrowdDoublesAndGivesBackWhenThereIsRoom) {
    BudgetSim sim;
    sim.add(500);
    sim.frame();
    const double anim_target = 0.7 * sim.anim_truth, geom_target = 0.6 * sim.geom_truth;
    sim.set_targets(anim_target, geom_target);
    for (int f = 0; f < 150; ++f) sim.frame();
    sim.add(500);  // the same kind of crowd again: about twice the cost
    const size_t geom_before = sim.geom_steps.size();
    for (int f = 0; f < 150; ++f) sim.frame();
    EXPECT_NEAR(sim.anim_truth, anim_target, 0.1 * anim_target);
    EXPECT_NEAR(sim.geom_truth, geom_target, 0.1 * geom_target);
    EXPECT_LE(sim.geom_steps.size() - geom_before, 8u);

    sim.set_targets(10.0 * anim_target, 10.0 * geom_target);  // plenty of room
    for (int f = 0; f < 300; ++f) sim.frame();
    for (const LodState& s : sim.crowd.states) {
        EXPECT_EQ(s.budget_demotion, 0);
        EXPECT_EQ(s.anim_demotion, 0);
    }
}

TEST(PartBudget, InsideTheToleranceNothingMoves) {
    BudgetSim sim;
    sim.add(300);
    sim.frame();
    sim.set_targets(sim.anim_truth * 1.01, sim.geom_truth * 0.99);  // within +-5% already
    for (int f = 0; f < 100; ++f) sim.frame();
    EXPECT_TRUE(sim.anim_steps.empty());
    EXPECT_TRUE(sim.geom_steps.empty());
}

}  // namespace
}  // namespace aloha
