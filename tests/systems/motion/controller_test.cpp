// Motion controller: request queue order and durations, cross-fade continuity, throttled updates,
// resting characters untouched, walking root motion along a path, poses nobody reads left out.
#include "systems/motion/controller.hpp"
#include "tests/systems/motion/motion_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace aloha {
namespace {

constexpr float kDt = 1.0f / 60.0f;

// A 4-joint chain with two clips: "swing" rotates every joint about X by 0.6*sin(2*pi*t) (1 s
// loop), "still" holds every joint at 0.8 rad about X.
struct Fixture {
    Skeleton sk = build_skeleton(test::make_chain(4), "chain4").value();
    ClipLibrary clips;
    ClipId swing = 0, still = 0;
    size_t count;
    std::vector<AnimLod> lods;
    std::vector<MotionState> states;
    std::vector<Transform> xs;
    std::vector<Velocity> vs;
    explicit Fixture(size_t n) : count(n), lods(n), states(n), xs(n), vs(n) {
        RawAnimation a;
        a.name = "swing";
        a.tracks.resize(4);
        for (auto& tr : a.tracks)
            for (int k = 0; k <= 60; ++k) {
                const float t = static_cast<float>(k) / 60.0f;
                tr.rotations.times.push_back(t);
                tr.rotations.values.push_back(glm::angleAxis(0.6f * std::sin(6.2831853f * t), glm::vec3(1, 0, 0)));
            }
        swing = clips.add(a, sk).value();
        RawAnimation b;
        b.name = "still";
        b.tracks.resize(4);
        for (auto& tr : b.tracks) {
            tr.rotations.times = {0.0f};
            tr.rotations.values = {glm::angleAxis(0.8f, glm::vec3(1, 0, 0))};
        }
        still = clips.add(b, sk).value();
    }
    size_t step(MotionController& mc) { return mc.update(kDt, lods, states, xs, vs); }
};

MotionRequest play(ClipId clip, float duration, float crossfade = 0.0f, bool loop = true) {
    MotionRequest r;
    r.kind = RequestKind::PlayClip;
    r.clip = clip;
    r.duration = duration;
    r.crossfade_s = crossfade;
    r.loop = loop ? 1 : 0;
    return r;
}

TEST(MotionController, QueueRunsInOrderForTheirDurations) {
    Fixture f(2);
    MotionController mc(f.sk, f.clips, 2);
    ASSERT_TRUE(mc.push_request(0, play(f.swing, 0.5f)));
    ASSERT_TRUE(mc.push_request(0, play(f.still, 0.25f)));
    ASSERT_TRUE(mc.push_request(0, play(f.swing, -1.0f, 0.0f, false)));  // once: ends after 1 s
    EXPECT_EQ(mc.queued(0), 3u);
    std::vector<std::pair<int, uint16_t>> switches;  // (frame, clip or 0xFFFF for rest) at each start
    int frame = 0;
    for (; frame < 200 && !mc.active().empty(); ++frame) {
        f.step(mc);
        const MotionRequest& cur = mc.current(0);
        if (f.states[0].request_time <= kDt * 1.001f)  // a request started this frame
            switches.emplace_back(frame, cur.kind == RequestKind::Rest ? uint16_t{0xFFFF} : cur.clip);
    }
    // Durations are counted in whole frames: 0.5 s = 30 frames, 0.25 s = 15, the once clip 60.
    ASSERT_EQ(switches.size(), 4u);
    EXPECT_EQ(switches[0], std::make_pair(0, f.swing));
    EXPECT_EQ(switches[1].second, f.still);
    EXPECT_NEAR(switches[1].first, 30, 1);  // float accumulation of 1/60 may end a frame late
    EXPECT_EQ(switches[2].second, f.swing);
    EXPECT_NEAR(switches[2].first - switches[1].first, 15, 1);
    EXPECT_EQ(switches[3].second, 0xFFFF);  // back to rest, then inactive
    EXPECT_NEAR(switches[3].first - switches[2].first, 60, 1);
    EXPECT_TRUE(mc.active().empty());
    EXPECT_EQ(f.states[0].at_rest, 1);
    // Character 1 never had a request: never touched.
    EXPECT_EQ(f.states[1].frames_since_update, 0);
    EXPECT_EQ(f.states[1].at_rest, 1);
}

// Largest per-joint rotation angle between two local poses.
float pose_distance(const ConstPoseView& a, const std::vector<glm::quat>& b) {
    float d = 0.0f;
    for (size_t j = 0; j < b.size(); ++j)
        d = std::max(d, 2.0f * std::acos(std::min(1.0f, std::abs(glm::dot(a.rotations[j], b[j])))));
    return d;
}

TEST(MotionController, CrossFadeHasNoJumpAtTheSwitch) {
    Fixture f(1);
    MotionController mc(f.sk, f.clips, 1);
    const float fade = 0.25f;
    ASSERT_TRUE(mc.push_request(0, play(f.swing, 0.4f)));
    ASSERT_TRUE(mc.push_request(0, play(f.still, -1.0f, fade)));
    std::vector<glm::quat> prev(4);
    f.step(mc);
    auto copy = [&] {
        const ConstPoseView v = mc.poses().view(0);
        std::copy(v.rotations.begin(), v.rotations.end(), prev.begin());
    };
    copy();
    // Bound per frame: the swing clip moves at most 0.6 * 2*pi rad/s * dt = 0.063 rad; the fade moves
    // the blend by dt/fade of the gap between the poses (at most 0.6 + 0.8 = 1.4 rad): 0.093 rad.
    // Without a fade the switch would jump by up to 1.4 rad.
    const float bound = 0.6f * 6.2831853f * kDt + 1.4f * kDt / fade + 1e-3f;
    float worst = 0.0f;
    bool faded = false;
    for (int frame = 1; frame < 60; ++frame) {
        f.step(mc);
        faded = faded || mc.fading(0);
        const float d = pose_distance(mc.poses().view(0), prev);
        worst = std::max(worst, d);
        copy();
    }
    EXPECT_TRUE(faded);
    EXPECT_LE(worst, bound);
    // After the fade the pose is the still clip's.
    EXPECT_NEAR(glm::angle(mc.poses().view(0).rotations[2]), 0.8f, 1e-4f);
}

TEST(MotionController, UpdateIntervalPosesEveryNFramesWhileTimeAdvances) {
    Fixture f(1);
    f.lods[0].update_interval = 3;
    MotionController mc(f.sk, f.clips, 1);
    ASSERT_TRUE(mc.push_request(0, play(f.swing, -1.0f)));
    std::vector<int> posed_frames;
    float last_time = -1.0f;
    for (int frame = 0; frame < 12; ++frame) {
        if (f.step(mc) == 1) posed_frames.push_back(frame);
        EXPECT_GT(f.states[0].time, last_time);  // time advances every frame
        last_time = f.states[0].time;
    }
    EXPECT_EQ(posed_frames, (std::vector<int>{0, 3, 6, 9}));
    EXPECT_NEAR(f.states[0].time, 12 * kDt, 1e-5f);
    // The pose shown is the clip at the time of the last update (frame 9: t = 10 dt).
    const float t = 10.0f * kDt;
    EXPECT_NEAR(glm::angle(mc.poses().view(0).rotations[1]), std::abs(0.6f * std::sin(6.2831853f * t)), 2e-3f);
}

bool same_model(const ConstPoseView& a, const ConstPoseView& b) { return std::equal(a.model.begin(), a.model.end(), b.model.begin()); }

// PoseUse: an unseen clip pose is left stale while its clock runs and posed exactly when seen again; a pose
// read at updates only is not interpolated (nor keyed) between them and is posed at once when read every frame
// again; from the next scheduled update on everything is as if every pose had been read every frame (`ref`).
TEST(MotionController, PosesNobodyReadsAreLeftOutAndCurrentWhenSeen) {
    Fixture f(2), g(2);
    for (Fixture* x : {&f, &g}) x->lods[0].update_interval = x->lods[1].update_interval = 4;
    MotionController mc(f.sk, f.clips, 2), ref(g.sk, g.clips, 2);
    for (uint32_t c = 0; c < 2; ++c) {
        ASSERT_TRUE(mc.push_request(c, play(f.swing, -1.0f)));
        ASSERT_TRUE(ref.push_request(c, play(g.swing, -1.0f)));
    }
    std::vector<uint8_t> use(2, static_cast<uint8_t>(PoseUse::EveryFrame));
    mc.set_pose_use(use);
    std::vector<glm::mat4> held, last_update;
    for (int frame = 0; frame < 26; ++frame) {
        use[0] = static_cast<uint8_t>(frame == 0 || frame >= 18 ? PoseUse::EveryFrame : frame < 10 ? PoseUse::Unseen : PoseUse::AtUpdates);
        f.step(mc);
        g.step(ref);
        ASSERT_EQ(f.states[0].time, g.states[0].time) << frame;  // the clock runs, seen or not
        EXPECT_TRUE(same_model(mc.poses().view(1), ref.poses().view(1))) << frame;
        const ConstPoseView pose = mc.poses().view(0);
        if (frame == 0) held.assign(pose.model.begin(), pose.model.end());
        if (frame > 0 && frame < 10) {
            EXPECT_TRUE(std::equal(held.begin(), held.end(), pose.model.begin())) << frame;  // left out
            EXPECT_EQ(mc.stale(0), frame >= 4) << frame;  // stale from its first update left out (frame 4)
        }
        if (frame == 10 || frame == 18) {  // seen again / read every frame again: posed at once, at the clock's time
            EXPECT_FALSE(mc.stale(0));
            EXPECT_EQ(f.states[0].frames_since_update, 0);
            EXPECT_NEAR(glm::angle(pose.rotations[1]), std::abs(0.6f * std::sin(6.2831853f * f.states[0].time)), 2e-3f);
        }
        if (frame >= 10 && frame < 18) {
            if (f.states[0].frames_since_update == 0) last_update.assign(pose.model.begin(), pose.model.end());
            EXPECT_TRUE(std::equal(last_update.begin(), last_update.end(), pose.model.begin())) << frame;  // not interpolated
        }
        if ((frame >= 12 && frame < 18) || frame >= 20) {  // back on the schedule
            EXPECT_EQ(f.states[0].frames_since_update, g.states[0].frames_since_update) << frame;
        }
        if (frame >= 20) {
            EXPECT_TRUE(same_model(pose, ref.poses().view(0))) << frame;  // keyed and interpolated as ever
        }
    }
    std::vector<uint8_t> bad(2, 7);
    MotionUpdateJob job{&mc, kDt, f.lods, f.states, f.xs, f.vs};
    job.pose_use = bad;
    EXPECT_FALSE(job.Validate());
}

TEST(MotionController, RestingCharactersAreNotIterated) {
    Fixture f(1000);
    MotionController mc(f.sk, f.clips, 1000);
    for (auto& s : f.states) s.frames_since_update = 77;  // sentinel
    f.xs[500].position = glm::vec3(1, 2, 3);
    ASSERT_TRUE(mc.push_request(7, play(f.swing, -1.0f)));
    for (int i = 0; i < 10; ++i) EXPECT_EQ(f.step(mc), 1u);
    EXPECT_EQ(mc.active().size(), 1u);
    for (size_t c = 0; c < 1000; ++c) {
        if (c == 7) continue;
        EXPECT_EQ(f.states[c].frames_since_update, 77);
    }
    EXPECT_EQ(f.xs[500].position, glm::vec3(1, 2, 3));
    EXPECT_EQ(mc.poses().view(3).rotations[1], f.sk.rest_rotations()[1]);
    // Rest request: character 7 drops out of the active list.
    MotionRequest rest;
    ASSERT_TRUE(mc.push_request(7, rest));
    f.step(mc);
    EXPECT_TRUE(mc.active().empty());
    EXPECT_EQ(f.states[7].at_rest, 1);
}

// set_stance: characters not posed yet hold the clip's first pose (every joint of "still" at 0.8 rad, the root at
// its rest translation), through a look-at without IK (which holds the pose) and with no request at all; a
// character posed already keeps its pose. Exact: the stance is sampled at a key and copied.
TEST(MotionController, CharactersHoldTheStanceUntilPosed) {
    Fixture f(3);
    MotionController mc(f.sk, f.clips, 3);
    ASSERT_TRUE(mc.push_request(0, play(f.swing, -1.0f)));
    f.step(mc);  // character 0 is posed; 1 and 2 are not
    const std::vector<glm::quat> posed(mc.poses().view(0).rotations.begin(), mc.poses().view(0).rotations.end());
    const AnimationClip& still = *f.clips.find(f.still);
    mc.set_stance(still);
    MotionRequest look;
    look.kind = RequestKind::LookAt;  // no IK registered: holds the pose it finds
    look.target = glm::vec3(0, 1, 5);
    ASSERT_TRUE(mc.push_request(1, look));
    for (int frame = 0; frame < 5; ++frame) f.step(mc);
    glm::vec3 t[4], sc[4];
    glm::quat r[4];
    sample_blocks(still, 0, 0.0f, t, r, sc);
    for (uint32_t c : {1u, 2u}) {
        const ConstPoseView pose = mc.poses().view(c);
        EXPECT_EQ(pose.translations[0], f.sk.rest_translations()[0]) << c;
        for (size_t j = 0; j < 4; ++j) EXPECT_EQ(pose.rotations[j], r[j]) << c << " joint " << j;
        EXPECT_NEAR(glm::angle(pose.rotations[2]), 0.8f, 1e-4f) << "the stance, not the rest pose";
    }
    f.step(mc);
    EXPECT_NE(mc.poses().view(0).rotations[1], r[1]) << "a posed character keeps being posed by its request";
    EXPECT_NEAR(glm::angle(posed[1]), std::abs(0.6f * std::sin(6.2831853f * kDt)), 2e-3f);
}

TEST(MotionController, WalkFollowsPathWithRootMotion) {
    Fixture f(1);
    MotionController mc(f.sk, f.clips, 1);
    const uint16_t path = mc.add_path({glm::vec3(0, 0, 2), glm::vec3(2, 0, 2)});
    MotionRequest walk;
    walk.kind = RequestKind::Walk;
    walk.speed = 1.5f;
    walk.path = path;
    ASSERT_TRUE(mc.push_request(0, walk));
    f.step(mc);
    EXPECT_NEAR(f.xs[0].position.z, 1.5f * kDt, 1e-6f);
    EXPECT_NEAR(glm::length(f.vs[0].linear), 1.5f, 1e-5f);
    int frames = 1;
    uint32_t cursor = 0;
    while (!mc.active().empty() && frames < 1000) {
        f.step(mc);
        ++frames;
        if (f.states[0].active == RequestKind::Walk) cursor = std::max(cursor, f.states[0].path_cursor);
    }
    // 4 m of path at 1.5 m/s = 2.67 s = 160 frames (+1 frame to notice the end).
    EXPECT_NEAR(frames, 161, 2);
    EXPECT_NEAR(f.xs[0].position.x, 2.0f, 0.03f);  // within one frame of travel (0.025 m)
    EXPECT_NEAR(f.xs[0].position.z, 2.0f, 0.03f);
    EXPECT_EQ(f.vs[0].linear, glm::vec3(0.0f));
    EXPECT_EQ(cursor, 2u);  // both waypoints passed
}

// A looping path: after the last waypoint the walker heads for the first again and walks until its
// request's duration; a loop whose waypoints are all on one spot ends the walk instead of spinning.
TEST(MotionController, WalkOnALoopPathGoesRoundUntilItsDuration) {
    Fixture f(2);
    MotionController mc(f.sk, f.clips, 2);
    // A 2 m square from the start (the origin): 8 m a lap, 5.33 s at 1.5 m/s.
    const uint16_t square = mc.add_path({glm::vec3(0, 0, 2), glm::vec3(2, 0, 2), glm::vec3(2, 0, 0), glm::vec3(0, 0, 0)}, true);
    const uint16_t spot = mc.add_path({glm::vec3(0, 0, 0), glm::vec3(0, 0, 0)}, true);
    MotionRequest walk;
    walk.kind = RequestKind::Walk;
    walk.speed = 1.5f;
    walk.path = square;
    walk.duration = 8.0f;  // a lap and a half
    ASSERT_TRUE(mc.push_request(0, walk));
    walk.path = spot;
    walk.duration = -1.0f;
    f.xs[1].position = glm::vec3(0.0f);
    ASSERT_TRUE(mc.push_request(1, walk));
    int frames = 0;
    bool wrapped = false;
    uint32_t last = 0;
    float farthest = 0.0f;
    while (frames < 2000) {
        f.step(mc);
        ++frames;
        if (f.states[0].active != RequestKind::Walk) break;
        wrapped |= f.states[0].path_cursor < last;
        last = f.states[0].path_cursor;
        // On the square's edges: never farther from its centre than a corner (+ one frame of travel).
        farthest = std::max(farthest, glm::length(glm::vec2(f.xs[0].position.x - 1.0f, f.xs[0].position.z - 1.0f)));
    }
    EXPECT_TRUE(wrapped);                  // went round past the last waypoint
    EXPECT_NEAR(frames, 8.0f / kDt, 2.0f);  // ended by its duration, not by the path
    EXPECT_LE(farthest, std::sqrt(2.0f) + 1.5f * kDt + 1e-4f);
    // 12 m walked: a lap (8 m) and half of the next (4 m), so at the square's opposite corner (2, 0, 2)
    // within a frame of travel.
    EXPECT_NEAR(f.xs[0].position.x, 2.0f, 0.03f);
    EXPECT_NEAR(f.xs[0].position.z, 2.0f, 0.03f);
    EXPECT_NE(f.states[1].active, RequestKind::Walk);  // the one-spot loop ended at once
    EXPECT_EQ(f.xs[1].position, glm::vec3(0.0f));
}

// A walker turns towards its direction at 6 rad/s and, once facing it, keeps its rotation bit for bit
// (the controller then skips the turn); a rotation set from outside is turned from again.
TEST(MotionController, WalkerTurnsToItsDirectionAndFromARotationSetOutside) {
    Fixture f(1);
    MotionController mc(f.sk, f.clips, 1);
    MotionRequest walk;
    walk.kind = RequestKind::Walk;
    walk.speed = 1.0f;
    walk.target = glm::vec3(1, 0, 0);  // facing +x is a yaw of pi/2 from +z
    ASSERT_TRUE(mc.push_request(0, walk));
    auto yaw = [&] {
        const glm::vec3 fwd = f.xs[0].rotation * glm::vec3(0, 0, 1);
        return std::atan2(fwd.x, fwd.z);
    };
    const float step = 6.0f * kDt;  // the most one frame turns (rad)
    f.step(mc);
    EXPECT_NEAR(yaw(), step, 1e-4f);
    for (int i = 0; i < 30; ++i) f.step(mc);  // pi/2 takes 16 frames at 0.1 rad per frame
    EXPECT_NEAR(yaw(), 1.5707963f, 1e-5f);
    const glm::quat faced = f.xs[0].rotation;
    f.step(mc);
    f.step(mc);
    EXPECT_EQ(f.xs[0].rotation, faced);
    f.xs[0].rotation = glm::quat(1, 0, 0, 0);  // turned back to +z from outside
    f.step(mc);
    EXPECT_NEAR(yaw(), step, 1e-4f);
}

TEST(MotionController, JobValidates) {
    Fixture f(2);
    MotionController mc(f.sk, f.clips, 3);
    MotionUpdateJob job{&mc, kDt, f.lods, f.states, f.xs, f.vs};
    std::vector<std::string> errors;
    EXPECT_FALSE(job.Validate(&errors));
    EXPECT_EQ(errors.size(), 4u);
    MotionController ok(f.sk, f.clips, 2);
    job.controller = &ok;
    EXPECT_TRUE(job.Validate());
    EXPECT_EQ(job.Run(), 0u);
}

}  // namespace
}  // namespace aloha
