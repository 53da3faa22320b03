// PartBudget with steps coarser than its band (a hero's dynamic walk, a subdivided body: a few times
// the band) among fine ones: a coarse step that would overshoot is passed over, one that closes the
// gap by itself is taken as one unit, a shortfall only coarse promotions could fill is filled by one
// combined with finer demotions, and coarse disturbances of the rules are answered by coarse units.
#include "systems/lod/part_budget.hpp"
#include "tests/systems/lod/part_budget_sim.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <vector>

namespace aloha {
namespace {

using lod_test::at_distance;
using lod_test::BudgetSim;
using lod_test::direction_changes;
using lod_test::kAnimCost;

// One hero whose level step costs far more than the band (a dynamic walk among kinematic and clip
// walkers; a subdivided body among meshes): demoting it would carry the time across the band, so the
// controllers pass it over and close the gap with the finer steps of the rest; given room they promote
// the rest back and leave the hero alone; only when nothing finer can close the gap is it demoted,
// once, and never given back while that holds (its return would land as far from the target).
TEST(PartBudget, ACoarseHeroIsPassedOverWithoutOscillation) {
    BudgetSim sim;
    sim.anim_per_level = true;
    sim.geom_cost[0] = 1.5;  // rich: the hero only
    sim.anim_cost[0] = 2.0;  // full: the hero only
    sim.add(1, 3.0f, 3.0f);  // the hero, 3 m away: near (rich, full)
    sim.crowd.attrs[0].importance = 0.9f;
    sim.add(500, 12.0f, 40.0f);  // mid (kin) or far (proxy, clip)
    sim.frame();
    const double anim_full = sim.anim_truth, geom_full = sim.geom_truth;
    const double anim_hero = sim.anim_cost[0] - sim.anim_cost[1], geom_hero = sim.geom_cost[0] - sim.geom_cost[1];
    size_t hero_switches = 0;
    uint8_t hero_geom = sim.crowd.states[0].geom_level, hero_anim = sim.crowd.states[0].anim_level;
    auto run = [&](int frames) {
        for (int f = 0; f < frames; ++f) {
            sim.frame();
            const LodState& h = sim.crowd.states[0];
            hero_switches += (h.geom_level != hero_geom) + (h.anim_level != hero_anim);
            hero_geom = h.geom_level, hero_anim = h.anim_level;
        }
    };
    auto within_band = [&](double anim_target, double geom_target) {
        // The band is 5% of the target (noise 2% is under it); 10% is what the issue asks.
        EXPECT_NEAR(sim.anim_truth, anim_target, 0.1 * anim_target);
        EXPECT_NEAR(sim.geom_truth, geom_target, 0.1 * geom_target);
    };

    // 1. Over by 0.4 ms: 2.5-3 bands, a fifth to a quarter of the hero's step.
    double anim_target = anim_full - 0.4, geom_target = geom_full - 0.4;
    ASSERT_GT(0.4, 2.0 * 0.05 * anim_target);
    ASSERT_GT(anim_hero, 0.4 + 0.05 * anim_target);  // demoting the hero would overshoot the band
    ASSERT_GT(geom_hero, 0.4 + 0.05 * geom_target);
    sim.set_targets(anim_target, geom_target);
    run(200);
    within_band(anim_target, geom_target);
    EXPECT_EQ(hero_switches, 0u);
    EXPECT_EQ(sim.crowd.states[0].budget_demotion, 0);
    EXPECT_EQ(sim.crowd.states[0].anim_demotion, 0);
    EXPECT_LE(direction_changes(sim.anim_steps), 1);
    EXPECT_LE(direction_changes(sim.geom_steps), 1);
    std::printf("phase 1: animation %.3f -> %.3f ms (target %.3f, %zu steps), geometry %.3f -> %.3f ms (target %.3f, %zu steps)\n",
                anim_full, sim.anim_truth, anim_target, sim.anim_steps.size(), geom_full, sim.geom_truth, geom_target,
                sim.geom_steps.size());

    // 2. Room for half of it again: the rest is promoted, the hero untouched.
    anim_target += 0.2, geom_target += 0.2;
    sim.set_targets(anim_target, geom_target);
    sim.anim_steps.clear(), sim.geom_steps.clear();
    run(200);
    within_band(anim_target, geom_target);
    EXPECT_EQ(hero_switches, 0u);
    EXPECT_LE(direction_changes(sim.anim_steps), 1);
    EXPECT_LE(direction_changes(sim.geom_steps), 1);

    // 3. More than every finer step can save: the hero goes down once and stays down.
    // What demoting every other character one level below its request saves (proxy and clip are the
    // last levels a visible character can be demoted to).
    double fine_anim = 0, fine_geom = 0;
    for (size_t i = 1; i < sim.crowd.req.size(); ++i) {
        const LodRequest& r = sim.crowd.req[i];
        fine_anim += r.anim_level + 1 < 3 ? sim.anim_cost[r.anim_level] - sim.anim_cost[r.anim_level + 1] : 0.0;
        fine_geom += r.geom_level + 1 < 3 ? sim.geom_cost[r.geom_level] - sim.geom_cost[r.geom_level + 1] : 0.0;
    }
    // Beyond those by three quarters of the hero's step: taking it lands a quarter of a step under,
    // nearer by more than the band; giving it back would land three quarters over.
    anim_target = anim_full - fine_anim - 0.75 * anim_hero, geom_target = geom_full - fine_geom - 0.75 * geom_hero;
    sim.set_targets(anim_target, geom_target);
    sim.anim_steps.clear(), sim.geom_steps.clear();
    run(300);
    EXPECT_EQ(hero_switches, 2u);  // one geometric, one animation switch
    EXPECT_EQ(sim.crowd.states[0].budget_demotion, 1);
    EXPECT_EQ(sim.crowd.states[0].anim_demotion, 1);
    within_band(anim_target, geom_target);
    EXPECT_LE(direction_changes(sim.anim_steps), 1);
    EXPECT_LE(direction_changes(sim.geom_steps), 1);
    std::printf("phase 3: animation %.3f ms (target %.3f, %zu steps), geometry %.3f ms (target %.3f, %zu steps)\n",
                sim.anim_truth, anim_target, sim.anim_steps.size(), sim.geom_truth, geom_target, sim.geom_steps.size());
}

// Three heroes whose dynamic walk costs far more than the band (0.4 ms against kinematic 0.006 ms),
// among 500 kinematic and clip walkers (the plaza at 300 characters): a first target demotes the
// heroes and a few fine steps; raised, it leaves room for 45% of a hero's step. The fine promotions
// alone cannot fill it and a hero would carry the time 0.2 ms (three bands) over: without a finer
// path the part held 12% under its target (1.238 ms against 1.415). Counts the heroes' animation
// switches and the steps after the raise.
struct CoarseUnder {
    BudgetSim sim;
    double hero = 0, target = 0;  // one hero's promotion (ms), the raised target
    size_t hero_switches = 0;
    std::vector<uint8_t> hero_levels;

