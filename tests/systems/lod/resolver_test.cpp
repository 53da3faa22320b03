// LodResolveJob: time hysteresis, transitions, budget demotion, change reporting, and the
// no-flicker property of the whole rules + resolver pipeline at a threshold.
#include "systems/lod/resolver.hpp"
#include "systems/lod/rule_eval.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace aloha {
namespace {

using lod_test::at_distance;
using lod_test::kFrameDt;
using lod_test::must_parse;
using lod_test::small_rules;

struct Frame {
    std::vector<LodState> states;
    std::vector<GeomLod> geom;
    std::vector<AnimLod> anim;
    std::vector<uint8_t> flags;
    std::vector<uint32_t> indices;
    explicit Frame(size_t n) : states(n), geom(n), anim(n), flags(n), indices(n) {}
    size_t resolve(const RuleTable& t, const std::vector<LodRequest>& req, bool snap = false) {
        LodResolveJob job{&t, req, states, geom, anim, flags, indices, 100, snap ? 0.0f : kFrameDt, snap};
        std::vector<std::string> errors;
        EXPECT_TRUE(job.Validate(&errors));
        return job.Run();
    }
};

LodRequest request(uint8_t g, uint8_t a, uint16_t rule) { return {g, a, rule}; }

TEST(Resolver, SnapTakesRequestsWithoutTransitions) {
    const RuleTable t = must_parse(small_rules());
    Frame f(2);
    EXPECT_EQ(f.resolve(t, {request(2, 2, 3), request(0, 0, 0)}, true), 1u);  // only #0 differs from 0/0
    EXPECT_EQ(f.states[0].geom_level, 2);
    EXPECT_EQ(f.states[0].geomorph_left_s, 0.0f);
    EXPECT_EQ(f.states[0].crossfade_left_s, 0.0f);
    EXPECT_EQ(f.states[0].rule_id, 3);
    EXPECT_EQ(f.geom[0].method, GeomMethod::RigidProxy);
    EXPECT_EQ(f.anim[0].update_interval, 8);
    EXPECT_EQ(f.indices[0], 100u);  // index_base + 0
    EXPECT_EQ(f.flags[0], 1);
    EXPECT_EQ(f.flags[1], 0);
}

TEST(Resolver, MinimumTimeAtALevelAndTransitions) {
    const RuleTable t = must_parse(small_rules());  // min_seconds 0.08: 5 frames of 1/60 s
    Frame f(1);
    f.resolve(t, {request(2, 2, 3)}, true);
    // Request "near" (rich, full) at once: held until the level has been kept 0.08 s (5 frames).
    int switched_at = -1;
    for (int frame = 1; frame <= 10; ++frame) {
        if (f.resolve(t, {request(0, 0, 1)}) == 1) {
            EXPECT_EQ(switched_at, -1);
            switched_at = frame;
            EXPECT_EQ(f.states[0].geom_level, 0);
            EXPECT_EQ(f.states[0].prev_geom_level, 2);
            EXPECT_EQ(f.states[0].geomorph_left_s, 0.2f);   // entered level's geomorph_s
            EXPECT_EQ(f.geom[0].geomorph_s, 0.2f);
            EXPECT_EQ(f.states[0].seconds_at_geom, 0.0f);
            EXPECT_EQ(f.states[0].prev_anim_level, 2);
            EXPECT_EQ(f.states[0].crossfade_left_s, 0.15f);  // entered level's crossfade_s
            EXPECT_EQ(f.states[0].rule_id, 1);
        } else if (switched_at < 0) {
            EXPECT_EQ(f.states[0].rule_id, 3);  // the rule that produced the current levels
        }
    }
    EXPECT_EQ(switched_at, 5);
    // Five more frames (5/60 s) after the switch: the morph counts down 0.2 -> 0.1167 s, the
    // cross-fade 0.15 -> 0.0667 s (float sums of five steps: 1e-6 s).
    EXPECT_NEAR(f.states[0].geomorph_left_s, 0.2f - 5.0f * kFrameDt, 1e-6f);
    EXPECT_NEAR(f.states[0].crossfade_left_s, 0.15f - 5.0f * kFrameDt, 1e-6f);
    EXPECT_NEAR(f.states[0].seconds_at_geom, 5.0f * kFrameDt, 1e-6f);
}

TEST(Resolver, LeavingHiddenIsImmediate) {
    const RuleTable t = must_parse(small_rules());
    Frame f(1);
    f.resolve(t, {request(3, 2, 0)}, true);
    EXPECT_EQ(f.resolve(t, {request(1, 2, 2)}), 1u);  // geometry leaves hidden on the first frame
    EXPECT_EQ(f.states[0].geom_level, 1);
}

// enter_after_s on "hidden" (0.25 s = 15 frames at 60 Hz): a character enters it only after asking for it
// 15 frames in a row (the frame it first asks counts 0 s); any frame asking for something else restarts
// the count; leaving is not delayed. Exact frame counts: the slack is 1e-6 s against frames of 1/60 s.
TEST(Resolver, EnterAfterNeedsAnUnbrokenRequestAndLeavesAtOnce) {
    auto j = small_rules();
    j["geometric_levels"][3]["enter_after_s"] = 0.25;
    const RuleTable t = must_parse(j);
    Frame f(1);
    f.resolve(t, {request(1, 1, 2)}, true);
    for (int frame = 1; frame <= 20; ++frame) f.resolve(t, {request(1, 1, 2)});  // held well past min_seconds
    // Asked for hidden 10 frames (0.15 s), then once for mid: never hidden.
    for (int frame = 0; frame < 10; ++frame) EXPECT_EQ(f.resolve(t, {request(3, 2, 0)}), frame == 0 ? 1u : 0u);  // animation follows at once
    EXPECT_EQ(f.states[0].geom_level, 1);
    f.resolve(t, {request(1, 2, 2)});
    int hidden_at = -1;
    for (int frame = 0; frame < 30 && hidden_at < 0; ++frame) {
        f.resolve(t, {request(3, 2, 0)});
        if (f.states[0].geom_level == 3) hidden_at = frame;
    }
    EXPECT_EQ(hidden_at, 15);  // 0 s on frame 0, 15/60 = 0.25 s on frame 15
    EXPECT_EQ(f.resolve(t, {request(1, 2, 2)}), 1u);  // leaving: on the first frame
    EXPECT_EQ(f.states[0].geom_level, 1);
    // Entering a level without enter_after_s is only subject to min_seconds, as before.
    for (int frame = 0; frame < 20; ++frame) f.resolve(t, {request(1, 2, 2)});
    EXPECT_EQ(f.resolve(t, {request(2, 2, 3)}), 1u);
    EXPECT_EQ(f.states[0].geom_level, 2);
    // A snap (first frame, teleport) enters at once.
    Frame g(1);
    g.resolve(t, {request(3, 2, 0)}, true);
    EXPECT_EQ(g.states[0].geom_level, 3);
}

// The same delay at 30, 60 and 120 Hz: the switch into hidden comes at the same simulated time, to
// within one frame of each rate.
TEST(Resolver, EnterAfterIsInSeconds) {
    auto j = small_rules();
    j["geometric_levels"][3]["enter_after_s"] = 0.4;
    const RuleTable t = must_parse(j);
    for (const int hz : {30, 60, 120}) {
        const float dt = 1.0f / static_cast<float>(hz);
        std::vector<LodState> states(1);
        std::vector<GeomLod> geom(1);
        std::vector<AnimLod> anim(1);
        LodResolveJob{&t, std::vector<LodRequest>{request(1, 1, 2)}, states, geom, anim, {}, {}, 0, 0.0f, true}.Run();
        float time = 0.0f, hidden_at = -1.0f;
        for (int frame = 1; hidden_at < 0.0f && frame < 10 * hz; ++frame) {
            time = static_cast<float>(frame) * dt;
            const std::vector<LodRequest> req{time >= 1.0f ? request(3, 2, 0) : request(1, 1, 2)};
            LodResolveJob{&t, req, states, geom, anim, {}, {}, 0, dt, false}.Run();
            if (states[0].geom_level == 3) hidden_at = time;
        }
        SCOPED_TRACE(hz);
        // The request starts on the first frame at or after 1.0 s and the switch comes 0.4 s later: at
        // 1.4 s, or one frame of this rate later when float rounding puts a frame just short of a mark.
        EXPECT_GE(hidden_at, 1.4f - 1e-4f);
        EXPECT_LE(hidden_at, 1.4f + dt + 1e-4f);
    }
}

TEST(Resolver, BudgetDemotionNeverHidesAVisibleCharacter) {
    const RuleTable t = must_parse(small_rules());  // levels: rich, mid, proxy, hidden
    EXPECT_EQ(demoted_geom_level(t, 0, 1), 1);
    EXPECT_EQ(demoted_geom_level(t, 1, 5), 2);   // stops at proxy, skips hidden
    EXPECT_EQ(demoted_geom_level(t, 3, 1), 3);   // hidden stays hidden
    EXPECT_EQ(demoted_anim_level(t, 1, 9), 2);
    Frame f(1);
    f.states[0].budget_demotion = 1;  // geometric levels removed
    f.states[0].anim_demotion = 1;    // animation levels removed (separate since the part budgets)
    f.resolve(t, {request(0, 0, 1)}, true);
    EXPECT_EQ(f.states[0].geom_level, 1);
    EXPECT_EQ(f.states[0].anim_level, 1);
    EXPECT_EQ(f.states[0].rule_id, 1);
}

TEST(Resolver, OutOfRangeStatesAreClamped) {
    const RuleTable t = must_parse(small_rules());
    std::vector<LodState> s(1);
    s[0].geom_level = 9;
    s[0].anim_level = 9;
    s[0].rule_id = 40;
    clamp_lod_states(t, s);
    EXPECT_EQ(s[0].geom_level, 3);
    EXPECT_EQ(s[0].anim_level, 2);
    EXPECT_EQ(s[0].rule_id, 3);
}

// Counts geometric level switches of one character whose distance is 20 +- 0.5 (deterministic
// LCG noise) over 1,000 frames, through rules then resolver.
int switches_at_threshold(const RuleTable& t) {
    Frame f(1);
    std::vector<LodAttributes> a(1);
    std::vector<LodRequest> req(1);
    uint32_t seed = 12345u;
    int switches = 0;
    for (int frame = 0; frame < 1000; ++frame) {
        seed = seed * 1664525u + 1013904223u;
        const float noise = (static_cast<float>(seed >> 8) / 16777216.0f - 0.5f);  // [-0.5, 0.5)
        a[0] = at_distance(20.0f + noise);
        RuleEvalJob eval{&t, a, f.states, 0, req};
        eval.Run();
        const uint8_t before = f.states[0].geom_level;
        f.resolve(t, req, frame == 0);
        if (frame > 0 && f.states[0].geom_level != before) ++switches;
    }
    return switches;
}

TEST(Resolver, NoFlickerAtAThreshold) {
    const RuleTable with = must_parse(small_rules());  // band 0.1 (threshold 20 -> leave above 22)
    EXPECT_LE(switches_at_threshold(with), 1);
    auto j = small_rules();
    j["hysteresis"] = {{"band", 0.0}, {"min_seconds", 0}};
    const RuleTable without = must_parse(j);
    // Without hysteresis the level follows the sign of the noise: about half the frames switch.
    EXPECT_GT(switches_at_threshold(without), 300);
}

}  // namespace
}  // namespace aloha
