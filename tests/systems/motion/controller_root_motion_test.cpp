// A clip whose root travels or turns, played by the controller: its root motion moves the transform and the pose is
// shown in place, so the character's body in the world (transform x pose) moves on continuously, repeat after
// repeat, where without root motion it goes back to where the clip starts at every wrap; played once, the character
// stays where the clip took it; the same with throttled updates and with the steady step on; a fade between two
// clips blends their motions.
#include "systems/motion/controller.hpp"
#include "tests/systems/motion/motion_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace aloha {
namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr float kPi = 3.14159265f;
const glm::vec3 kUp(0.0f, 1.0f, 0.0f);
// Slack on a frame's step: the 16-bit keys hold a 1 m travel in 65,535 steps, twice over a step (3.1e-5 m), plus float
// rounding of positions a few metres out (~1e-6 m).
constexpr float kStepSlack = 1e-4f;

// A 3-joint chain; over 1 s the root walks 1 m along its own heading (+Z turned by the heading) while turning
// `turn` rad about the vertical at an even rate: with turn = pi / 2, four repeats walk a closed loop.
RawAnimation walk_and_turn(float turn, float metres = 1.0f) {
    RawAnimation a;
    a.name = "walk_and_turn";
    a.duration = 1.0f;
    a.tracks.resize(3);
    glm::vec3 at(0.0f, 0.9f, 0.0f);
    constexpr int kKeys = 120;
    for (int k = 0; k <= kKeys; ++k) {
        const float t = static_cast<float>(k) / kKeys;
        if (k > 0) {  // midpoint heading of the step: the path is the arc to second order
            const float mid = turn * (t - 0.5f / kKeys);
            at += glm::angleAxis(mid, kUp) * glm::vec3(0.0f, 0.0f, metres / kKeys);
        }
        a.tracks[0].translations.times.push_back(t);
        a.tracks[0].translations.values.push_back(at);
        a.tracks[0].rotations.times.push_back(t);
        a.tracks[0].rotations.values.push_back(glm::angleAxis(turn * t, kUp));
    }
    return a;
}

struct Trace {
    std::vector<glm::vec3> root;     // the root joint in the world, each frame
    std::vector<glm::vec3> placed;   // the transform's position, each frame
    std::vector<float> speed;        // |Velocity|, each frame
    Transform first, last;           // the transform after the first and the last frame
    size_t steady_frames = 0;        // frames the character took the steady step
};

struct Options {
    bool root_motion = true;
    bool loop = true;
    uint8_t interval = 1;
    bool steady = false;
    int frames = 240;
    float speed = 1.0f;
};

Trace play(const RawAnimation& clip, const Options& o) {
    const Skeleton sk = build_skeleton(test::make_chain(3), "chain3").value();
    ClipLibrary clips;
    const ClipId id = clips.add(clip, sk).value();
    std::vector<AnimLod> lods(1);
    lods[0].update_interval = o.interval;
    std::vector<MotionState> states(1);
    std::vector<Transform> xs(1);
    xs[0].position = glm::vec3(5.0f, 0.0f, -3.0f);  // anywhere, facing anywhere
    xs[0].rotation = glm::angleAxis(0.4f, kUp);
    std::vector<Velocity> vs(1);
    MotionController mc(sk, clips, 1);
    mc.set_steady_steps(o.steady);
    MotionRequest r;
    r.kind = RequestKind::PlayClip;
    r.clip = id;
    r.loop = o.loop ? 1 : 0;
    r.root_motion = o.root_motion ? 1 : 0;
    r.speed = o.speed;
    EXPECT_TRUE(mc.push_request(0, r));
    Trace out;
    for (int f = 0; f < o.frames; ++f) {
        mc.update(kDt, lods, states, xs, vs);
        const glm::vec3 local(mc.poses().view(0).model[0][3]);
        out.root.push_back(xs[0].position + xs[0].rotation * (xs[0].scale * local));
        out.placed.push_back(xs[0].position);
        out.speed.push_back(glm::length(vs[0].linear));
        out.steady_frames += mc.steady_count();
        if (f == 0) out.first = xs[0];
    }
    out.last = xs[0];
    return out;
}

float largest_step(const std::vector<glm::vec3>& v) {
    float worst = 0.0f;
    for (size_t i = 1; i < v.size(); ++i) worst = std::max(worst, glm::length(v[i] - v[i - 1]));
    return worst;
}

TEST(RootMotion, ALoopingTravellingClipCarriesOnWhereEachRepeatEnded) {
    // 1 m a second in a straight line: 4 s of it end 4 m on. Each frame the root moves 1 m/s x dt; a frame that
    // crosses a wrap moves as much (the clip's ends meet once its travel is aside). Without root motion the
    // root goes back 1 m at every wrap and the transform stays.
    const Trace on = play(walk_and_turn(0.0f), {});
    EXPECT_LE(largest_step(on.root), 1.0f * kDt + kStepSlack);
    EXPECT_NEAR(glm::length(on.root.back() - on.root.front()), 239.0f * kDt, 1e-3f);
    EXPECT_NEAR(glm::length(on.placed.back() - glm::vec3(5.0f, 0.0f, -3.0f)), 240.0f * kDt, 1e-3f);
    // The speed reads within the 16-bit keys' step (1 m in 65,535 steps) twice over a frame: 2 x 1.5e-5 m / dt.
    for (size_t f = 1; f < on.speed.size(); ++f) EXPECT_NEAR(on.speed[f], 1.0f, 2.0f * 1.53e-5f / kDt) << "frame " << f;
    const Trace off = play(walk_and_turn(0.0f), {.root_motion = false});
    EXPECT_GT(largest_step(off.root), 0.9f);
    EXPECT_EQ(off.placed.back(), glm::vec3(5.0f, 0.0f, -3.0f));
}

