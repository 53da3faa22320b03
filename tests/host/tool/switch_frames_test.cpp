// The detrended whole-frame switch comparison (host/tool/switch_frames.hpp): a trend cancels, the rank
// test's chance against exact counts, and its verdicts with and without pops.
#include "host/tool/switch_frames.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace aloha::tool {
namespace {

TEST(SwitchFrames, ALinearTrendLeavesNoResidual) {
    std::vector<double> v;
    for (int k = 0; k < 20; ++k) v.push_back(0.02 + 0.0005 * k);
    const std::vector<double> r = detrended(v, 4);
    EXPECT_TRUE(std::isnan(r.front()));
    EXPECT_TRUE(std::isnan(r.back()));
    for (size_t k = 1; k + 1 < r.size(); ++k) EXPECT_NEAR(r[k], 0.0, 1e-15) << k;
    // A spike stands out by its own height over its neighbours' median.
    v[10] += 0.01;
    EXPECT_NEAR(detrended(v, 4)[10], 0.01, 1e-15);
}

TEST(SwitchFrames, RankTestMatchesExactChances) {
    // One value above two: it ranks first among 3 with chance 1/3.
    EXPECT_NEAR(rank_test_greater(std::vector<double>{3.0}, std::vector<double>{1.0, 2.0}), 1.0 / 3.0, 0.01);
    // Two values above three: both on top with chance 1 / C(5, 2) = 0.1.
    EXPECT_NEAR(rank_test_greater(std::vector<double>{9.0, 8.0}, std::vector<double>{1.0, 2.0, 3.0}), 0.1, 0.01);
    // All tied: every labelling has the same mean rank.
    EXPECT_EQ(rank_test_greater(std::vector<double>{1.0, 1.0}, std::vector<double>{1.0, 1.0}), 1.0);
    EXPECT_EQ(rank_test_greater({}, std::vector<double>{1.0}), 1.0);
    // Ten values above ten: no relabelling does as well; the estimate stops at 1 / (relabellings + 1).
    std::vector<double> high, low;
    for (int i = 0; i < 10; ++i) high.push_back(100.0 + i), low.push_back(double(i));
    EXPECT_NEAR(rank_test_greater(high, low, 20000), 1.0 / 20001.0, 1e-12);
}

// 40 frames whose change rises 20% over the run, the switches on the last 30 (as on crowd_10k's frames
// 140-179): the raw comparison fails with no pop, the detrended one does not; a switch that adds a
// tenth of the change on its frames is found.
TEST(SwitchFrames, TrendIsNoPopButAddedChangeIs) {
    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0.0, 0.0001);
    std::vector<double> change(40);
    std::vector<uint8_t> at_switch(40, 0);
    for (size_t k = 1; k < 40; ++k) {
        change[k] = 0.025 * (1.0 + 0.2 * double(k) / 39.0) + noise(rng);
        at_switch[k] = k >= 10 ? 1 : 0;
    }
    double switch_max = 0.0, ordinary_max = 0.0;
    for (size_t k = 1; k < 40; ++k) (at_switch[k] ? switch_max : ordinary_max) = std::max(at_switch[k] ? switch_max : ordinary_max, change[k]);
    EXPECT_GT(switch_max, ordinary_max);  // the raw bar: over
    const SwitchFrameTest trend = switch_frame_test(change, at_switch);
    EXPECT_EQ(trend.switch_frames, 29u);  // frame 39, the last, cannot be centred
    EXPECT_EQ(trend.ordinary_frames, 8u);  // nor frame 1, the first compared
    EXPECT_TRUE(trend.no_worse) << trend.p_value;
    // Every third switch frame 10% above the trend: a pop the test must see.
    std::vector<double> popped = change;
    std::vector<uint8_t> pops(40, 0);
    for (size_t k = 2; k < 39; k += 3) popped[k] *= 1.1, pops[k] = 1;
    const SwitchFrameTest found = switch_frame_test(popped, pops);
    EXPECT_FALSE(found.no_worse) << found.p_value;
    EXPECT_LT(found.p_value, 0.001);
}

}  // namespace
}  // namespace aloha::tool
