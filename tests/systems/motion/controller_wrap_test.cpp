// A looping clip played over and over: one whose ends do not meet (AnimationClip::ends_meet) is inertialized where
// it wraps, as a level change is, so the pose never jumps there; with root motion off the root's travel over the
// ground returns to the start at each wrap; a clip whose ends meet is not touched at its wrap; the same with the
// steady step on and with throttled updates.
#include "systems/motion/controller.hpp"
#include "tests/systems/motion/motion_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace aloha {
namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr float kJump = 0.5f;  // rad: how far joint 1 ends from where it starts

// A 3-joint chain; over 1 s, joint 1 turns about X from 0 to kJump at an even rate, and the root travels
// `travel` m along X.
RawAnimation ramp(float travel) {
    RawAnimation a;
    a.name = "ramp";
    a.duration = 1.0f;
    a.tracks.resize(3);
    for (int k = 0; k <= 60; ++k) {
        const float t = static_cast<float>(k) / 60.0f;
        a.tracks[1].rotations.times.push_back(t);
        a.tracks[1].rotations.values.push_back(glm::angleAxis(kJump * t, glm::vec3(1, 0, 0)));
        a.tracks[0].translations.times.push_back(t);
        a.tracks[0].translations.values.push_back(glm::vec3(travel * t, 0.0f, 0.0f));
    }
    return a;
}

// Joint 1's angle and the root's X, each frame, over `frames` frames of `clip` played looping.
struct Played {
    std::vector<float> angle, root_x;
    size_t inertialized_frames = 0;
};

Played play_looping(const RawAnimation& clip, float crossfade, uint8_t interval, bool steady, int frames = 150, bool root_motion = true) {
    const Skeleton sk = build_skeleton(test::make_chain(3), "chain3").value();
    ClipLibrary clips;
    const ClipId id = clips.add(clip, sk).value();
    std::vector<AnimLod> lods(1);
    lods[0].crossfade_s = crossfade;
    lods[0].update_interval = interval;
    std::vector<MotionState> states(1);
    std::vector<Transform> xs(1);
    std::vector<Velocity> vs(1);
    MotionController mc(sk, clips, 1);
    mc.set_steady_steps(steady);
    MotionRequest r;
    r.kind = RequestKind::PlayClip;
    r.clip = id;
    r.loop = 1;
    r.root_motion = root_motion ? 1 : 0;
    EXPECT_TRUE(mc.push_request(0, r));
    Played out;
    for (int f = 0; f < frames; ++f) {
        mc.update(kDt, lods, states, xs, vs);
        const ConstPoseView v = mc.poses().view(0);
        // Joint 1's turn as shown (the root does not turn): throttled frames between updates interpolate the model
        // matrices only.
        out.angle.push_back(glm::angle(glm::quat_cast(glm::mat3(v.model[1]))));
        out.root_x.push_back(v.translations[0].x);
        out.inertialized_frames += mc.inertializing();
    }
    return out;
}

float largest_step(const std::vector<float>& v) {
    float worst = 0.0f;
    for (size_t i = 1; i < v.size(); ++i) worst = std::max(worst, std::abs(v[i] - v[i - 1]));
    return worst;
}

TEST(LoopingClipWrap, AClipWhoseEndsDoNotMeetIsInertializedWhereItWraps) {
    const float fade = 0.25f;
    // Per frame, the clip itself turns joint 1 by kJump * dt; the offset melts along 1 - smootherstep(t / fade),
    // whose steepest slope is 15/8 per fade: at most 15/8 * kJump * dt / fade more. Without the transition the
    // wrap jumps by kJump.
    const float bound = kJump * kDt + 1.875f * kJump * kDt / fade + 1e-3f;
    for (const uint8_t interval : {uint8_t{1}, uint8_t{3}})
        for (const bool steady : {false, true}) {
            const Played smooth = play_looping(ramp(0.0f), fade, interval, steady);
            EXPECT_LE(largest_step(smooth.angle), bound) << "interval " << int(interval) << (steady ? ", steady" : "");
            EXPECT_GT(smooth.inertialized_frames, 0u);
            const Played jumps = play_looping(ramp(0.0f), 0.0f, interval, steady);  // no transition at this level
            EXPECT_GT(largest_step(jumps.angle), 0.9f * kJump);
            std::printf("[figure] interval %d%s: largest step a frame %.4f rad inertialized (bound %.4f), %.4f without\n", int(interval),
                        steady ? ", steady step" : "", static_cast<double>(largest_step(smooth.angle)), static_cast<double>(bound),
                        static_cast<double>(largest_step(jumps.angle)));
        }
}

TEST(LoopingClipWrap, WithoutRootMotionTheRootsTravelReturnsToTheStart) {
    // Root motion off (controller_root_motion_test.cpp has it on): the root walks 1 m along X each second in the pose
    // and comes back at the wrap; the pose's jump (joint 1) is faded all the same.
    const Played p = play_looping(ramp(1.0f), 0.25f, 1, false, 150, false);
    size_t wrap = 0;
    for (size_t i = 1; i < p.root_x.size() && wrap == 0; ++i)
        if (p.root_x[i] < p.root_x[i - 1] - 0.5f) wrap = i;
    ASSERT_GT(wrap, 0u) << "the root went back to where the clip starts";
    EXPECT_LT(p.root_x[wrap], 2.0f * kDt + 1e-3f);  // a frame or two into the next cycle
    EXPECT_GT(p.angle[wrap], 0.8f * kJump) << "joint 1 still near where it was, fading";
}

TEST(LoopingClipWrap, AClipWhoseEndsMeetIsLeftAtItsWrap) {
    // Joint 1 swings out and back within the second: the ends meet, nothing is inertialized, and the steady step
    // keeps the character.
    RawAnimation swing = ramp(0.0f);
    for (size_t k = 0; k < swing.tracks[1].rotations.times.size(); ++k)
        swing.tracks[1].rotations.values[k] = glm::angleAxis(kJump * std::sin(3.14159265f * swing.tracks[1].rotations.times[k]), glm::vec3(1, 0, 0));
    const Played p = play_looping(swing, 0.25f, 1, true);
    EXPECT_EQ(p.inertialized_frames, 0u);
}

}  // namespace
}  // namespace aloha