TEST(RootMotion, ATurningClipTurnsTheTransformAndRepeatsAlongItsPath) {
    // A quarter turn a second along a 1 m arc: four repeats close the loop, and the transform has turned round once
    // (frame 240 against frame 0).
    const Trace on = play(walk_and_turn(0.5f * kPi), {});
    EXPECT_LE(largest_step(on.root), 1.0f * kDt + kStepSlack);
    const Trace four = play(walk_and_turn(0.5f * kPi), {.frames = 241});  // frame 240 is 4 s after frame 0
    EXPECT_LT(glm::length(four.root.back() - four.root.front()), 1e-3f);
    EXPECT_GT(std::abs(glm::dot(four.last.rotation, four.first.rotation)), 1.0f - 1e-6f);
    // Halfway round, the body is across the loop: the diameter of a circle of circumference 4 m.
    EXPECT_NEAR(glm::length(four.root[120] - four.root[0]), 4.0f / kPi, 2e-3f);
}

TEST(RootMotion, AClipPlayedOnceLeavesTheCharacterWhereItEnded) {
    // Played once at double speed: done after 0.5 s, 1 m on; the character stays there after.
    const Trace once = play(walk_and_turn(0.0f), {.loop = false, .frames = 90, .speed = 2.0f});
    EXPECT_NEAR(glm::length(once.root[89] - once.root[0]), 1.0f - 2.0f * kDt, 1e-3f);
    EXPECT_EQ(once.root[89], once.root[45]);
    EXPECT_LE(largest_step(once.root), 2.0f * kDt + kStepSlack);
}

TEST(RootMotion, ThrottledAndSteadyCharactersMoveAlike) {
    // Every third frame posed and the frames between interpolated, or the steady step asked for: the root still
    // moves on continuously (a throttled pose blends two in-place poses, whose roots stay put).
    for (const uint8_t interval : {uint8_t{1}, uint8_t{3}})
        for (const bool steady : {false, true}) {
            const Trace r = play(walk_and_turn(0.5f * kPi), {.interval = interval, .steady = steady});
            EXPECT_LE(largest_step(r.root), 1.0f * kDt + kStepSlack) << "interval " << int(interval) << (steady ? ", steady" : "");
            const Trace every = play(walk_and_turn(0.5f * kPi), {.interval = interval});
            if (steady) {
                // It takes the steady step (every frame but the first few) and moves the transform as the full step
                // does, bit for bit.
                EXPECT_GT(r.steady_frames, r.placed.size() - 10);
                for (size_t f = 0; f < r.placed.size(); ++f) ASSERT_EQ(r.placed[f], every.placed[f]) << "frame " << f;
                EXPECT_EQ(r.last.rotation, every.last.rotation);
            }
            EXPECT_LT(glm::length(r.placed.back() - play(walk_and_turn(0.5f * kPi), {}).placed.back()), 1e-4f);
        }
}

TEST(RootMotion, AFadeBetweenTwoClipsBlendsTheirMotions) {
    // 1 m/s for a second, then a 3 m/s clip faded in over 0.5 s: the transform's step goes from 1 to 3 m/s x dt
    // as the poses blend (linearly: at most 2 m/s x dt / 30 frames more a frame), not at the switch (2 m/s x dt).
    const Skeleton sk = build_skeleton(test::make_chain(3), "chain3").value();
    ClipLibrary clips;
    const ClipId slow = clips.add(walk_and_turn(0.0f, 1.0f), sk).value();
    const ClipId fast = clips.add(walk_and_turn(0.0f, 3.0f), sk).value();
    std::vector<AnimLod> lods(1);
    std::vector<MotionState> states(1);
    std::vector<Transform> xs(1);
    std::vector<Velocity> vs(1);
    MotionController mc(sk, clips, 1);
    MotionRequest a;
    a.kind = RequestKind::PlayClip;
    a.clip = slow;
    a.duration = 1.0f;
    MotionRequest b = a;
    b.clip = fast;
    b.duration = -1.0f;
    b.crossfade_s = 0.5f;
    ASSERT_TRUE(mc.push_request(0, a));
    ASSERT_TRUE(mc.push_request(0, b));
    std::vector<float> steps;
    for (int f = 0; f < 120; ++f) {
        const glm::vec3 before = xs[0].position;
        mc.update(kDt, lods, states, xs, vs);
        steps.push_back(glm::length(xs[0].position - before));
    }
    // The clips' keys are 16-bit: a 3 m range in steps of 4.6e-5 m, so a frame's step, a difference of two sampled
    // positions, reads its speed to within 2 x 4.6e-5 m / dt = 0.0055 m/s.
    constexpr float kKeyNoise = 0.0055f;
    float largest_change = 0.0f;
    for (size_t f = 2; f < steps.size(); ++f) largest_change = std::max(largest_change, std::abs(steps[f] - steps[f - 1]) / kDt);
    EXPECT_LE(largest_change, 2.0f / 30.0f + 2.0f * kKeyNoise);
    EXPECT_NEAR(steps[10] / kDt, 1.0f, kKeyNoise);
    EXPECT_NEAR(steps[75] / kDt, 2.0f, kKeyNoise);  // halfway through the fade (frames 61-90)
    EXPECT_NEAR(steps.back() / kDt, 3.0f, kKeyNoise);
}

}  // namespace
}  // namespace aloha
