// PartBudget (separate animation and geometry budgets) against a synthetic cost model with
// measurement noise: each part settles within 10% of its own target in a few steps and stays
// there without oscillating, learns the per-level costs, never demotes always_full characters,
// re-converges when the crowd doubles and gives everything back when there is room.
#include "systems/lod/part_budget.hpp"
#include "tests/systems/lod/lod_crowd_sim.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <span>

namespace aloha {
namespace {

using lod_test::at_distance;
using lod_test::CrowdSim;
using lod_test::Lcg;
using lod_test::must_parse;
using lod_test::small_rules;

// True cost in ms per character at each level (rich, mid, proxy, hidden; full, kin, clip).
constexpr double kGeomCost[] = {0.050, 0.012, 0.002, 0.0};
constexpr double kAnimCost[] = {0.030, 0.006, 0.001};
// Measurements are the truth times (1 + noise), noise uniform in +-kNoise.
constexpr double kNoise = 0.02;

struct BudgetSim {
    RuleTable table = must_parse(small_rules());
    CrowdSim crowd{table, 0};
    BudgetParams common;
    PartBudget anim{BudgetKind::Animation, {}, {}};
    PartBudget geom{BudgetKind::Geometry, {}, {}};
    Lcg rnd;
    std::vector<double> geom_cost{std::begin(kGeomCost), std::end(kGeomCost)};  // truth, ms per character per level
    std::vector<double> anim_cost{std::begin(kAnimCost), std::end(kAnimCost)};
    bool anim_per_level = false;                // animation told its per-level times too (as the World does)
    double geom_truth = 0, anim_truth = 0;      // noise-free cost of the last frame
    double geom_ms = -1, anim_ms = -1;          // what the controllers are told
    std::vector<double> geom_level_ms, anim_level_ms;
    std::vector<int> anim_steps, geom_steps;    // direction of every step, in order

    // Adds n characters at near..far m with random importance.
    void add(size_t n, float near = 2.0f, float far = 40.0f) {
        const size_t old = crowd.attrs.size();
        crowd.resize(old + n);
        for (size_t i = old; i < crowd.attrs.size(); ++i) {
            crowd.attrs[i] = at_distance(near + (far - near) * rnd.next());
            crowd.attrs[i].importance = rnd.next();
        }
    }
    void set_targets(double anim_target, double geom_target) {
        common.settle_frames = 2;
        BudgetPartParams a, g;
        a.target_ms = static_cast<float>(anim_target);
        g.target_ms = static_cast<float>(geom_target);
        anim.set_params(a, common);
        geom.set_params(g, common);
    }
    void frame() {
        if (anim.params().target_ms > 0) {
            const std::span<const double> per_level = anim_per_level ? std::span<const double>(anim_level_ms) : std::span<const double>();
            const BudgetStep s = anim.update(static_cast<float>(anim_ms), per_level, crowd.attrs, crowd.req, crowd.states, table);
            if (s.direction) anim_steps.push_back(s.direction);
        }
        if (geom.params().target_ms > 0) {
            const BudgetStep s = geom.update(static_cast<float>(geom_ms), geom_level_ms, crowd.attrs, crowd.req, crowd.states, table);
            if (s.direction) geom_steps.push_back(s.direction);
        }
        crowd.frame();
        geom_level_ms.assign(geom_cost.size(), 0.0);
        anim_level_ms.assign(anim_cost.size(), 0.0);
        anim_truth = geom_truth = 0.0;
        for (const LodState& s : crowd.states) {
            geom_level_ms[s.geom_level] += geom_cost[s.geom_level];
            anim_level_ms[s.anim_level] += anim_cost[s.anim_level];
        }
        for (double& l : geom_level_ms) geom_truth += l, l *= 1.0 + kNoise * (2.0 * rnd.next() - 1.0);
        for (double& l : anim_level_ms) anim_truth += l, l *= anim_per_level ? 1.0 + kNoise * (2.0 * rnd.next() - 1.0) : 1.0;
        geom_ms = geom_truth * (1.0 + kNoise * (2.0 * rnd.next() - 1.0));
        anim_ms = anim_per_level ? std::accumulate(anim_level_ms.begin(), anim_level_ms.end(), 0.0)
                                 : anim_truth * (1.0 + kNoise * (2.0 * rnd.next() - 1.0));
    }
};

int direction_changes(const std::vector<int>& steps) {
    int n = 0;
    for (size_t i = 1; i < steps.size(); ++i) n += steps[i] != steps[i - 1];
    return n;
}

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

}  // namespace
}  // namespace aloha
