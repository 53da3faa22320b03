// Inertialization: the decay curve, offsets that reproduce the shown pose exactly, and the generated
// walk through the controller switching walk method, IK and update interval with no joint jump over
// the ordinary frame-to-frame motion, transitions timed in seconds at any frame rate.
#include "systems/motion/controller.hpp"
#include "systems/motion/inertialize.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/motion_metrics.hpp"
#include "tests/common/test_humanoid.hpp"
#include "tests/systems/motion/generated_gait_fixture.hpp"
#include "tests/systems/motion/walk_request.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <random>

namespace aloha {
namespace {

TEST(InertialWeight, OneToZeroSmoothlyAtBothEnds) {
    EXPECT_FLOAT_EQ(inertial_weight(0.0f, 0.2f), 1.0f);
    EXPECT_FLOAT_EQ(inertial_weight(0.2f, 0.2f), 0.0f);
    EXPECT_FLOAT_EQ(inertial_weight(1.0f, 0.2f), 0.0f);
    EXPECT_NEAR(inertial_weight(0.1f, 0.2f), 0.5f, 1e-6f);  // symmetric about the middle
    // Slope (1 - smootherstep)' = -30 t^2 (1 - t)^2: zero at both ends, largest (-15/8 per unit t) in
    // the middle; checked by differences.
    const float h = 1e-3f;
    float prev = 1.0f, steepest = 0.0f;
    for (int i = 1; i <= 1000; ++i) {
        const float w = inertial_weight(static_cast<float>(i) * h, 1.0f);
        EXPECT_LE(w, prev + 2.0f * FLT_EPSILON);  // monotone up to float rounding near 1
        steepest = std::max(steepest, (prev - w) / h);
        prev = w;
    }
    EXPECT_NEAR(steepest, 15.0f / 8.0f, 1e-2f);
    // Flat ends: the change over the first and last h is 10 h^3 (+ float rounding of 1 at the start),
    // so the mean slope there is 10 h^2 = 1e-5, against 1.875 in the middle.
    EXPECT_LT((1.0f - inertial_weight(h, 1.0f)) / h, 10.0f * h * h + 2.0f * FLT_EPSILON / h);
    EXPECT_NEAR(inertial_weight(1.0f - h, 1.0f) / h, 10.0f * h * h, 1e-6f);
}

// hold + relate + apply(1) gives back the held pose (to float precision); apply(0) leaves the new one.
TEST(InertialOffsets, FullWeightReproducesTheShownPose) {
    const Skeleton sk = test::humanoid_skeleton_for();
    const size_t n = static_cast<size_t>(sk.joint_count());
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    auto random_pose = [&](std::vector<glm::vec3>& t, std::vector<glm::quat>& r, std::vector<glm::vec3>& s) {
        t.resize(n), r.resize(n), s.assign(n, glm::vec3(1.0f));
        for (size_t j = 0; j < n; ++j) {
            t[j] = sk.rest_translations()[j] + 0.05f * glm::vec3(u(rng), u(rng), u(rng));
            r[j] = glm::normalize(glm::quat(1.0f + u(rng), u(rng), u(rng), u(rng)));
        }
    };
    std::vector<glm::vec3> ta, sa, tb, sb;
    std::vector<glm::quat> ra, rb;
    random_pose(ta, ra, sa);
    random_pose(tb, rb, sb);
    std::vector<glm::mat4> shown(n), model(n);
    local_to_model(sk.parents().data(), ta.data(), ra.data(), sa.data(), nullptr, shown.data(), n);
    InertialOffsets offsets(sk.joint_count());
    const uint32_t slot = offsets.acquire();
    offsets.hold(slot, sk.parents().data(), shown);
    offsets.relate(slot, ConstPoseView{tb, rb, sb, model});
    std::vector<glm::vec3> t = tb, s = sb;
    std::vector<glm::quat> r = rb;
    offsets.apply(slot, 0.0f, PoseView{t, r, s, model});
    for (size_t j = 0; j < n; ++j) EXPECT_EQ(r[j], rb[j]);
    offsets.apply(slot, 1.0f, PoseView{t, r, s, model});
    local_to_model(sk.parents().data(), t.data(), r.data(), s.data(), nullptr, model.data(), n);
    for (size_t j = 0; j < n; ++j)
        EXPECT_LT(glm::length(glm::vec3(model[j][3]) - glm::vec3(shown[j][3])), 1e-5f) << "joint " << j;
    EXPECT_EQ(offsets.in_use(), 1u);
    offsets.release(slot);
    EXPECT_EQ(offsets.in_use(), 0u);
}

// The generated walk at 1.4 m/s through the controller; `lod_at(time, lod)` sets the level each frame.
// `pops` counts the frames of a change as switch frames; `during` (optional) every frame from a change
// to the end of its transition.
class SwitchedWalk : public test::GeneratedGait {
protected:
    template <class LodAt>
    size_t walk(float seconds, float dt, PopMeter& pops, LodAt lod_at, std::vector<float>* transition_lengths = nullptr,
                PopMeter* during = nullptr) {
        Walker w(*this, 1.4f);
        std::vector<glm::vec3> world;
        size_t changes = 0;
        float transition = -1.0f;
        for (int f = 0; f < static_cast<int>(std::lround(seconds / dt)); ++f) {
            const AnimLod before = w.lod();
            lod_at(static_cast<float>(f) * dt, w.lod());
            const AnimLod& now = w.lod();
            const bool changed = f > 0 && (before.walk != now.walk || before.ik != now.ik ||
                                           before.update_interval != now.update_interval || before.level != now.level);
            changes += changed;
            w.step(dt);
            if (changed) transition = 0.0f;
            if (transition >= 0.0f && !changed) transition += dt;
            if (transition >= 0.0f && !w.mc.in_transition(0)) {
                if (transition_lengths) transition_lengths->push_back(transition);
                transition = -1.0f;
            }
            w.world_joints(world);
            pops.add(world, changed);
            if (during) during->add(world, changed || w.mc.in_transition(0));
        }
        return changes;
    }
};

AnimLod level(uint8_t index, WalkMethod walk, uint8_t interval, float crossfade_s) {
    AnimLod l;
    l.level = index;
    l.walk = walk;
    l.ik = IkSolver::None;
    l.update_interval = interval;
    l.crossfade_s = crossfade_s;
    return l;
}

// Kinematic -> clip (interval 1) -> clip at interval 8 -> clip at interval 2 -> ... every 0.7 s. The
// bar of issue 15: the frame of a change moves no joint further than the 95th percentile of ordinary
// frames. Transition frames: the shown motion is the new level's own motion plus the change of the
// decaying offset, whose weight falls by at most 15/8 * dt / T per frame (the steepest slope of
// 1 - smootherstep); the offset is at most the jump the same change makes with transitions off. So no
// transition frame moves a joint further than the fastest ordinary frame plus 15/8 * dt / T of the
// largest snapped jump.
TEST_F(SwitchedWalk, InertializedSwitchesStayWithinOrdinaryMotion) {
    auto ladder = [](float fade) {
        return [fade](float t, AnimLod& lod) {
            const AnimLod steps[4] = {level(0, WalkMethod::Kinematic, 1, fade), level(1, WalkMethod::ClipPlayback, 1, fade),
                                      level(2, WalkMethod::ClipPlayback, 8, fade), level(3, WalkMethod::ClipPlayback, 2, fade)};
            lod = steps[static_cast<int>(t / 0.7f) % 4];
        };
    };
    const float dt = 1.0f / 60.0f, T = 0.2f;
    PopMeter pops, during, snapped;
    const size_t changes = walk(10.0f, dt, pops, ladder(T), nullptr, &during);
    walk(10.0f, dt, snapped, ladder(0.0f));
    const float transition_bound = during.ordinary_max() + 15.0f / 8.0f * dt / T * snapped.worst_switch();
    std::printf("inertialized: %zu changes, worst change frame %.2f cm, ordinary p95 %.2f cm; %zu transition frames, "
                "worst %.2f cm, bound %.2f cm (fastest ordinary %.2f cm, largest snapped jump %.2f cm)\n",
                changes, static_cast<double>(100.0f * pops.worst_switch()), static_cast<double>(100.0f * pops.ordinary_p95()),
                during.switches(), static_cast<double>(100.0f * during.worst_switch()),
                static_cast<double>(100.0f * transition_bound), static_cast<double>(100.0f * during.ordinary_max()),
                static_cast<double>(100.0f * snapped.worst_switch()));
    EXPECT_EQ(changes, 14u);
    EXPECT_EQ(pops.switches(), changes);
    EXPECT_GE(during.switches(), changes * 12);  // each transition lasts its 0.2 s (12 frames at 60 Hz)
    EXPECT_LE(pops.worst_switch(), pops.ordinary_p95());
    EXPECT_LE(during.worst_switch(), transition_bound);
}

// The same ladder with transitions off snaps: the check above is not passed by accident.
TEST_F(SwitchedWalk, WithoutTransitionsTheKinematicToClipSwitchJumps) {
    PopMeter snapped, smooth;
    auto ladder = [](float fade) {
        return [fade](float t, AnimLod& lod) {
            lod = static_cast<int>(t / 0.7f) % 2 ? level(1, WalkMethod::ClipPlayback, 1, fade)
                                                 : level(0, WalkMethod::Kinematic, 1, fade);
        };
    };
    walk(6.0f, 1.0f / 60.0f, snapped, ladder(0.0f));
    walk(6.0f, 1.0f / 60.0f, smooth, ladder(0.2f));
    std::printf("kinematic <-> clip: snapped worst %.2f cm, inertialized worst %.2f cm\n",
                static_cast<double>(100.0f * snapped.worst_switch()), static_cast<double>(100.0f * smooth.worst_switch()));
    EXPECT_GT(snapped.worst_switch(), snapped.ordinary_p95());
    EXPECT_LE(smooth.worst_switch(), smooth.ordinary_p95());
}

// Transitions last their time in seconds whatever the frame rate: 12 frames at 60 Hz = 0.2 s, ended
// within one frame of 0.2 s at 30, 60 and 120 Hz.
TEST_F(SwitchedWalk, TransitionsLastTheSameSecondsAtAnyFrameRate) {
    for (float hz : {30.0f, 60.0f, 120.0f}) {
        PopMeter pops;
        std::vector<float> lengths;
        walk(3.0f, 1.0f / hz, pops, [](float t, AnimLod& lod) {
            lod = t < 1.0f ? level(0, WalkMethod::Kinematic, 1, 0.2f) : level(1, WalkMethod::ClipPlayback, 1, 0.2f);
        }, &lengths);
        ASSERT_EQ(lengths.size(), 1u) << hz << " Hz";
        EXPECT_NEAR(lengths[0], 0.2f, 1.0f / hz + 1e-4f) << hz << " Hz";
    }
}

}  // namespace
}  // namespace aloha
