// The local pop test (host/tool/pop_statistics.hpp): its Poisson-binomial tail and its verdicts on
// series with and without pops.
#include "host/tool/pop_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace aloha::tool {
namespace {

double binomial_at_least(int n, double p, int k) {
    double below = 0.0;
    for (int j = 0; j < k; ++j) below += std::tgamma(n + 1.0) / (std::tgamma(j + 1.0) * std::tgamma(n - j + 1.0)) * std::pow(p, j) * std::pow(1.0 - p, n - j);
    return 1.0 - below;
}

TEST(PopStatistics, PoissonBinomialWithEqualChancesIsTheBinomialTail) {
    const std::vector<double> p(10, 0.2);
    for (int k = 0; k <= 10; ++k) EXPECT_NEAR(poisson_binomial_at_least(p, size_t(k)), binomial_at_least(10, 0.2, k), 1e-12) << k;
    EXPECT_EQ(poisson_binomial_at_least(p, 11), 0.0);
    EXPECT_EQ(poisson_binomial_at_least({}, 0), 1.0);
}

TEST(PopStatistics, PoissonBinomialWithUnequalChances) {
    // Two trials 0.5 and 0.25: P(>= 1) = 1 - 0.5 * 0.75, P(2) = 0.125.
    const std::vector<double> p{0.5, 0.25};
    EXPECT_NEAR(poisson_binomial_at_least(p, 1), 0.625, 1e-15);
    EXPECT_NEAR(poisson_binomial_at_least(p, 2), 0.125, 1e-15);
}

// Exchangeable changes (every frame's change drawn from one law): the switch frame is the largest of nine
// with probability 1/9, so the count above stays within 4 standard deviations of n / 9 (a false failure
// has probability ~6e-5; the seed is fixed, so this run is deterministic).
TEST(PopStatistics, ExchangeableSeriesShowNoMorePopsThanChance) {
    std::mt19937 rng(7);
    std::lognormal_distribution<double> change(-5.0, 0.6);
    std::vector<LocalPopEvent> events(2000);
    for (LocalPopEvent& e : events) {
        e.change = change(rng);
        for (int h = 0; h < 8; ++h) e.history.push_back(change(rng));
    }
    const LocalPopSummary s = local_pop_summary(events, 4);
    EXPECT_EQ(s.events, 2000u);
    EXPECT_NEAR(s.expected_above, 2000.0 / 9.0, 1e-9);
    const double sd = std::sqrt(2000.0 * (1.0 / 9.0) * (8.0 / 9.0));
    EXPECT_LE(std::abs(double(s.above) - s.expected_above), 4.0 * sd);
    EXPECT_GT(s.p_value, 1e-4);
}

// Every fifth switch adds half its pixels' largest ordinary change: far more switches above their
// history than 1/9 of them, found with a vanishing p-value.
TEST(PopStatistics, SwitchesThatAddChangeAreFound) {
    std::mt19937 rng(11);
    std::lognormal_distribution<double> change(-5.0, 0.6);
    std::vector<LocalPopEvent> events(200);
    for (size_t i = 0; i < events.size(); ++i) {
        LocalPopEvent& e = events[i];
        for (int h = 0; h < 8; ++h) e.history.push_back(change(rng));
        double largest = 0.0;
        for (const double h : e.history) largest = std::max(largest, h);
        e.change = i % 5 == 0 ? 1.5 * largest : change(rng);
    }
    const LocalPopSummary s = local_pop_summary(events, 4);
    EXPECT_GE(s.above, 40u);
    EXPECT_LT(s.p_value, 1e-6);
    EXPECT_FALSE(s.no_more_than_chance);
    EXPECT_GE(s.worst_ratio, 1.5 - 1e-12);  // the added ones; an ordinary draw may exceed its history by more
}

TEST(PopStatistics, InvisibleAndShortHistoryEventsAreNotTested) {
    std::vector<LocalPopEvent> events;
    events.push_back({0.0, {0.0, 0.0, 0.0, 0.0, 0.0}});  // hidden: no change now nor before
    events.push_back({0.3, {0.1, 0.2}});                   // two frames of history: too short
    events.push_back({0.3, {0.1, 0.2, 0.1, 0.4}});         // tested, below its history's largest
    const LocalPopSummary s = local_pop_summary(events, 4);
    EXPECT_EQ(s.invisible, 1u);
    EXPECT_EQ(s.short_history, 1u);
    EXPECT_EQ(s.events, 1u);
    EXPECT_EQ(s.above, 0u);
    EXPECT_NEAR(s.expected_above, 0.2, 1e-15);
    EXPECT_EQ(s.p_value, 1.0);
    EXPECT_NEAR(s.worst_ratio, 0.75, 1e-15);
}

// A character appearing where nothing moved before (a change over an all-zero history) counts as above.
TEST(PopStatistics, ChangeOverAStillHistoryCountsAsAbove) {
    const std::vector<LocalPopEvent> events{{0.01, {0.0, 0.0, 0.0, 0.0}}};
    const LocalPopSummary s = local_pop_summary(events, 4);
    EXPECT_EQ(s.events, 1u);
    EXPECT_EQ(s.above, 1u);
    EXPECT_NEAR(s.p_value, 0.2, 1e-15);
    EXPECT_TRUE(s.no_more_than_chance);
}

// A camera closing in: every pixel's change grows 10% a frame. On the raw changes a switch that adds nothing
// is above its 8-frame history most of the time; as shares of the whole frame's change, at chance.
TEST(PopStatistics, SharesOfTheFrameCancelAWholePictureTrend) {
    std::mt19937 rng(3);
    std::lognormal_distribution<double> noise(0.0, 0.3);
    std::vector<LocalPopEvent> raw, shares;
    for (int i = 0; i < 400; ++i) {
        // Frames 0..8: frame 8 is the switch frame; the switch's pixels hold a tenth of each frame's change.
        std::vector<double> whole(9), local(9);
        for (int f = 0; f < 9; ++f) {
            whole[size_t(f)] = 0.01 * std::pow(1.1, f) * noise(rng);
            local[size_t(f)] = 0.1 * whole[size_t(f)] * noise(rng);
        }
        LocalPopEvent e{local[8], {}};
        std::vector<double> history_whole;
        for (int h = 7; h >= 0; --h) e.history.push_back(local[size_t(h)]), history_whole.push_back(whole[size_t(h)]);
        raw.push_back(e);
        shares.push_back(share_of_frame(e, whole[8], history_whole));
    }
    const LocalPopSummary r = local_pop_summary(raw, 4), s = local_pop_summary(shares, 4);
    EXPECT_LT(r.p_value, 1e-6);  // the trend alone looks like pops
    const double sd = std::sqrt(400.0 * (1.0 / 9.0) * (8.0 / 9.0));
    EXPECT_LE(std::abs(double(s.above) - s.expected_above), 4.0 * sd);
    EXPECT_GT(s.p_value, 1e-4);
}

TEST(PopStatistics, ShareOfFrameDropsStillFrames) {
    const LocalPopEvent e{0.02, {0.01, 0.03, 0.02}};
    const LocalPopEvent s = share_of_frame(e, 0.1, std::vector<double>{0.05, 0.0, 0.1});
    EXPECT_NEAR(s.change, 0.2, 1e-15);
    ASSERT_EQ(s.history.size(), 2u);
    EXPECT_NEAR(s.history[0], 0.2, 1e-15);
    EXPECT_NEAR(s.history[1], 0.2, 1e-15);
    EXPECT_EQ(share_of_frame(e, 0.0, std::vector<double>{0.05}).change, 0.0);
}

}  // namespace
}  // namespace aloha::tool
