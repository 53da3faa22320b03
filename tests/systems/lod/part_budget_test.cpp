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

// Walkers and characters that are not walking cost differently at the same animation level (the
// plaza: a hero's dynamic walk ~0.1-0.3 ms, the same level playing an idle clip ~0.002 ms). Told
// which is which (cost classes), the part learns each class's cost per level and demotes only
// characters whose demotion saves time: no idler is demoted (each would save 0.0002 ms or less,
// under the 1% of the band a demotion must save), and it settles within 10%. With one class per
// level the idlers look as costly as the level's average and are demoted for nothing.
TEST(PartBudget, WalkersAndOthersAreCostedApart) {
    auto run = [](bool classes, size_t* idlers_demoted, double* error, BudgetSim* out) {
        BudgetSim sim;
        sim.anim_per_level = true;
        sim.add(600);
        sim.anim_still_cost = {0.0006, 0.0005, 0.0004};
        std::vector<uint8_t> walking(600);
        for (size_t i = 0; i < walking.size(); ++i) walking[i] = i % 2;
        sim.walking = walking;
        sim.tell_classes = classes;  // else the same truth, told per level only
        sim.frame();
        const double target = 0.6 * sim.anim_truth;
        sim.set_targets(10.0 * sim.anim_truth, 0.0);  // room first: costs learned at the rules' levels
        for (int f = 0; f < 30; ++f) sim.frame();
        sim.set_targets(target, 0.0);
        for (int f = 0; f < 300; ++f) sim.frame();
        *idlers_demoted = 0;
        for (size_t i = 0; i < walking.size(); ++i) *idlers_demoted += !walking[i] && sim.crowd.states[i].anim_demotion > 0;
        *error = std::fabs(sim.anim_truth - target) / target;
        if (out) *out = std::move(sim);
    };
    size_t idlers = 0;
    double error = 0.0;
    BudgetSim apart;
    run(true, &idlers, &error, &apart);
    EXPECT_EQ(idlers, 0u);
    EXPECT_LE(error, 0.1);
    // The walkers' learned cost per populated level within the noise (2%) plus the average's lag: 5%.
    const auto& costs = apart.anim.costs().costs();
    ASSERT_EQ(costs.size(), 3 * kAnimCostClasses);
    std::vector<uint32_t> walkers_at(3, 0);
    for (size_t i = 1; i < apart.crowd.states.size(); i += 2) ++walkers_at[apart.crowd.states[i].anim_level];
    for (size_t l = 0; l < 3; ++l) {
        if (walkers_at[l] <= 20) continue;  // too few to have a settled average
        EXPECT_NEAR(costs[anim_cost_slot(l, true)], kAnimCost[l], 0.05 * kAnimCost[l]) << "level " << l;
    }
    size_t idlers_one_class = 0;
    run(false, &idlers_one_class, &error, nullptr);
    EXPECT_GT(idlers_one_class, 0u);
    std::printf("idlers demoted: %zu with cost classes, %zu with one class per level\n", idlers, idlers_one_class);
}

}  // namespace
}  // namespace aloha
