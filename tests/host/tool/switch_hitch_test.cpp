// The switch-hitch reading (host/tool/switch_hitch.hpp): the slowest frame against the p95, apart for
// frames with and without a level switch, and the worst frame's slowest system against its median.
#include "host/tool/switch_hitch.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace aloha::tool {
namespace {

const std::vector<std::string> kSystems = {"motion", "spring_skin"};

// 40 frames of 1 ms (0.4 + 0.6), every fourth with a switch; then one slow frame.
std::vector<HitchFrame> steady_run() {
    std::vector<HitchFrame> frames;
    for (uint32_t k = 0; k < 40; ++k) frames.push_back({1.0, k % 4 == 0 ? 2u : 0u, {0.4, 0.6}});
    return frames;
}

TEST(SwitchHitch, ASlowFrameWithoutASwitchIsNotASwitchHitch) {
    std::vector<HitchFrame> frames = steady_run();
    frames[17] = {7.0, 0, {6.4, 0.6}};  // a stall in motion, no switch
    const nlohmann::json r = switch_hitch_report(frames, kSystems);
    // The p95 by nearest rank is the 38th of the 40 sorted values: 1 ms.
    EXPECT_DOUBLE_EQ(r["p95_ms"].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(r["all"]["max_over_p95"].get<double>(), 7.0);
    EXPECT_FALSE(r["all"]["within_bar"].get<bool>());
    EXPECT_EQ(r["with_switch"]["frames"].get<size_t>(), 10u);
    EXPECT_DOUBLE_EQ(r["with_switch"]["max_over_p95"].get<double>(), 1.0);
    EXPECT_TRUE(r["with_switch"]["within_bar"].get<bool>());
    EXPECT_EQ(r["without_switch"]["frames"].get<size_t>(), 30u);
    EXPECT_FALSE(r["without_switch"]["within_bar"].get<bool>());
    EXPECT_EQ(r["worst_frame"]["index"].get<size_t>(), 17u);
    EXPECT_EQ(r["worst_frame"]["switches"].get<uint32_t>(), 0u);
    EXPECT_EQ(r["worst_frame"]["system"].get<std::string>(), "motion");
    EXPECT_DOUBLE_EQ(r["worst_frame"]["system_ms"].get<double>(), 6.4);
    EXPECT_DOUBLE_EQ(r["worst_frame"]["system_p50_ms"].get<double>(), 0.4);
    const std::string line = switch_hitch_line(r);
    EXPECT_NE(line.find("bar 3x"), std::string::npos) << line;
    EXPECT_NE(line.find("frames with a level switch 1.00x (10 frames)"), std::string::npos) << line;
    EXPECT_NE(line.find("slowest frame 17 (0 switches): motion 6.400 ms against a median 0.400 ms"), std::string::npos) << line;
}

TEST(SwitchHitch, ASlowSwitchFrameIsOneAndTheBarIsInclusive) {
    std::vector<HitchFrame> frames = steady_run();
    frames[8] = {3.0, 5, {0.4, 2.6}};  // exactly 3x: within the bar
    nlohmann::json r = switch_hitch_report(frames, kSystems);
    EXPECT_DOUBLE_EQ(r["with_switch"]["max_over_p95"].get<double>(), 3.0);
    EXPECT_TRUE(r["with_switch"]["within_bar"].get<bool>());
    frames[8].cpu_ms = 3.5;
    r = switch_hitch_report(frames, kSystems);
    EXPECT_FALSE(r["with_switch"]["within_bar"].get<bool>());
    EXPECT_TRUE(r["without_switch"]["within_bar"].get<bool>());
    EXPECT_EQ(r["worst_frame"]["system"].get<std::string>(), "spring_skin");
}

TEST(SwitchHitch, EmptySidesAndRunsAreNull) {
    EXPECT_TRUE(switch_hitch_report({}, kSystems).is_null());
    EXPECT_EQ(switch_hitch_line(nullptr), "");
    std::vector<HitchFrame> frames(5, HitchFrame{2.0, 0, {1.0, 1.0}});
    const nlohmann::json r = switch_hitch_report(frames, kSystems);
    EXPECT_EQ(r["with_switch"]["frames"].get<size_t>(), 0u);
    EXPECT_TRUE(r["with_switch"]["max_over_p95"].is_null());
    EXPECT_TRUE(r["with_switch"]["within_bar"].is_null());
    EXPECT_NE(switch_hitch_line(r).find("frames with a level switch none"), std::string::npos);
}

}  // namespace
}  // namespace aloha::tool
