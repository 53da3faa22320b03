// Clip building and sampling: exact at keys (Float32 clips) or within the clip's derived error bound
// (the default 16-bit quantised clips, clip_quant.hpp), lerp/nlerp between keys, looping, cursor reuse.
#include "systems/motion/clip.hpp"
#include "systems/motion/sampling.hpp"
#include "tests/systems/motion/clip_reference.hpp"
#include "tests/systems/motion/motion_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace aloha {
namespace {

Skeleton chain(int n) { return build_skeleton(test::make_chain(n), "chain").value(); }

// Two-joint clip; joint 0 has keys at non-uniform times, joint 1 has no track (rest pose).
RawAnimation nonuniform_clip() {
    RawAnimation a;
    a.name = "nonuniform";
    a.tracks.resize(1);
    auto& tr = a.tracks[0];
    tr.translations.times = {0.0f, 0.1f, 0.35f, 0.4f, 1.0f};
    tr.translations.values = {glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(1, 2, 0), glm::vec3(0, 2, 3), glm::vec3(-1, 0, 0)};
    tr.rotations.times = {0.0f, 0.5f, 1.0f};
    tr.rotations.values = {glm::angleAxis(0.0f, glm::vec3(0, 1, 0)), glm::angleAxis(1.0f, glm::vec3(0, 1, 0)),
                           -glm::angleAxis(2.0f, glm::vec3(0, 1, 0))};  // opposite sign: hemisphere fix needed
    a.duration = 1.0f;
    return a;
}

struct Pose {
    explicit Pose(int n) : t(static_cast<size_t>(n)), r(static_cast<size_t>(n)), s(static_cast<size_t>(n)) {}
    std::vector<glm::vec3> t;
    std::vector<glm::quat> r;
    std::vector<glm::vec3> s;
};

void sample(const AnimationClip& clip, float time, Pose& p, SamplingCache* cache = nullptr, bool loop = true) {
    SampleJob job{&clip, time, loop, cache, p.t, p.r, p.s};
    std::vector<std::string> errors;
    ASSERT_TRUE(job.Validate(&errors));
    job.Run();
}

TEST(Sampling, UniformKeysAreExactAtKeyTimes) {
    const Skeleton sk = chain(3);
    // Spacing 1/32 s is a power of two, so key times are exact floats and t / spacing is an exact
    // integer: sampling a Float32 clip must return the key bits unchanged for T and S (a*1 + b*0).
    RawAnimation raw = test::make_wave_clip(sk, 33, 1.0f);
    const AnimationClip clip = build_clip(raw, sk, ClipEncoding::Float32).value();
    ASSERT_TRUE(clip.uniform());
    EXPECT_EQ(clip.key_count(), 33);
    Pose p(3);
    for (int k = 0; k < 33; ++k) {
        sample(clip, static_cast<float>(k) / 32.0f, p, nullptr, false);
        for (int j = 0; j < 3; ++j) {
            const auto& tr = raw.tracks[static_cast<size_t>(j)];
            EXPECT_EQ(p.t[static_cast<size_t>(j)], tr.translations.values[static_cast<size_t>(k)]);
            EXPECT_EQ(p.s[static_cast<size_t>(j)], tr.scales.values[static_cast<size_t>(k)]);
            // Rotation keys are renormalised once at build and once at sampling: 2 roundings of ~6e-8.
            const glm::quat q = glm::normalize(tr.rotations.values[static_cast<size_t>(k)]);
            EXPECT_NEAR(std::abs(glm::dot(p.r[static_cast<size_t>(j)], q)), 1.0f, 1e-6f);
            for (int c = 0; c < 4; ++c) EXPECT_NEAR(p.r[static_cast<size_t>(j)][c], q[c], 1e-6f);
        }
    }
}

TEST(Sampling, UniformKeysAreWithinTheBoundAtKeyTimes) {
    const Skeleton sk = chain(3);
    // The same keys from the default (quantised) clip: each component within the clip's bound of
    // the source key, each rotation within its angle bound (clip_quant.hpp derives both).
    RawAnimation raw = test::make_wave_clip(sk, 33, 1.0f);
    const AnimationClip clip = build_clip(raw, sk).value();
    ASSERT_EQ(clip.encoding(), ClipEncoding::Quantized16);
    const ClipErrorBound& b = clip.error_bound();
    Pose p(3);
    for (int k = 0; k < 33; ++k) {
        sample(clip, static_cast<float>(k) / 32.0f, p, nullptr, false);
        for (size_t j = 0; j < 3; ++j) {
            const auto& tr = raw.tracks[j];
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(p.t[j][c], tr.translations.values[static_cast<size_t>(k)][c], b.translation);
                EXPECT_NEAR(p.s[j][c], tr.scales.values[static_cast<size_t>(k)][c], b.scale);
            }
            const glm::dquat q = glm::normalize(glm::dquat(glm::normalize(tr.rotations.values[static_cast<size_t>(k)])));
            EXPECT_LE(test::rotation_angle(p.r[j], q), b.rotation);
        }
    }
}

