// Where a part's level changes come from, and the dwell (BudgetParams::dwell). 500 characters whose
// importance (and so significance) random-walks, constant per-level costs; every switch classified
// (SwitchCauseJob) as the rules' or the budget's. With the measured times merely noisy (BudgetSim's
// 2%, inside the band) the budget makes no change at all, however the order moves: the part never
// re-ranks without a step, and a step's size is set by the time's error, not by who is ranked where.
// Under load (a slow drift and short bursts, as another process makes) it chases each burst with
// level changes that the burst's end undoes; a dwell of one time constant lets bursts pass.
#include "systems/lod/part_budget.hpp"
#include "systems/lod/switch_causes.hpp"
#include "tests/systems/lod/part_budget_sim.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace aloha {
namespace {

using lod_test::BudgetSim;

// The machine's load: a slow drift (AR(1), time constant 1 s, about +-10%) and bursts (another
// process: +60% for 4 frames, on average one every 40 frames).
struct Load {
    lod_test::Lcg rnd{11u};
    double drift = 0.0;
    int burst = 0;
    double next() {
        drift += (0.17 * (2.0 * rnd.next() - 1.0) - drift) / 60.0;
        if (burst > 0) --burst;
        else if (rnd.next() < 1.0 / 40.0) burst = 4;
        return 1.0 + drift + (burst > 0 ? 0.6 : 0.0);
    }
};

struct ChurnRun {
    SwitchCauseCounts causes;                    // over the measured frames
    double anim_mean = 0.0, geom_mean = 0.0;     // mean measured times over them (what the budget holds)
    double anim_target = 0.0, geom_target = 0.0;
    double seconds = 0.0;
    [[nodiscard]] double budget_per_s(size_t k) const { return (causes.budget_down[k] + causes.budget_up[k]) / seconds; }
};

struct ChurnSetup {
    float walk = 0.02f;   // importance random-walk step per frame (0: a fixed order)
    bool loaded = false;  // drift and bursts on the measured times
    float dwell = 0.0f;   // BudgetParams::dwell
    float confidence = 0.0f;  // BudgetParams::confidence: these tests show the band test (0) and its dwell
};

// Both parts at 0.7 of the crowd's full cost; settles 300 frames, then counts over `frames` more.
ChurnRun run_churn(const ChurnSetup& setup, int frames = 1200, int settle = 300) {
    BudgetSim sim;
    Load load;
    sim.add(500, 2.0f, 40.0f);
    sim.frame();
    ChurnRun r;
    r.anim_target = 0.7 * sim.anim_truth;
    r.geom_target = 0.7 * sim.geom_truth;
    sim.common.dwell = setup.dwell;
    sim.common.confidence = setup.confidence;
    sim.set_targets(r.anim_target, r.geom_target);
    std::vector<SwitchRecord> records(sim.crowd.states.size());
    std::vector<uint32_t> changed;
    std::vector<LodState> before;
    for (int f = 0; f < settle + frames; ++f) {
        for (LodAttributes& a : sim.crowd.attrs)  // reflected into [0, 1] by the clamp
            a.importance = std::clamp(a.importance + setup.walk * (2.0f * sim.rnd.next() - 1.0f), 0.0f, 1.0f);
        if (setup.loaded) sim.load = load.next();
        before = sim.crowd.states;
        sim.frame();
        changed.clear();
        for (uint32_t i = 0; i < before.size(); ++i)
            if (before[i].geom_level != sim.crowd.states[i].geom_level || before[i].anim_level != sim.crowd.states[i].anim_level)
                changed.push_back(i);
        SwitchCauseCounts counts;  // keys: the sim never reorders, so the index is the key
        SwitchCauseJob job{&sim.table, sim.crowd.req, sim.crowd.states, changed, changed, records, uint64_t(f), 60, &counts};
        EXPECT_TRUE(job.Validate());
        job.Run();
        if (f < settle) continue;
        r.causes.add(counts);
        r.anim_mean += sim.anim_ms / frames;
        r.geom_mean += sim.geom_ms / frames;
    }
    r.seconds = frames * lod_test::kFrameDt;
    return r;
}

void print(const char* what, const ChurnRun& r) {
    for (size_t k = 0; k < 2; ++k)
        std::printf("%-22s %-9s: rules %5.1f/s, budget %5.1f down + %5.1f up /s (undone within 1 s %5.1f/s); mean/target %.3f\n",
                    what, k ? "animation" : "geometry", r.causes.rules[k] / r.seconds, r.causes.budget_down[k] / r.seconds,
                    r.causes.budget_up[k] / r.seconds, r.causes.undone[k] / r.seconds,
                    k ? r.anim_mean / r.anim_target : r.geom_mean / r.geom_target);
}

void expect_held(const ChurnRun& r) {  // the budget's promise: each part's mean within 10% of its target
    EXPECT_NEAR(r.anim_mean, r.anim_target, 0.1 * r.anim_target);
    EXPECT_NEAR(r.geom_mean, r.geom_target, 0.1 * r.geom_target);
}

TEST(PartBudgetChurn, AMovingSignificanceOrderAloneMakesNoChanges) {
    const ChurnRun r = run_churn({});
    print("order walks, no load", r);
    // The noise (2%) is inside the band (5%, BudgetPartParams::tolerance): no step, so no change, at
    // any order; the importance walk does not reach the distance-only rules either.
    EXPECT_EQ(r.causes.budget_down[0] + r.causes.budget_up[0] + r.causes.budget_down[1] + r.causes.budget_up[1], 0u);
    EXPECT_EQ(r.causes.rules[0] + r.causes.rules[1], 0u);
    expect_held(r);
}

TEST(PartBudgetChurn, UnderLoadTheChangesFollowTheLoadNotTheOrder) {
    const ChurnRun walking = run_churn({.walk = 0.02f, .loaded = true});
    const ChurnRun fixed = run_churn({.walk = 0.0f, .loaded = true});
    print("loaded, order walks", walking);
    print("loaded, fixed order", fixed);
    // The same load with the order fixed makes about as many changes: the order is not their cause.
    // (A regression guard: measured 64.1 / 61.3 geometric and 45.1 / 39.8 animation changes a second.)
    for (size_t k = 0; k < 2; ++k) {
        EXPECT_GT(walking.budget_per_s(k), 20.0);
        EXPECT_NEAR(fixed.budget_per_s(k), walking.budget_per_s(k), 0.25 * walking.budget_per_s(k));
    }
    // Most are undone within a second by the same character (the burst's end).
    EXPECT_GT(walking.causes.undone[0], (walking.causes.budget_down[0] + walking.causes.budget_up[0]) / 2);
    expect_held(walking);
}

TEST(PartBudgetChurn, ADwellOfOneTimeConstantLetsBurstsPass) {
    const ChurnRun now = run_churn({.walk = 0.02f, .loaded = true});
    const ChurnRun dwell = run_churn({.walk = 0.02f, .loaded = true, .dwell = 1.0f});
    print("loaded, no dwell", now);
    print("loaded, dwell 1", dwell);
    // A 4-frame burst keeps the smoothed time (weight 0.25) outside the band for fewer updates than
    // the dwell (ceil(1 / 0.25) = 4) most of the time; the drift, slower than a second, is still
    // followed. Regression guard (measured: 64.1 -> 6.4 geometric, 45.1 -> 5.4 animation a second):
    // at most a quarter of the changes are left.
    for (size_t k = 0; k < 2; ++k) EXPECT_LT(dwell.budget_per_s(k), 0.25 * now.budget_per_s(k));
    expect_held(now);
    expect_held(dwell);
}

TEST(PartBudgetChurn, ADwellStillAnswersALargeChangeAtOnce) {
    // The crowd doubles: the dwell delays the first step by 4 updates (a time constant), no more.
    const int now = lod_test::frames_to_reconverge(0.0f), dwell = lod_test::frames_to_reconverge(0.0f, 1.0f);
    std::printf("back within 10%% after %d frames (no dwell) and %d (dwell 1)\n", now + 1, dwell + 1);
    ASSERT_LT(now, 60);
    // Each further step waits the dwell again only if the time came back inside the band in between;
    // 30 frames of slack are a regression guard (half a second), not derived (measured: 25 -> 27).
    EXPECT_LE(dwell, now + 30);
}

}  // namespace
}  // namespace aloha
