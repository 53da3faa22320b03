// LevelCostModel: the learned average and marginal cost of a level, from per-level measured times.
#include "systems/lod/level_cost.hpp"
#include "tests/systems/lod/lod_crowd_sim.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace aloha {
namespace {

using lod_test::must_parse;
using lod_test::small_rules;

// The geometric model of small_rules (rich, mid, proxy, hidden), per-slot times given; level 0 is the
// one a test drives, the others stay empty.
struct OneLevel {
    RuleTable table = must_parse(small_rules());
    LevelCostModel model;
    std::vector<uint32_t> counts = std::vector<uint32_t>(4, 0);
    std::vector<double> ms = std::vector<double>(4, 0.0);
    // Plain least squares of the same frames (the moments fit_marginal keeps, unshrunk), for contrast.
    double n = 0, t = 0, nn = 0, nt = 0;
    bool first = true;

    OneLevel() { model.set_levels(BudgetKind::Geometry, table); }
    // One frame: `count` characters at level 0 took `level_ms`.
    void frame(uint32_t count, double level_ms, float weight) {
        counts[0] = count;
        ms[0] = level_ms;
        model.observe(counts, ms, level_ms, weight);
        const double w = 0.25 * weight, c = count;
        if (first) n = c, t = level_ms, nn = c * c, nt = c * level_ms, first = false;
        n += w * (c - n), t += w * (level_ms - t), nn += w * (c * c - nn), nt += w * (c * level_ms - nt);
    }
    [[nodiscard]] double least_squares_slope() const { return (nt - n * t) / (nn - n * n); }
};

// The plaza_budget run that never settled (docs/PERFORMANCE.md): ~30 characters at the costly level,
// their count moving by a few while the machine's speed moved too, and with it: a controller demotes
// when the machine slows (the time rises) and promotes when it recovers. Here the machine is 30% slower
// for 60 frames in every 120 (time = 0.26 ms * count * speed) and the count is 28 while it is slow, 35
// while fast (or the other way round): the time hardly moves with the count, so plain least squares
// reads a slope near zero (or far above the average). The ridge bound (fit_marginal): a drift d moves
// the marginal by at most d / (2 * 0.3) of the average, half of it for d = 0.3; 1% more is allowed
// for the average's own ripple (an EMA of weight 0.2 following the square wave).
TEST(LevelCost, MarginalStaysNearTheAverageWhenTheMachineDriftsWithTheCount) {
    constexpr double kCost = 0.26;
    for (const bool fewer_when_slow : {true, false}) {
        OneLevel m;
        for (int k = 0; k < 1200; ++k) {
            const bool slow = (k / 60) % 2 == 1;
            const uint32_t count = slow == fewer_when_slow ? 28 : 35;
            m.frame(count, kCost * count * (slow ? 1.3 : 1.0), 0.2f);
            if (k < 120) continue;
            const double average = m.model.cost(0), marginal = m.model.marginal(0);
            ASSERT_LE(std::fabs(marginal - average), 0.51 * average)
                << "frame " << k << (fewer_when_slow ? " fewer" : " more") << " when slow: marginal " << marginal
                << " average " << average;
        }
        // The scenario misleads plain least squares: fewer when slow, a slope under half the average;
        // more when slow, over one and a half times it.
        const double plain = m.least_squares_slope(), average = m.model.cost(0);
        if (fewer_when_slow) EXPECT_LT(plain, 0.5 * average);
        else EXPECT_GT(plain, 1.5 * average);
    }
}

// A level with a part that does not scale with its count (2 ms) and a count that ranges over 20-200
// (a new value every 20 frames): what one more character costs is the slope, 0.05 ms, well under the
// average (0.05 + 2 / count). With a count spread of ~52 against lambda's 0.3 * 110 = 33 the slope
// gets ~70% of the weight, so the marginal must be nearer the truth than the average, by half at least.
TEST(LevelCost, MarginalLearnsTheSlopeWhenTheCountRangesWidely) {
    constexpr double kFixed = 2.0, kSlope = 0.05;
    OneLevel m;
    lod_test::Lcg rnd;
    uint32_t count = 110;
    for (int k = 0; k < 4000; ++k) {
        if (k % 20 == 0) count = 20 + static_cast<uint32_t>(180.0f * rnd.next());
        m.frame(count, kFixed + kSlope * count, 0.2f);
    }
    const double average = m.model.cost(0), marginal = m.model.marginal(0);
    EXPECT_GT(average, 1.2 * kSlope);
    EXPECT_LE(std::fabs(marginal - kSlope), 0.5 * std::fabs(average - kSlope))
        << "marginal " << marginal << " average " << average;
}

// A level with no fixed part whose count never changes: the marginal is the average.
TEST(LevelCost, MarginalIsTheAverageForACountThatNeverMoves) {
    OneLevel m;
    for (int k = 0; k < 300; ++k) m.frame(40, 0.1 * 40, 0.2f);
    EXPECT_NEAR(m.model.marginal(0), m.model.cost(0), 1e-9);
    EXPECT_NEAR(m.model.cost(0), 0.1, 1e-6);
}

}  // namespace
}  // namespace aloha
