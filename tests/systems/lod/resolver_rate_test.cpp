// Frame-rate independence of the rules + resolver pipeline: the resolver's clocks (time hysteresis,
// geomorph and cross-fade) run in seconds, so the same attribute trajectory stepped at 30, 60 and
// 120 Hz switches levels at the same times.
#include "systems/lod/resolver.hpp"
#include "systems/lod/rule_eval.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace aloha {
namespace {

using lod_test::at_distance;
using lod_test::must_parse;
using lod_test::small_rules;

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;
constexpr size_t kCharacters = 4;

// The attributes of character c at time t (seconds): smooth trajectories crossing the rules' distance
// thresholds (10 and 20 m, left 10% further out) at different speeds, and one leaving the view.
LodAttributes trajectory(size_t c, float t) {
    switch (c) {
        case 0: return at_distance(20.0f + 15.0f * std::sin(kTwoPi * t / 4.0f));    // slow: all three rules
        case 1: return at_distance(10.5f + 2.5f * std::sin(kTwoPi * t / 1.2f));     // fast, around "near"
        case 2: return at_distance(19.0f + 4.0f * std::sin(kTwoPi * t / 0.9f));     // fast, around "mid"
        default: {
            LodAttributes a = at_distance(8.0f);
            a.visible = (t >= 1.0f && t < 1.7f) || (t >= 3.1f && t < 3.5f) ? 0 : 1;  // out of view twice
            return a;
        }
    }
}

struct Switch {
    size_t character;
    bool geometric;
    uint8_t level;
    float time;
};

// Every level switch of the crowd over `seconds` stepped at `hz` (frame 0 at t = 0 snaps).
std::vector<Switch> switches_at(const RuleTable& t, int hz, float seconds) {
    const float dt = 1.0f / static_cast<float>(hz);
    std::vector<LodAttributes> attrs(kCharacters);
    std::vector<LodRequest> req(kCharacters);
    std::vector<LodState> states(kCharacters);
    std::vector<GeomLod> geom(kCharacters);
    std::vector<AnimLod> anim(kCharacters);
    std::vector<Switch> out;
    const int frames = static_cast<int>(std::lround(seconds * static_cast<float>(hz)));
    for (int f = 0; f <= frames; ++f) {
        const float time = static_cast<float>(f) * dt;
        for (size_t c = 0; c < kCharacters; ++c) attrs[c] = trajectory(c, time);
        RuleEvalJob{&t, attrs, states, t.default_tier, req}.Run();
        const std::vector<LodState> before = states;
        LodResolveJob job{&t, req, states, geom, anim, {}, {}, 0, f == 0 ? 0.0f : dt, f == 0};
        EXPECT_TRUE(job.Validate());
        job.Run();
        if (f == 0) continue;
        for (size_t c = 0; c < kCharacters; ++c) {
            if (states[c].geom_level != before[c].geom_level) out.push_back({c, true, states[c].geom_level, time});
            if (states[c].anim_level != before[c].anim_level) out.push_back({c, false, states[c].anim_level, time});
        }
    }
    return out;
}

TEST(ResolverRate, SameSwitchTimesAt30And60And120Hz) {
    auto j = small_rules();
    // 0.3 s is a whole number of frames at each rate (9, 18, 36), so each rate's switch lags the
    // continuous-time switch by less than its own frame: any two rates agree within 1/30 s.
    j["hysteresis"]["min_seconds"] = 0.3;
    const RuleTable t = must_parse(j);
    const std::vector<Switch> at30 = switches_at(t, 30, 6.0f);
    const std::vector<Switch> at60 = switches_at(t, 60, 6.0f);
    const std::vector<Switch> at120 = switches_at(t, 120, 6.0f);
    ASSERT_GE(at30.size(), 20u);  // the trajectories do exercise the resolver
    size_t held = 0;              // switches the time hysteresis delayed past the request change
    // Compared per character and kind of level (switches of different characters a fraction of a
    // frame apart may come in either order at different rates).
    auto of = [](const std::vector<Switch>& all, size_t c, bool geometric) {
        std::vector<Switch> out;
        for (const Switch& s : all)
            if (s.character == c && s.geometric == geometric) out.push_back(s);
        return out;
    };
    for (const auto* other : {&at60, &at120})
        for (size_t c = 0; c < kCharacters; ++c)
            for (const bool geometric : {true, false}) {
                const std::vector<Switch> a = of(at30, c, geometric), b = of(*other, c, geometric);
                ASSERT_EQ(a.size(), b.size()) << "character " << c << (geometric ? " geometric" : " animation");
                for (size_t k = 0; k < a.size(); ++k) {
                    EXPECT_EQ(a[k].level, b[k].level) << "character " << c << " switch " << k;
                    // One frame at the coarsest rate (plus float rounding of the summed frame times).
                    EXPECT_LE(std::fabs(a[k].time - b[k].time), 1.0f / 30.0f + 1e-4f)
                        << "character " << c << (geometric ? " geometric" : " animation") << " switch " << k << ": "
                        << a[k].time << " s vs " << b[k].time << " s";
                }
            }
    // The fast trajectories run into the time hysteresis: some switch exactly min_seconds after the last.
    for (size_t k = 0; k < at120.size(); ++k)
        for (size_t p = 0; p < k; ++p)
            if (at120[p].character == at120[k].character && at120[p].geometric == at120[k].geometric &&
                std::fabs(at120[k].time - at120[p].time - 0.3f) < 1e-3f)
                ++held;
    EXPECT_GT(held, 0u);
}

TEST(ResolverRate, TransitionFramesLastTheirSeconds) {
    for (const float seconds : {0.0f, 0.05f, 0.133f, 0.2f, 1.0f})
        for (const int hz : {30, 60, 120, 144}) {
            const float dt = 1.0f / static_cast<float>(hz);
            const uint16_t frames = transition_frames(seconds, dt);
            if (seconds == 0.0f) {
                EXPECT_EQ(frames, 0);
                continue;
            }
            // Rounded to the nearest frame, at least one.
            EXPECT_LE(std::fabs(static_cast<float>(frames) * dt - seconds), std::max(0.5f * dt, dt - seconds) + 1e-6f);
            EXPECT_GE(frames, 1);
        }
    EXPECT_EQ(transition_frames(0.2f, 0.0f), 0);  // no time step: nothing to count
}

}  // namespace
}  // namespace aloha
