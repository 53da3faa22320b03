// BudgetNoise and TrackedMean: the long-run noise of a series from batch means, and averages that
// know their standard error.
#include "systems/lod/budget_noise.hpp"
#include "tests/systems/lod/lod_crowd_sim.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

TEST(BudgetNoise, WhiteNoiseGivesItsStandardDeviation) {
    // Uniform in +-h: deviation h / sqrt(3). 2,000 differences averaged plainly (weight 0): the variance
    // to sqrt(2 / 2000) = 3.2%, sigma to half that; 3 of those allowed.
    lod_test::Lcg rnd{5u};
    BudgetNoise n;
    const double h = 0.3;
    for (int i = 0; i < 4 * 2001; ++i) n.observe(1.0 + h * (2.0 * rnd.next() - 1.0), 4, 0.0);
    EXPECT_EQ(n.samples(), 2000);
    EXPECT_NEAR(n.sigma(), h / std::sqrt(3.0), 3 * 0.016 * h / std::sqrt(3.0));
}

TEST(BudgetNoise, NoiseThatCancelsWithinABatchAddsNothing) {
    // Alternating +-h, period 2, in batches of 4: every batch mean is the same, nothing reaches an average.
    BudgetNoise n;
    for (int i = 0; i < 400; ++i) n.observe(i % 2 ? 1.2 : 0.8, 4, 0.04);
    EXPECT_NEAR(n.sigma(), 0.0, 1e-12);
}

TEST(BudgetNoise, ShiftsAndBreaksKeepChangesOut) {
    // A constant that a switch moves by 0.5 mid-batch: shifted, the batches still agree.
    BudgetNoise n;
    for (int i = 0; i < 10; ++i) n.observe(1.0, 4, 0.04);
    n.shift(0.5);
    for (int i = 0; i < 10; ++i) n.observe(1.5, 4, 0.04);
    EXPECT_NEAR(n.sigma(), 0.0, 1e-12);
    // A change nobody predicted, with the batches broken where it was found: not noise either.
    n.break_batches();
    for (int i = 0; i < 12; ++i) n.observe(3.0, 4, 0.04);
    EXPECT_NEAR(n.sigma(), 0.0, 1e-12);
    // Unbroken, it is.
    for (int i = 0; i < 4; ++i) n.observe(4.0, 4, 0.04);
    EXPECT_GT(n.sigma(), 0.1);
}

TEST(TrackedMean, KnowsItsVarianceFactor) {
    TrackedMean m;
    EXPECT_TRUE(m.empty());
    for (double y : {1.0, 2.0, 3.0, 6.0}) m.add_to_mean(y);
    EXPECT_DOUBLE_EQ(m.mean, 3.0);
    EXPECT_NEAR(m.factor, 0.25, 1e-12);  // the plain mean of 4
    TrackedMean e;
    for (int i = 0; i < 200; ++i) e.add(1.0, 0.25);
    EXPECT_NEAR(e.factor, 0.25 / 1.75, 1e-9);  // an EMA of weight a: a / (2 - a)
}

}  // namespace
}  // namespace aloha
