// Root motion tracks (systems/motion/root_motion.hpp): the ground motions' algebra, a clip's track against the root's
// own travel and turn, which clips move, and the looping clock's repeats.
#include "systems/motion/clip.hpp"
#include "systems/motion/root_motion.hpp"
#include "systems/motion/sampling.hpp"
#include "tests/systems/motion/motion_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

namespace aloha {
namespace {

constexpr float kPi = 3.14159265f;
const glm::vec3 kUp(0.0f, 1.0f, 0.0f);

// Float rounding of a few compositions of metre-sized motions (the tests' tolerance, not a measured bound).
constexpr float kEps = 1e-5f;

void expect_near(const glm::vec3& a, const glm::vec3& b, float eps) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

TEST(GroundMotion, TurnsAsAQuaternionAboutTheVerticalAndComposes) {
    const GroundMotion a{{0.3f, -1.2f}, 0.7f}, b{{-2.0f, 0.5f}, -1.9f};
    const glm::vec3 p(0.4f, 1.3f, -0.8f);
    // apply = rotation() then the offset; the height is kept.
    expect_near(a.apply(p), glm::angleAxis(0.7f, kUp) * p + glm::vec3(0.3f, 0.0f, -1.2f), kEps);
    expect_near(a.after(b).apply(p), a.apply(b.apply(p)), kEps);
    expect_near(a.inverse().apply(a.apply(p)), p, kEps);
    expect_near(a.after(a.inverse()).apply(p), p, kEps);
    // power(n): n compositions, and the inverse's for n < 0.
    GroundMotion three = a.after(a.after(a));
    expect_near(a.power(3).apply(p), three.apply(p), kEps);
    expect_near(a.power(-3).apply(three.apply(p)), p, kEps);
    expect_near(a.power(0).apply(p), p, 0.0f);
    // Many repeats: a quarter turn about a point 1 m off the axis four times over is the identity.
    const GroundMotion quarter{{1.0f, 1.0f}, 0.5f * kPi};  // a turn about a fixed point
    expect_near(quarter.power(4000).apply(p), p, 1e-3f);
}

// A clip over a 3-joint chain: over 1 s the root goes from (x0, z0) along `travel` (m, ground) and turns `turn`
// rad about the vertical, both at an even rate, and pitches `pitch` rad about X at the same time.
RawAnimation moving(glm::vec2 start, glm::vec2 travel, float turn, float pitch = 0.0f) {
    RawAnimation a;
    a.name = "moving";
    a.duration = 1.0f;
    a.tracks.resize(3);
    for (int k = 0; k <= 30; ++k) {
        const float t = static_cast<float>(k) / 30.0f;
        a.tracks[0].translations.times.push_back(t);
        a.tracks[0].translations.values.push_back(glm::vec3(start.x + travel.x * t, 0.9f, start.y + travel.y * t));
        a.tracks[0].rotations.times.push_back(t);
        a.tracks[0].rotations.values.push_back(glm::angleAxis(turn * t, kUp) * glm::angleAxis(pitch * t, glm::vec3(1, 0, 0)));
    }
    return a;
}

const Skeleton& chain3() {
    static const Skeleton sk = build_skeleton(test::make_chain(3), "chain3").value();
    return sk;
}

TEST(RootMotionTrack, FollowsTheRootsTravelAndTurnOverTheGround) {
    // Float32 keys: the track is read from the keys as sampling returns them.
    const AnimationClip clip = build_clip(moving({0.5f, -0.25f}, {2.0f, 1.0f}, 0.5f * kPi, 0.3f), chain3(), ClipEncoding::Float32).value();
    const RootMotionTrack& track = clip.root_motion();
    ASSERT_TRUE(track.moves());
    EXPECT_NEAR(track.net_turn(), 0.5f * kPi, 1e-5f);  // the pitch is not a turn about the vertical
    EXPECT_NEAR(track.net_travel(), std::sqrt(5.0f), 1e-5f);
    EXPECT_NEAR(track.excursion(), std::sqrt(5.0f), 1e-5f);
    for (const float t : {0.0f, 0.25f, 0.5f, 1.0f}) {
        // F(t) takes the root's key-0 ground point to its point at t, and turns by the heading at t.
        const GroundMotion f = track.at(t);
        expect_near(f.apply(glm::vec3(0.5f, 0.9f, -0.25f)), glm::vec3(0.5f + 2.0f * t, 0.9f, -0.25f + 1.0f * t), kEps);
        EXPECT_NEAR(f.turn, 0.5f * kPi * t, 1e-5f);
    }
    // Clamped outside the clip; between() once is F(t0)^-1 F(t1).
    expect_near(track.at(3.0f).apply(glm::vec3(0.0f)), track.at(1.0f).apply(glm::vec3(0.0f)), 0.0f);
    const glm::vec3 p(0.2f, 0.0f, 0.7f);
    expect_near(track.between(0.25f, 0.75f, false).apply(p), track.at(0.25f).inverse().apply(track.at(0.75f).apply(p)), kEps);
}

TEST(RootMotionTrack, UnevenlySpacedKeysAreFoundAsEvenOnesAre) {
    // Keys bunched towards the end (times (k / 30)^2): the track finds each time's segment by search, not by a
    // multiply, and reads the same line (the root's travel is linear in time).
    RawAnimation a = moving({0.0f, 0.0f}, {2.0f, 0.0f}, 0.0f);
    for (auto* times : {&a.tracks[0].translations.times, &a.tracks[0].rotations.times})
        for (float& t : *times) t = t * t;
    for (size_t k = 0; k < a.tracks[0].translations.values.size(); ++k)
        a.tracks[0].translations.values[k].x = 2.0f * a.tracks[0].translations.times[k];
    const AnimationClip clip = build_clip(a, chain3(), ClipEncoding::Float32).value();
    const RootMotionTrack& track = clip.root_motion();
    ASSERT_TRUE(track.moves());
    for (const float t : {0.003f, 0.1f, 0.37f, 0.5f, 0.93f})
        EXPECT_NEAR(track.at(t).offset.x, 2.0f * t, kEps) << "t " << t;
}

TEST(RootMotionTrack, AHeadingUnwrapsPastAHalfTurn) {
    // Three quarters of a turn and more: the heading grows on (no jump back by a whole turn at a half turn).
    const AnimationClip clip = build_clip(moving({0.0f, 0.0f}, {0.0f, 0.0f}, 1.75f * kPi), chain3(), ClipEncoding::Float32).value();
    ASSERT_TRUE(clip.root_motion().moves());  // it turns in place
    EXPECT_NEAR(clip.root_motion().net_turn(), 1.75f * kPi, 1e-4f);
    float previous = 0.0f;
    for (int k = 1; k <= 100; ++k) {
        const float turn = clip.root_motion().at(static_cast<float>(k) / 100.0f).turn;
        EXPECT_GT(turn, previous);
        EXPECT_LT(turn - previous, 1.75f * kPi / 100.0f + 1e-4f);
        previous = turn;
    }
}

TEST(RootMotionTrack, ASwayOrASmallTurnStaysInThePose) {
    // 8 cm out and back (under kRootMotionMinTravel) and 20 degrees of turn (under kRootMotionMinTurn): no root motion.
    RawAnimation sway = moving({0.0f, 0.0f}, {0.0f, 0.0f}, 20.0f * kPi / 180.0f);
    for (size_t k = 0; k < sway.tracks[0].translations.values.size(); ++k)
        sway.tracks[0].translations.values[k].x = 0.08f * std::sin(kPi * sway.tracks[0].translations.times[k]);
    const AnimationClip clip = build_clip(sway, chain3()).value();
    EXPECT_FALSE(clip.root_motion().moves());
    EXPECT_NEAR(clip.root_motion().excursion(), 0.08f, 1e-3f);
    // A track that does not move gives the identity everywhere.
    EXPECT_EQ(clip.root_motion().at(0.5f).turn, 0.0f);
    EXPECT_EQ(clip.root_motion().between(0.1f, 7.3f, true).offset, glm::vec2(0.0f));
    // 12 cm of travel moves.
    EXPECT_TRUE(build_clip(moving({0.0f, 0.0f}, {0.12f, 0.0f}, 0.0f), chain3()).value().root_motion().moves());
}

TEST(RootMotionTrack, ARootBoneThatStaysPutHandsItToTheJointThatTravels) {
    // An Unreal-style root bone on the ground (joint 0, still) with the pelvis (joint 1) walking 2 m and turning a
    // quarter turn below it: the track follows joint 1 in model space; the in-place pose, made at joint 0, keeps
    // joint 1 over its first ground position facing its first way.
    const Skeleton& sk = chain3();
    RawAnimation a = moving({0.0f, 0.0f}, {0.0f, 2.0f}, 0.5f * kPi);
    std::swap(a.tracks[0], a.tracks[1]);
    const AnimationClip clip = build_clip(a, sk, ClipEncoding::Float32).value();
    const RootMotionTrack& track = clip.root_motion();
    ASSERT_TRUE(track.moves());
    EXPECT_EQ(track.joint(), 1);
    EXPECT_NEAR(track.net_travel(), 2.0f, 1e-5f);
    EXPECT_NEAR(track.net_turn(), 0.5f * kPi, 1e-5f);
    std::vector<glm::vec3> t(3), s(3);
    std::vector<glm::quat> r(3);
    sample_blocks(clip, 15, 0.0f, t.data(), r.data(), s.data());  // t = 0.5 s
    put_roots_in_place(track.at(0.5f).inverse(), sk.parents(), t, r);
    const glm::vec3 pelvis = t[0] + r[0] * t[1];
    EXPECT_NEAR(pelvis.x, 0.0f, kEps);
    EXPECT_NEAR(pelvis.z, 0.0f, kEps);
    const glm::vec3 facing = r[0] * r[1] * glm::vec3(0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(facing.x, 0.0f, kEps);
    EXPECT_NEAR(facing.z, 1.0f, kEps);
    // A clip where nothing travels: joint 0's track, not moving.
    RawAnimation still = moving({0.0f, 0.0f}, {0.0f, 0.0f}, 0.0f);
    EXPECT_FALSE(build_clip(still, sk).value().root_motion().moves());
    EXPECT_EQ(build_clip(still, sk).value().root_motion().joint(), 0);
}

TEST(RootMotionTrack, ALoopingClockCountsItsRepeats) {
    const AnimationClip clip = build_clip(moving({0.0f, 0.0f}, {1.0f, 0.0f}, 0.25f * kPi), chain3(), ClipEncoding::Float32).value();
    const RootMotionTrack& track = clip.root_motion();
    const glm::vec3 p(0.3f, 0.0f, -0.4f);
    // From 0.5 s to 2.5 s: the rest of the first repeat, a whole one, and half of the third.
    const GroundMotion expected = track.at(0.5f).inverse().after(track.at(1.0f).after(track.at(1.0f).after(track.at(0.5f))));
    expect_near(track.between(0.5f, 2.5f, true).apply(p), expected.apply(p), kEps);
    // Backwards (a clip played at a negative speed) undoes it; far into its repeats the clock loses nothing.
    expect_near(track.between(2.5f, 0.5f, true).apply(expected.apply(p)), p, kEps);
    expect_near(track.between(10000.5f, 10002.5f, true).apply(p), expected.apply(p), 1e-3f);
    // Once: clamped to the clip.
    expect_near(track.between(0.5f, 2.5f, false).apply(p), track.at(0.5f).inverse().after(track.at(1.0f)).apply(p), kEps);
}

}  // namespace
}  // namespace aloha