    // `fine_demotions`: whether the other walkers may be demoted (else they are all at the last level).
    explicit CoarseUnder(bool fine_demotions) {
        sim.anim_per_level = true;
        sim.anim_cost[0] = 0.4;
        sim.add(3, 3.0f, 3.0f);  // near: full
        for (size_t i = 0; i < 3; ++i) sim.crowd.attrs[i].importance = 0.9f;
        if (fine_demotions) sim.add(500, 12.0f, 40.0f);  // mid (kin) or far (clip)
        else sim.add(500, 25.0f, 40.0f);                 // far (clip): nothing finer to demote
        sim.frame();
        hero = sim.anim_cost[0] - sim.anim_cost[1];
        const double all_full = sim.anim_truth, heroes_down = all_full - 3.0 * hero;
        sim.set_targets(10.0 * all_full, 0.0);  // room: the costs are learned with the heroes at full
        run(30);
        sim.set_targets(heroes_down - (fine_demotions ? 0.1 : 0.0), 0.0);
        run(150);
        for (size_t i = 0; i < 3; ++i) EXPECT_EQ(sim.crowd.states[i].anim_demotion, 1) << "hero " << i;
        target = heroes_down + 0.45 * hero;
        // 45% of a hero is more than 10% of the target (the criterion) and more than the
        // band (5%) plus the 0.1 ms of fine steps; a hero more than the gap plus the band.
        EXPECT_GT(0.45 * hero, 0.1 * target);
        EXPECT_GT(hero, 0.45 * hero + 0.1 + 0.05 * target);
        sim.set_targets(target, 0.0);
        sim.anim_steps.clear();
        hero_switches = 0;
        run(300);
    }
    void run(int frames) {
        for (int f = 0; f < frames; ++f) {
            sim.frame();
            hero_levels.resize(3);
            for (size_t i = 0; i < 3; ++i) {
                hero_switches += sim.crowd.states[i].anim_level != hero_levels[i];
                hero_levels[i] = sim.crowd.states[i].anim_level;
            }
        }
    }
};

TEST(PartBudget, CoarseStepsUnderTheBandAreCombinedWithFinerOnes) {
    CoarseUnder c(true);
    // One hero comes back, paid for by demoting finer walkers: the time lands inside the band (5%),
    // within the 10% the issue asks, in one direction and then holds.
    EXPECT_NEAR(c.sim.anim_truth, c.target, 0.1 * c.target);
    EXPECT_EQ(c.hero_switches, 1u);
    EXPECT_LE(direction_changes(c.sim.anim_steps), 1);
    EXPECT_LE(c.sim.anim_steps.size(), 4u);
    // Settled: the last 150 frames took no step and switched no hero.
    const size_t steps = c.sim.anim_steps.size(), switches = c.hero_switches;
    c.run(150);
    EXPECT_EQ(c.sim.anim_steps.size(), steps);
    EXPECT_EQ(c.hero_switches, switches);
    EXPECT_NEAR(c.sim.anim_truth, c.target, 0.1 * c.target);
    std::printf("coarse under: %.3f ms (target %.3f, hero step %.3f, %zu steps)\n", c.sim.anim_truth, c.target, c.hero,
                c.sim.anim_steps.size());
}

TEST(PartBudget, CoarseStepsUnderTheBandHoldWhenNothingFinerFits) {
    CoarseUnder c(false);
    // The only finer demotions left (the other two heroes, kin -> clip, 0.005 ms each) cannot pull a
    // hero's 0.4 ms back into the band: the part holds under its target without a step or a switch.
    EXPECT_TRUE(c.sim.anim_steps.empty());
    EXPECT_EQ(c.hero_switches, 0u);
    EXPECT_LT(c.sim.anim_truth, c.target - 0.05 * c.target);
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(c.sim.crowd.states[i].anim_demotion, 1) << "hero " << i;
}

// Steps coarser than the band as units of their own (the plaza's walking heroes): three heroes whose
// dynamic walk costs 0.394 ms more than the kinematic one, four times the band, among 500 kinematic and
// clip walkers (0.005 ms a step), a target that leaves room for one and a half heroes, and the rules
// moving the heroes: every 2 s one of them walks out of range for 1 s (its request drops to kin) and
// back. Each move is a coarse disturbance; answered by fine steps it costs 80 walker switches one way
// and 80 back. Counts every animation switch after settling.
struct CoarseDisturbed {
    BudgetSim sim;
    static constexpr int kPeriod = 120, kAway = 60;  // frames between departures, frames away
    double hero = 0, target = 0, band = 0, mean = 0;  // one hero's step, the target, the band, the settled mean
    int hold = 0;                                     // coarse_hold_updates of a hero's step (frames)
    uint32_t switches = 0, hero_switches = 0;         // animation switches after settling: all, the heroes'
    int frames = 0;                                   // settled frames counted