TEST(Sampling, BetweenKeysIsLerpAndNlerpWithinTheBound) {
    // The default clip between keys: the source's lerp / nlerp (in double, at the segment point
    // sampling used) within the clip's bound; joints without a track are copied exactly.
    const Skeleton sk = chain(2);
    const RawAnimation raw = nonuniform_clip();
    const AnimationClip clip = build_clip(raw, sk).value();
    const ClipErrorBound& b = clip.error_bound();
    EXPECT_FALSE(clip.uniform());
    EXPECT_EQ(clip.key_count(), 6);
    Pose p(2);
    for (float t : {0.2f, 0.75f}) {
        sample(clip, t, p);
        int k = 0;
        float alpha = 0.0f;
        find_key(clip, t, nullptr, &k, &alpha);
        const double ts = test::segment_time(clip, k, alpha);
        const glm::dvec3 et = test::ref_vec(raw.tracks[0].translations, ts, glm::vec3(0));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(p.t[0][c], et[c], b.translation);
        EXPECT_LE(test::rotation_angle(p.r[0], test::ref_rot(raw.tracks[0].rotations, ts, glm::quat(1, 0, 0, 0))),
                  b.rotation);
        EXPECT_EQ(p.t[1], sk.rest_translations()[1]);
        EXPECT_EQ(p.r[1], sk.rest_rotations()[1]);
    }
    // nlerp midpoint of 1 and 2 rad about Y is 1.5 rad up to 1e-3 (nlerp is not slerp), plus the bound.
    EXPECT_NEAR(glm::angle(p.r[0]), 1.5f, 1e-3f + b.rotation);
}

TEST(Sampling, BetweenKeysIsLerpAndNlerp) {
    const Skeleton sk = chain(2);
    const RawAnimation raw = nonuniform_clip();
    const AnimationClip clip = build_clip(raw, sk, ClipEncoding::Float32).value();
    EXPECT_FALSE(clip.uniform());
    // Union of key times: 0, .1, .35, .4, .5, 1.
    EXPECT_EQ(clip.key_count(), 6);
    Pose p(2);
    const float t = 0.2f;  // between translation keys .1 and .35, rotation keys 0 and .5
    sample(clip, t, p);
    const float a = (t - 0.1f) / 0.25f;
    const glm::vec3 expect_t = glm::vec3(1, 0, 0) * (1 - a) + glm::vec3(1, 2, 0) * a;
    // Values are O(1), so float lerp error is a few ulps (~1e-7); 1e-6 leaves margin.
    EXPECT_NEAR(p.t[0].x, expect_t.x, 1e-6f);
    EXPECT_NEAR(p.t[0].y, expect_t.y, 1e-6f);
    const float b = t / 0.5f;
    const glm::quat q0 = raw.tracks[0].rotations.values[0], q1 = raw.tracks[0].rotations.values[1];
    const glm::quat expect_q = glm::normalize(glm::quat(q0.w * (1 - b) + q1.w * b, q0.x * (1 - b) + q1.x * b,
                                                        q0.y * (1 - b) + q1.y * b, q0.z * (1 - b) + q1.z * b));
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(p.r[0][c], expect_q[c], 1e-6f);
    // Rotation between .5 and 1: the last key has the opposite sign, the hemisphere fix negates it.
    sample(clip, 0.75f, p);
    const glm::quat q2 = -raw.tracks[0].rotations.values[2];
    const glm::quat e2 = glm::normalize(glm::quat(0.5f * (q1.w + q2.w), 0.5f * (q1.x + q2.x), 0.5f * (q1.y + q2.y), 0.5f * (q1.z + q2.z)));
    EXPECT_NEAR(std::abs(glm::dot(p.r[0], e2)), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::angle(p.r[0]), 1.5f, 1e-3f);  // nlerp midpoint of 1 and 2 rad about Y is 1.5 rad
    // Joint 1 has no track: rest pose.
    EXPECT_EQ(p.t[1], sk.rest_translations()[1]);
    EXPECT_EQ(p.r[1], sk.rest_rotations()[1]);
}

