// The part budget's confidence test (BudgetParams::confidence): a step only when the mean the part
// steers on is outside the tolerance band by k of its standard errors. Under stationary noise much
// wider than the band the band test (confidence 0) steps on noise, each step moving the mean by a
// fraction of the band and so provoking the next (the plaza's slow cycle); the confidence test settles
// and then holds. After a step of the machine's load it is back within 10% within a bound derived
// below from the controller's own settings.
#include "systems/lod/part_budget.hpp"
#include "tests/systems/lod/part_budget_sim.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace aloha {
namespace {

using lod_test::BudgetSim;

struct NoisyRun {
    size_t anim_steps = 0, geom_steps = 0;  // steps after settling
    double anim_mean = 0.0, geom_mean = 0.0, anim_target = 0.0, geom_target = 0.0;
};

// 500 characters, both parts at 0.7 of the full cost, measurements uniform in +-`noise` of the truth
// (seeded); settles `settle` frames, then counts steps and averages the measured times over `frames`.
NoisyRun run_noisy(float confidence, double noise, int settle = 600, int frames = 1800) {
    BudgetSim sim;
    sim.noise = noise;
    sim.add(500, 2.0f, 40.0f);
    sim.frame();
    NoisyRun r;
    r.anim_target = 0.7 * sim.anim_truth;
    r.geom_target = 0.7 * sim.geom_truth;
    sim.common.confidence = confidence;
    sim.set_targets(r.anim_target, r.geom_target);
    for (int f = 0; f < settle; ++f) sim.frame();
    const size_t anim0 = sim.anim_steps.size(), geom0 = sim.geom_steps.size();
    for (int f = 0; f < frames; ++f) {
        sim.frame();
        r.anim_mean += sim.anim_ms / frames;
        r.geom_mean += sim.geom_ms / frames;
    }
    r.anim_steps = sim.anim_steps.size() - anim0;
    r.geom_steps = sim.geom_steps.size() - geom0;
    return r;
}

TEST(PartBudgetConfidence, StationaryNoiseSettlesThenHolds) {
    // +-20% uniform: one frame's deviation is 11.5% of the truth, the band 5% (tolerance): the smoothed
    // time (weight 0.25) still spreads 0.115 * sqrt(0.25 / 1.75) = 4.4%, past the band every few frames,
    // and short of the reaction band (25%, 5.7 of its deviations), where the band test would act.
    const NoisyRun band = run_noisy(0.0f, 0.2), confident = run_noisy(3.0f, 0.2);
    std::printf("30 s after settling, steps animation / geometry: band test %zu / %zu, confidence 3 %zu / %zu; "
                "means %.3f / %.3f and %.3f / %.3f of the targets\n",
                band.anim_steps, band.geom_steps, confident.anim_steps, confident.geom_steps, band.anim_mean / band.anim_target,
                band.geom_mean / band.geom_target, confident.anim_mean / confident.anim_target, confident.geom_mean / confident.geom_target);
    // The band test keeps stepping on noise.
    EXPECT_GT(band.anim_steps + band.geom_steps, 20u);
    // The confidence test: a look of a mean fires on noise with probability under 2 (1 - Phi(3)) = 0.27%
    // and a growing mean's looks are nearly one look; after settling at most one false step per part is
    // allowed (expected: well under one).
    EXPECT_LE(confident.anim_steps, 1u);
    EXPECT_LE(confident.geom_steps, 1u);
    // The promise still holds: each part's mean within 10% of its target.
    EXPECT_NEAR(confident.anim_mean, confident.anim_target, 0.1 * confident.anim_target);
    EXPECT_NEAR(confident.geom_mean, confident.geom_target, 0.1 * confident.geom_target);
}

// The bound on the frames from a step of the load (every measured time x `load`) until the true time
// is back within 10% of the target, from the settings alone, for a true error that was within the
// band before. Noise of one frame sigma (ms). Worst cases taken at each turn:
// - the error just after: e0 = load * (target + band) - target;
// - the smoothed time (weight a) has taken in e0 (1 - (1 - a)^j) after j frames; the slow mean
//   restarts from it once they are T = k sigma sqrt(2 a / (2 - a)) apart (both at most the smoothed
//   time's variance factor) and again at each step, so the estimate lags the truth by at most
//   L(j) = e0 (1 - a)^j + T;
// - a step is taken when the estimate is over the trigger B = band + k sigma sqrt(a / (2 - a)) and no
//   settle frame is left, and removes gain x the estimate (the costs learned before the load are
//   the true ones over load: a step removes at least what it predicts), so the error falls to at most
//   (1 - gain) e + gain L(j); with the estimate at or under B there is no step, and the error then is
//   at most B + L(j), which falls under 10% once L(j) has shrunk (B + T < 10%: checked);
// - one frame more: the budget steers on the last frame's measurement.
int derived_bound(double load, double target, double sigma, const BudgetParams& c, const BudgetPartParams& p) {
    const double a = c.smoothing, k = c.confidence, g = p.gain, band = p.tolerance * target;
    const double T = k * sigma * std::sqrt(2.0 * a / (2.0 - a)), B = band + k * sigma * std::sqrt(a / (2.0 - a));
    const double e0 = load * (target + band) - target, goal = 0.1 * target;
    if (B + T >= goal) return -1;  // no bound: the noise is too wide for the band
    double e = e0;
    int j = 0, settle = 0;
    while (e > goal && j < 100000) {
        const double lag = e0 * std::pow(1.0 - a, j) + T;
        if (settle > 0) --settle;
        else if (e - lag > B) e = (1.0 - g) * e + g * lag, settle = c.settle_frames;
        ++j;
    }
    return j + 1;
}

TEST(PartBudgetConfidence, ALoadStepIsAnsweredWithinTheDerivedBound) {
    for (double load : {1.3, 1.5, 0.75}) {
        BudgetSim sim;
        sim.add(500);
        sim.frame();
        const double target = 0.6 * sim.anim_truth;
        sim.common.confidence = 3.0f;  // the confidence test (the default, 0, is the band test)
        sim.set_targets(target, 0.0);
        for (int f = 0; f < 600; ++f) sim.frame();
        sim.load = load;
        int last_out = -1;
        for (int f = 0; f < 600; ++f) {
            sim.frame();
            if (std::fabs(sim.anim_truth * load - target) > 0.1 * target) last_out = f;
        }
        // Uniform noise of half-width n has deviation n / sqrt(3), of the truth near the target (x load).
        const double sigma = sim.noise / std::sqrt(3.0) * target * std::max(1.0, load);
        const int bound = derived_bound(std::max(load, 1.0 / load), target, sigma, sim.common, sim.anim.params());
        std::printf("load x%.2f: back within 10%% after %d frames, bound %d\n", load, last_out + 1, bound);
        ASSERT_GT(bound, 0);
        EXPECT_LE(last_out + 1, bound);
    }
}

// Spikes (another process takes the core one frame in ten, tripling the time) are part of the time the
// budget holds: the mean of the measured times, spikes included, must settle within 10% of the target.
// Spikes add 20% to the mean (0.1 x 2); the fast average clips each at 3 noise widths, so a slow mean of
// the clipped values would sit near the target while the true mean stayed up to ~20% over it.
TEST(PartBudgetConfidence, SpikesCountInTheMeanItHolds) {
    BudgetSim sim;
    sim.spike_every = 10;
    sim.spike_factor = 3.0;
    sim.add(500, 2.0f, 40.0f);
    sim.frame();
    const double anim_target = 0.7 * sim.anim_truth * 1.2, geom_target = 0.7 * sim.geom_truth * 1.2;
    sim.common.confidence = 3.0f;
    sim.set_targets(anim_target, geom_target);
    for (int f = 0; f < 1200; ++f) sim.frame();
    double anim = 0, geom = 0;
    const int frames = 1800;  // a multiple of the spike period: every window holds its share of spikes
    for (int f = 0; f < frames; ++f) {
        sim.frame();
        anim += sim.anim_ms, geom += sim.geom_ms;
    }
    anim /= frames, geom /= frames;
    std::printf("with spikes: animation %.3fx, geometry %.3fx of target\n", anim / anim_target, geom / geom_target);
    EXPECT_NEAR(anim / anim_target, 1.0, 0.1);
    EXPECT_NEAR(geom / geom_target, 1.0, 0.1);
}

TEST(PartBudgetConfidence, TheCrowdDoublingIsAnsweredAsQuicklyAsByTheBandTest) {
    // The slow mean restarts from the smoothed time as soon as they part: a large change is not
    // averaged away. Regression guard (measured 25 and 25 frames): no more than a time constant slower.
    const int band = lod_test::frames_to_reconverge(0.0f, 0.0f, 0.0f), confident = lod_test::frames_to_reconverge(0.0f, 0.0f, 3.0f);
    std::printf("crowd doubled: back within 10%% after %d frames (band test) and %d (confidence 3)\n", band + 1, confident + 1);
    ASSERT_GE(band, 0);
    EXPECT_LE(confident, band + 4);
}

}  // namespace
}  // namespace aloha