    CoarseDisturbed() {
        sim.anim_per_level = true;
        sim.anim_cost[0] = 0.4;
        sim.add(3, 3.0f, 3.0f);  // near: full
        for (size_t i = 0; i < 3; ++i) sim.crowd.attrs[i].importance = 0.9f;
        sim.add(500, 12.0f, 40.0f);  // mid (kin) or far (clip)
        sim.frame();
        hero = sim.anim_cost[0] - sim.anim_cost[1];
        target = sim.anim_truth - 1.5 * hero;
        band = 0.25 * hero;  // one hero's step is four bands
        BudgetPartParams a;
        a.target_ms = static_cast<float>(target);
        a.tolerance = static_cast<float>(band / target);
        sim.common.settle_frames = 2;
        sim.anim.set_params(a, sim.common);
        hold = coarse_hold_updates(hero, band, sim.common.smoothing);
        run(600, false);  // settles and learns the costs with the heroes moving
        run(1200, true);
    }
    void run(int n, bool count) {
        for (int f = 0; f < n; ++f, ++frames) {
            const int phase = frames % kPeriod, who = (frames / kPeriod) % 3;
            for (size_t i = 0; i < 3; ++i) sim.crowd.attrs[i] = at_distance(i == static_cast<size_t>(who) && phase < kAway ? 15.0f : 3.0f);
            for (size_t i = 0; i < 3; ++i) sim.crowd.attrs[i].importance = 0.9f;
            const uint32_t before = sim.crowd.switches[1];
            const uint8_t levels[3] = {sim.crowd.states[0].anim_level, sim.crowd.states[1].anim_level, sim.crowd.states[2].anim_level};
            sim.frame();
            if (!count) continue;
            switches += sim.crowd.switches[1] - before, mean += sim.anim_truth / n;
            for (size_t i = 0; i < 3; ++i) hero_switches += sim.crowd.states[i].anim_level != levels[i];
        }
    }
};

// A walker's finest step: kin -> clip.
double sim_walker_step() { return kAnimCost[1] - kAnimCost[2]; }

TEST(PartBudget, CoarseDisturbancesAreAnsweredByCoarseUnits) {
    CoarseDisturbed c;
    const double seconds = 1200 * lod_test::kFrameDt;
    std::printf("coarse disturbed: mean %.3f ms (target %.3f, band %.3f, hero step %.3f, hold %d frames), %u switches in %.0f s (%.1f/s), %u of the heroes\n",
                c.mean, c.target, c.band, c.hero, c.hold, c.switches, seconds, c.switches / seconds, c.hero_switches);
    // Within 10% of the target on average (the figure).
    EXPECT_NEAR(c.mean, c.target, 0.1 * c.target);
    // Bounds, per 2 s cycle of the rules: the departing hero switches out and back (2, the rules'
    // own); the budget answers each of the two moves with at most one coarse unit (a demoted hero
    // promoted when one leaves, the returning one held back when it comes: at most 2 more), so at most
    // 4 hero switches a cycle, 2 a second. The walkers are the fine steps: at most one coarse step's
    // worth of them (hero / 0.005 ms, 79 switches) in the whole 20 s, where answering every move with
    // fine steps costs that twice a cycle. Measured with main's controller (before the coarse units,
    // 2026-11-28): 588 switches in the 20 s (29.4 a second).
    const double cycles = 1200.0 / CoarseDisturbed::kPeriod;
    const double walker_step = sim_walker_step();
    EXPECT_LE(c.hero_switches, static_cast<uint32_t>(4.0 * cycles));
    EXPECT_LE(c.switches - c.hero_switches, static_cast<uint32_t>(c.hero / walker_step));
}

}  // namespace
}  // namespace aloha