TEST(Sampling, LoopingWrapsAndOnceClamps) {
    const Skeleton sk = chain(2);
    const AnimationClip clip = build_clip(nonuniform_clip(), sk).value();
    Pose a(2), b(2);
    sample(clip, 0.2f, a);
    sample(clip, 3.2f, b);  // three periods later
    // 3.2 mod 1 = 0.2 up to float rounding of fmod (exact) and of 3.2f (~1e-7 s); slope there is
    // 8 units/s (+ 2 bounds per 0.25 s segment once quantised): ~1e-6 apart.
    EXPECT_NEAR(glm::length(a.t[0] - b.t[0]), 0.0f, 1e-5f);
    sample(clip, -0.8f, b);
    EXPECT_NEAR(glm::length(a.t[0] - b.t[0]), 0.0f, 1e-5f);
    sample(clip, 5.0f, b, nullptr, false);  // clamped to the last key, within the clip's bound
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(b.t[0][c], glm::vec3(-1, 0, 0)[c], clip.error_bound().translation);
    EXPECT_FLOAT_EQ(wrap_clip_time(2.5f, 1.0f, true), 0.5f);
    EXPECT_FLOAT_EQ(wrap_clip_time(-0.25f, 1.0f, true), 0.75f);
    EXPECT_FLOAT_EQ(wrap_clip_time(2.5f, 1.0f, false), 1.0f);
}

TEST(Sampling, CursorNeverRestartsOnForwardPlayback) {
    const Skeleton sk = chain(2);
    const AnimationClip clip = build_clip(nonuniform_clip(), sk).value();
    SamplingCache cache;
    Pose p(2), ref(2);
    for (int f = 0; f < 60; ++f) {  // 1 s at 60 Hz, forward, no wrap
        const float t = static_cast<float>(f) / 60.0f;
        sample(clip, t, p, &cache, false);
        sample(clip, t, ref, nullptr, false);  // binary search reference
        EXPECT_EQ(p.t[0], ref.t[0]);
    }
    EXPECT_EQ(cache.restarts, 0u);
    EXPECT_EQ(cache.steps, 4u);  // five segments passed in order: 4 forward steps
    // Going backwards (a loop wrap) restarts once.
    sample(clip, 0.05f, p, &cache, false);
    EXPECT_EQ(cache.restarts, 1u);
}

TEST(Sampling, BuildRejectsBadTracks) {
    const Skeleton sk = chain(2);
    RawAnimation raw = nonuniform_clip();
    raw.tracks[0].translations.times[2] = 0.05f;  // not increasing
    auto r = build_clip(raw, sk);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().to_string().find("nonuniform"), std::string::npos);
    EXPECT_NE(r.error().to_string().find("joint 0 'j0' translation key 2"), std::string::npos);
    raw = nonuniform_clip();
    raw.tracks[0].rotations.values[1] = glm::quat(0, 0, 0, 0);
    r = build_clip(raw, sk);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("zero"), std::string::npos);
    raw = nonuniform_clip();
    raw.tracks.resize(3);
    EXPECT_FALSE(build_clip(raw, sk).ok());
    raw = nonuniform_clip();
    raw.tracks[0].scales.times = {0.0f};
    EXPECT_FALSE(build_clip(raw, sk).ok());  // one time, no value
}

TEST(Sampling, JobValidateListsEveryFailure) {
    const Skeleton sk = chain(3);
    const AnimationClip clip = build_clip(test::make_wave_clip(sk, 5, 1.0f), sk).value();
    std::vector<glm::vec3> t(2), s(1);
    std::vector<glm::quat> r(3);
    SampleJob job{&clip, 0.0f, true, nullptr, t, r, s};
    std::vector<std::string> errors;
    EXPECT_FALSE(job.Validate(&errors));
    EXPECT_EQ(errors.size(), 2u);
    job.clip = nullptr;
    EXPECT_FALSE(job.Validate());
}

TEST(ClipLibrary, OwnsClipsById) {
    const Skeleton sk = chain(2);
    ClipLibrary lib;
    const auto a = lib.add(nonuniform_clip(), sk);
    ASSERT_TRUE(a.ok());
    const AnimationClip* first = lib.find(a.value());
    for (int i = 0; i < 20; ++i) (void)lib.add(test::make_wave_clip(sk, 3, 1.0f), sk);
    EXPECT_EQ(lib.find(a.value()), first);  // addresses are stable as clips are added
    EXPECT_EQ(lib.find("nonuniform"), 0);
    EXPECT_EQ(lib.find(std::string("missing")), -1);
    EXPECT_EQ(lib.find(ClipId{500}), nullptr);
    // No looped version: a looping play samples the clip itself.
    EXPECT_FALSE(lib.has_looped(a.value()));
    EXPECT_EQ(lib.find_looped(a.value()), first);
    EXPECT_EQ(lib.find_looped(ClipId{500}), nullptr);
}

