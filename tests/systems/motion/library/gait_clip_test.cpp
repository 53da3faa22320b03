// The generated gait: stance feet planted (contact points still while on the ground), loop seam no
// larger than an ordinary frame, stride and cadence from the published relations.
#include "systems/motion/clip.hpp"
#include "systems/motion/library/gait_clip.hpp"
#include "systems/motion/library/posing.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/sampling.hpp"
#include "tests/common/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <vector>

namespace aloha {
namespace {

struct Sampled {
    std::vector<glm::mat4> model;
};

// Model matrices of `clip` at time t of an unbounded playback: the clip's own root travel for the
// cycles already played is added, so the result is the motion in the clip's ground frame.
std::vector<glm::mat4> pose_at(const AnimationClip& clip, const Skeleton& sk, float t, bool in_place) {
    const size_t n = static_cast<size_t>(sk.joint_count());
    std::vector<glm::vec3> tr(n), sc(n);
    std::vector<glm::quat> ro(n);
    const float cycles = std::floor(t / clip.duration());
    const float local = t - cycles * clip.duration();
    int k = 0;
    float a = 0.0f;
    find_key(clip, local, nullptr, &k, &a);
    sample_blocks(clip, k, a, tr.data(), ro.data(), sc.data());
    const glm::vec3 travel = clip.root_end() - clip.root_start();
    if (in_place) tr[0].z -= travel.z * local / clip.duration();
    else tr[0].z += travel.z * cycles;
    std::vector<glm::mat4> model(n);
    local_to_model(sk.parents().data(), tr.data(), ro.data(), sc.data(), nullptr, model.data(), n);
    return model;
}

class GaitClipTest : public ::testing::TestWithParam<float> {
protected:
    Skeleton sk = test::humanoid_skeleton_for();
    WalkRig rig = test::humanoid_rig(sk);
    HumanoidJoints joints = find_humanoid_joints(sk);
};

// Foot skate: a contact point (heel, or the ground under the ball joint) supports the foot while it
// is within 5 mm of the ground and within 1 mm of the foot's lower point: when the foot rolls over
// its heel or its ball the other end rises along an arc (rolling, not sliding) and stops counting
// as soon as it is 1 mm higher than the pivot. Each contact's travel is the largest horizontal
// distance the point gets from where it touched down (so sub-millimetre wobble of sampling between
// 60 Hz keys is not summed as a path); the sum over contacts per metre walked must be <= 2 mm, the
// issue's bound. Sampled at 240 Hz, between keys, as playback does at any rate.
TEST_P(GaitClipTest, StanceFeetStayPlanted) {
    const float speed = GetParam();
    GaitClip g = make_gait_clip(sk, rig, joints, speed, "gait");
    auto clip = build_clip(g.clip, sk);
    ASSERT_TRUE(clip.ok()) << clip.error().to_string();
    EXPECT_NEAR(clip.value().root_speed(), speed, 1e-3f * speed);
    const float dt = 1.0f / 240.0f;
    const int frames = static_cast<int>(3.0f * g.cycle.period / dt);
    PoseBuilder rest(sk);
    float skate = 0.0f;
    int contacts = 0;
    glm::vec3 start[4];
    float excursion[4] = {0, 0, 0, 0};
    bool down[4] = {false, false, false, false};
    for (int f = 0; f <= frames; ++f) {
        const auto model = pose_at(clip.value(), sk, static_cast<float>(f) * dt, false);
        for (int side = 0; side < 2; ++side) {
            const FootContacts c = foot_contacts(rig, rest, side);
            const glm::mat4& ankle = model[static_cast<size_t>(rig.ankle[side])];
            const glm::quat rest_inv = glm::inverse(rest.rest_model_rotation(rig.ankle[side]));
            const glm::vec3 toe(model[static_cast<size_t>(rig.toe[side])][3]);
            const glm::vec3 points[2] = {glm::vec3(ankle * glm::vec4(rest_inv * c.heel, 1.0f)),
                                         toe - glm::vec3(0.0f, rest.rest_position(rig.toe[side]).y, 0.0f)};
            const float lowest = std::min(points[0].y, points[1].y);
            for (int k = 0; k < 2; ++k) {
                const int i = 2 * side + k;
                const glm::vec3& p = points[k];
                const bool on = p.y < 0.005f && p.y < lowest + 0.001f;
                if (on && !down[i]) start[i] = p, excursion[i] = 0.0f, ++contacts;
                if (on) excursion[i] = std::max(excursion[i], glm::length(glm::vec2(p.x - start[i].x, p.z - start[i].z)));
                if (!on && down[i]) skate += excursion[i];
                down[i] = on;
            }
        }
    }
    for (int i = 0; i < 4; ++i)
        if (down[i]) skate += excursion[i];
    const float walked = speed * static_cast<float>(frames) * dt;
    EXPECT_GE(contacts, 10) << "heel and ball of each foot touch down every cycle";
    EXPECT_LE(1000.0f * skate / walked, 2.0f) << "mm of contact travel per metre walked at " << speed << " m/s";
    std::printf("gait %.1f m/s: %.3f mm per metre over %d contacts\n", speed, 1000.0f * skate / walked, contacts);
}

// The pose at the loop point (root travel taken out, as the walk playback does) jumps no more than
// the largest ordinary frame-to-frame change at 60 Hz.
TEST_P(GaitClipTest, LoopSeamIsAnOrdinaryFrame) {
    GaitClip g = make_gait_clip(sk, rig, joints, GetParam(), "gait");
    auto clip = build_clip(g.clip, sk);
    ASSERT_TRUE(clip.ok());
    const float T = clip.value().duration();
    const float dt = 1.0f / 60.0f;
    auto jump = [&](float t0, float t1) {
        const auto a = pose_at(clip.value(), sk, t0, true), b = pose_at(clip.value(), sk, t1, true);
        float m = 0.0f;
        for (size_t j = 0; j < a.size(); ++j) m = std::max(m, glm::length(glm::vec3(a[j][3]) - glm::vec3(b[j][3])));
        return m;
    };
    float ordinary = 0.0f;
    for (float t = 0.0f; t + dt < T; t += dt) ordinary = std::max(ordinary, jump(t, t + dt));
    const float seam = jump(T - 0.5f * dt, 0.5f * dt);
    EXPECT_LE(seam, ordinary);
    EXPECT_LT(jump(T, 0.0f), 1e-4f) << "the last key is the first (one stride on)";
}

INSTANTIATE_TEST_SUITE_P(Speeds, GaitClipTest, ::testing::Values(0.8f, 1.4f, 2.5f));

// Stride and cadence follow Alexander's relation; duty < 0.5 (running) only above Froude 0.5.
TEST(GaitModel, StrideCadenceAndTransition) {
    const float h = 0.93f;
    for (float v : {0.5f, 0.8f, 1.4f, 2.0f, 2.5f, 3.0f}) {
        const GaitCycle g = gait_cycle(v, h);
        const float froude = v * v / (9.81f * h);
        EXPECT_NEAR(g.stride, 2.3f * h * std::pow(froude, 0.3f), 1e-5f);
        EXPECT_NEAR(g.period * v, g.stride, 1e-5f);
        EXPECT_EQ(g.running, froude > 0.5f);
        EXPECT_EQ(g.duty < 0.5f, g.running) << v;
    }
    // 1.4 m/s for a 1.75 m adult: 1.3-1.5 m stride, 100-125 steps a minute (published norms).
    const GaitCycle walk = gait_cycle(1.4f, h);
    EXPECT_GT(walk.stride, 1.25f);
    EXPECT_LT(walk.stride, 1.5f);
    EXPECT_GT(120.0f / walk.period, 100.0f);
    EXPECT_LT(120.0f / walk.period, 130.0f);
}

}  // namespace
}  // namespace aloha
