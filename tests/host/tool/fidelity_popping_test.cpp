// The fidelity report's local pop tests (host/tool/fidelity_popping.hpp): a switch's pixels' change
// against the frames before it, and against the frames before and after it (centred).
#include "host/tool/fidelity_popping.hpp"

#include <gtest/gtest.h>

#include <functional>

namespace aloha::tool {
namespace {

// 21 frames whose whole change is 0.01 each, one switch (level 1 -> 2) on frame 10 whose rectangles'
// change on frame k is rect(k): the switch frame's history (frames 9..2) in by_pair, and frames 11..18
// carrying their change in its rectangles as later_changes, the way the probe records them.
std::vector<FidelityFrame> one_switch(const std::function<double(int)>& rect) {
    std::vector<FidelityFrame> frames(21);
    for (auto& f : frames) f.changed_fraction = 0.01;
    SwitchPairChange p;
    p.from = 1;
    p.to = 2;
    p.characters = 1;
    p.change = rect(10);
    for (int h = 9; h >= 2; --h) p.history.push_back(rect(h));
    p.change_before = p.history.front();
    frames[10].switches = 1;
    frames[10].by_pair.push_back(p);
    for (int k = 11; k <= 18; ++k) frames[size_t(k)].later_changes.push_back({uint32_t(k - 10), 0, rect(k)});
    return frames;
}

nlohmann::json local(const std::vector<FidelityFrame>& frames) { return local_popping(with_changes_after(frames), {}); }

TEST(FidelityPopping, LaterChangesFillTheSwitchsFramesAfterNearestFirst) {
    const auto frames = with_changes_after(one_switch([](int k) { return 0.001 * k; }));
    const std::vector<double> after = frames[10].by_pair[0].after;
    ASSERT_EQ(after.size(), 8u);
    for (size_t h = 0; h < after.size(); ++h) EXPECT_DOUBLE_EQ(after[h], 0.001 * double(11 + h));
}

// Change rising steadily in the rectangles (a nearer character moving across them): above every frame
// before, so the one-sided test counts it, but below the frames after: the centred test does not.
TEST(FidelityPopping, ARisingChangeIsAbovePastFramesButNotAPopWhenCentred) {
    const nlohmann::json j = local(one_switch([](int k) { return 0.001 * k; }));
    EXPECT_EQ(j["events"], 1);
    EXPECT_EQ(j["above_history"], 1);
    EXPECT_NEAR(j["expected_above_without_pops"].get<double>(), 1.0 / 9.0, 1e-12);  // largest of 9 by chance
    EXPECT_EQ(j["centred"]["events"], 1);
    EXPECT_EQ(j["centred"]["above_history"], 0);
    EXPECT_NEAR(j["centred"]["expected_above_without_pops"].get<double>(), 1.0 / 17.0, 1e-12);  // largest of 17
}

// A transient: the switch frame's change three times its pixels' usual one: a pop for both tests, and
// alone it is already improbable for the centred one (p = 1/17).
TEST(FidelityPopping, ASpikeIsAPopForBothTests) {
    const nlohmann::json j = local(one_switch([](int k) { return k == 10 ? 0.003 : 0.001; }));
    EXPECT_EQ(j["above_history"], 1);
    EXPECT_EQ(j["centred"]["above_history"], 1);
    EXPECT_NEAR(j["centred"]["p_value"].get<double>(), 1.0 / 17.0, 1e-12);
    EXPECT_NEAR(j["centred"]["worst_ratio_to_history_max"].get<double>(), 3.0, 1e-9);
}

// A switch with fewer than 4 frames after it (the end of the run) is left out of the centred test only.
TEST(FidelityPopping, TooFewFramesAfterLeaveTheSwitchOutOfTheCentredTest) {
    auto frames = one_switch([](int k) { return k == 10 ? 0.003 : 0.001; });
    frames.resize(13);  // frames 11 and 12 after the switch
    const nlohmann::json j = local(frames);
    EXPECT_EQ(j["events"], 1);
    EXPECT_EQ(j["centred"]["events"], 0);
    EXPECT_EQ(j["centred"]["short_history"], 1);
}

// The error-change bar: 20 frames, ordinary ones changing the error by 0.001 to 0.0019 (p95 0.0019), a
// switch frame at 0.0015 with two thirds of it inside its characters: within the bar, share 2/3. A second
// switch frame at 0.004 puts the switch frames over it.
TEST(FidelityPopping, ErrorChangeBarComparesSwitchFramesWithOrdinaryOnes) {
    std::vector<FidelityFrame> frames(21);
    for (size_t k = 1; k < frames.size(); ++k) frames[k].error_change = 0.001 + 0.0001 * double(k % 10);
    frames[10].switches = 1;
    frames[10].error_change = 0.0015;
    frames[10].error_change_in_switches = 0.001;
    nlohmann::json j = error_change_popping(frames);
    EXPECT_EQ(j["switch_frames"], 1);
    EXPECT_EQ(j["ordinary_frames"], 19);
    EXPECT_NEAR(j["ordinary_error_change_p95"].get<double>(), 0.0019, 1e-12);
    EXPECT_EQ(j["switch_no_worse_than_ordinary_p95"], true);
    EXPECT_NEAR(j["share_inside_switching_characters"].get<double>(), 2.0 / 3.0, 1e-12);
    frames[15].switches = 3;
    frames[15].error_change = 0.004;
    j = error_change_popping(frames);
    EXPECT_EQ(j["switch_no_worse_than_ordinary_p95"], false);
    // With every frame after the first holding a switch there is nothing to compare with.
    for (auto& f : frames) f.switches = 1;
    EXPECT_TRUE(error_change_popping(frames)["switch_no_worse_than_ordinary_p95"].is_null());
}

// A switch frame over the ordinary p95: when its switching characters' rectangles hold little of its
// change it stays over without them (something else raised the frame); when they hold the excess it does not.
TEST(FidelityPopping, SwitchFramesOverTheP95WithAndWithoutTheirSwitchingCharacters) {
    std::vector<FidelityFrame> frames(5);
    for (auto& f : frames) f.changed_fraction = 0.010;
    SwitchPairChange small, large;
    small.change = 0.0001;  // a character entering at the edge of the view: the frame is over by itself
    large.change = 0.0030;  // a switch carrying the excess
    frames[2].switches = 1, frames[2].changed_fraction = 0.012, frames[2].by_pair = {small};
    frames[3].switches = 2, frames[3].changed_fraction = 0.012, frames[3].by_pair = {small, large};
    frames[4].switches = 1, frames[4].changed_fraction = 0.009, frames[4].by_pair = {large};  // under the p95
    const nlohmann::json j = switch_frames_over_p95(frames, 0.010);
    EXPECT_EQ(j["switch_frames_over"], 2);
    EXPECT_EQ(j["over_even_without_the_switching_characters"], 1);
    ASSERT_EQ(j["frames"].size(), 2u);
    EXPECT_EQ(j["frames"][0]["frame"], 2);
    EXPECT_EQ(j["frames"][0]["over_without_them"], true);
    EXPECT_NEAR(j["frames"][1]["change_in_switching_characters"].get<double>(), 0.0031, 1e-12);
    EXPECT_EQ(j["frames"][1]["over_without_them"], false);
    // A switching character crossing the near plane has no rectangle: its share is unknown.
    frames[2].switches_without_rect = 1;
    EXPECT_EQ(switch_frames_over_p95(frames, 0.010)["over_even_without_the_switching_characters"], 0);
}

// The control: switch frames that come when the picture itself changes most (the reference's change as
// high as the LOD picture's) fail the raw bar and pass once the reference's change is taken out; a switch
// that adds change of its own fails both. 21 frames, the picture's own change 0.001 to 0.0019 a frame.
TEST(FidelityPopping, TheControlReadsTheSwitchFramesOnTheReferencesOwnChange) {
    std::vector<FidelityFrame> frames(21);
    for (size_t k = 1; k < frames.size(); ++k) {
        frames[k].reference_changed_fraction = 0.001 + 0.0001 * double(k % 10);
        frames[k].changed_fraction = frames[k].reference_changed_fraction;
    }
    for (size_t k : {4u, 9u, 14u, 19u}) {  // the frames where the picture changes most (k % 10 == 9 or 4)
        frames[k].switches = 1;
        frames[k].reference_changed_fraction += 0.002;
        frames[k].changed_fraction += 0.002;
    }
    nlohmann::json j = reference_change_control(frames);
    EXPECT_EQ(j["switch_frames"], 4);
    EXPECT_EQ(j["ordinary_frames"], 16);
    EXPECT_EQ(j["switch_no_worse_than_ordinary_p95"], false);  // the control fails too: the picture's own motion
    EXPECT_LT(j["detrended"]["p_value"].get<double>(), 0.05);
    EXPECT_EQ(j["raw_less_control"]["detrended"]["no_worse_than_ordinary"], true);  // nothing beyond it
    // The same switches adding 0.001 of their own: the control is unchanged, the difference ranks them first.
    for (size_t k : {4u, 9u, 14u, 19u}) frames[k].changed_fraction += 0.001;
    j = reference_change_control(frames);
    EXPECT_EQ(j["switch_no_worse_than_ordinary_p95"], false);
    EXPECT_EQ(j["raw_less_control"]["detrended"]["no_worse_than_ordinary"], false);
}

}  // namespace
}  // namespace aloha::tool