// A one-joint-turning clip over 1 s: joint 1 turns about X from 0 to `end_angle`; the root travels `travel` over
// the ground, turns `heading` about the vertical and rises `rise`.
RawAnimation ends_clip(float end_angle, glm::vec3 travel = glm::vec3(0.0f), float heading = 0.0f) {
    RawAnimation a;
    a.name = "ends";
    a.duration = 1.0f;
    a.tracks.resize(2);
    for (int k = 0; k <= 10; ++k) {
        const float t = 0.1f * static_cast<float>(k);
        a.tracks[1].rotations.times.push_back(t);
        a.tracks[1].rotations.values.push_back(glm::angleAxis(end_angle * std::sin(1.5707963f * t), glm::vec3(1, 0, 0)));
        a.tracks[0].translations.times.push_back(t);
        a.tracks[0].translations.values.push_back(travel * t);
        a.tracks[0].rotations.times.push_back(t);
        a.tracks[0].rotations.values.push_back(glm::angleAxis(heading * t, glm::vec3(0, 1, 0)) * glm::angleAxis(0.3f, glm::vec3(1, 0, 0)));
    }
    return a;
}

TEST(AnimationClip, EndsMeetWhenTheLastPoseIsTheFirstTravelAside) {
    const Skeleton sk = chain(3);
    auto meet = [&](const RawAnimation& raw) { return build_clip(raw, sk).value().ends_meet(); };
    EXPECT_TRUE(meet(test::make_wave_clip(sk, 3, 1.0f))) << "a cycle";
    EXPECT_FALSE(meet(ends_clip(0.5f))) << "joint 1 ends half a radian from where it started";
    // The threshold: 1e-3 rad. sin(pi/2 * 1) = 1, so the end angle is the jump.
    EXPECT_TRUE(meet(ends_clip(0.0f)));
    EXPECT_TRUE(meet(ends_clip(0.5f * kEndsMeetAngle)));
    EXPECT_FALSE(meet(ends_clip(2.0f * kEndsMeetAngle)));
    // The root's travel over the ground and its turn about the vertical are no jump of a clip played in place ...
    EXPECT_TRUE(meet(ends_clip(0.0f, glm::vec3(1.2f, 0.0f, -0.4f), 1.0f)));
    // ... its rise is.
    EXPECT_FALSE(meet(ends_clip(0.0f, glm::vec3(0.0f, 0.1f, 0.0f))));
    // A single key: nothing to repeat.
    RawAnimation held = ends_clip(0.5f);
    for (RawJointTracks& t : held.tracks) {
        t.rotations.times.resize(1), t.rotations.values.resize(1);
        t.translations.times.resize(1), t.translations.values.resize(1);
    }
    held.duration = 0.0f;
    EXPECT_TRUE(meet(held));
}

TEST(AnimationClip, TakingTheTurnAboutTheVerticalOutLeavesTheSwing) {
    const glm::quat swing = glm::angleAxis(0.4f, glm::normalize(glm::vec3(1, 0, 0.5f)));
    const glm::quat q = swing * glm::angleAxis(1.1f, glm::vec3(0, 1, 0));
    const glm::quat got = without_turn_about_vertical(q);
    EXPECT_NEAR(std::abs(glm::dot(got, swing)), 1.0f, 1e-6f);  // the swing has no Y part: recovered exactly
    EXPECT_NEAR(std::abs(glm::dot(without_turn_about_vertical(glm::angleAxis(2.0f, glm::vec3(0, 1, 0))), glm::quat(1, 0, 0, 0))), 1.0f, 1e-6f);
}

TEST(ClipLibrary, ALoopedVersionIsWhatALoopingPlaySamples) {
    const Skeleton sk = chain(3);
    ClipLibrary lib;
    const ClipId id = lib.add(ends_clip(0.5f), sk).value();
    const size_t bytes = lib.byte_size();
    RawAnimation closed = ends_clip(0.5f);
    closed.name = "ends (looped)";
    for (glm::quat& q : closed.tracks[1].rotations.values) q = glm::angleAxis(0.1f, glm::vec3(1, 0, 0));
    lib.set_looped(id, build_clip(closed, sk).value());
    EXPECT_TRUE(lib.has_looped(id));
    EXPECT_EQ(lib.find(id)->name(), "ends");
    EXPECT_EQ(lib.find_looped(id)->name(), "ends (looped)");
    EXPECT_EQ(lib.find("ends"), 0);
    EXPECT_EQ(lib.size(), 1u) << "a looped version is no clip of its own";
    EXPECT_GT(lib.byte_size(), bytes);
}

}  // namespace
}  // namespace aloha
