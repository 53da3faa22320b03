// Closing a loop's seam: a walk cut a little off its cycle meets itself in pose and velocity once closed, keys away
// from the ends are untouched and the loop still travels as far; a loop that already meets itself barely moves.
#include "systems/motion/clip.hpp"
#include "systems/motion/library/gait_clip.hpp"
#include "systems/motion/library/loop_cut.hpp"
#include "systems/motion/library/loop_seam.hpp"
#include "tests/common/clip_pose.hpp"
#include "tests/common/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace aloha {
namespace {

// The angle between two rotations (atan2 of the difference's parts: acos of a float dot near 1 resolves only 7e-4).
float angle_between(const glm::quat& a, const glm::quat& b) {
    const glm::quat d = b * glm::inverse(a);
    return 2.0f * std::atan2(glm::length(glm::vec3(d.x, d.y, d.z)), std::abs(d.w));
}

// How far a loop's ends are apart: mean joint distance between its first and last poses, and mean difference of the
// joints' velocities at the two ends (slopes of the parabola through three samples `h` apart), both in model space
// relative to the root's ground position.
struct Seam {
    float pose = 0.0f;      // m
    float velocity = 0.0f;  // m/s
};

class LoopSeamTest : public ::testing::Test {
protected:
    // `cycles` gait cycles at 1.4 m/s, the root travelling on; `cycle_keys` steps of `step` seconds make a cycle.
    RawAnimation walk(int cycles, size_t* cycle_keys, float* step) const {
        const GaitClip g = make_gait_clip(sk, rig, find_humanoid_joints(sk), 1.4f, "g");
        RawAnimation take;
        take.name = "walk";
        take.tracks.resize(static_cast<size_t>(sk.joint_count()));
        const size_t n = g.clip.tracks[0].rotations.values.size();
        const float dt = g.clip.duration / static_cast<float>(n - 1);
        *cycle_keys = n - 1;
        *step = dt;
        float t = 0.0f;
        for (int c = 0; c < cycles; ++c)
            for (size_t k = (c == 0 ? 0 : 1); k < n; ++k, t += dt)
                for (size_t j = 0; j < take.tracks.size(); ++j) {
                    take.tracks[j].rotations.times.push_back(t);
                    take.tracks[j].rotations.values.push_back(g.clip.tracks[j].rotations.values[k]);
                    if (j != 0) continue;
                    take.tracks[0].translations.times.push_back(t);
                    take.tracks[0].translations.values.push_back(g.clip.tracks[0].translations.values[k] +
                                                                 glm::vec3(0.0f, 0.0f, g.cycle.stride * static_cast<float>(c)));
                }
        take.duration = t - dt;
        return take;
    }

    // Keys first..last of `take` (all at one rate), re-timed from 0: a loop cut on keys, its seam left open.
    RawAnimation keys_between(const RawAnimation& take, size_t first, size_t last) const {
        RawAnimation out;
        out.name = "open";
        out.tracks.resize(take.tracks.size());
        for (size_t j = 0; j < take.tracks.size(); ++j) {
            const auto copy = [&](const auto& from, auto& to) {
                if (from.values.empty()) return;
                for (size_t k = first; k <= last; ++k) {
                    to.times.push_back(from.times[k] - from.times[first]);
                    to.values.push_back(from.values[k]);
                }
            };
            copy(take.tracks[j].rotations, out.tracks[j].rotations);
            copy(take.tracks[j].translations, out.tracks[j].translations);
        }
        out.duration = take.tracks[0].rotations.times[last] - take.tracks[0].rotations.times[first];
        return out;
    }

    // Joint positions of `clip` at time t, relative to the root's ground position.
    std::vector<glm::vec3> joints_at(const AnimationClip& clip, float t) const {
        std::vector<glm::vec3> out = test::clip_model_positions(clip, sk, t);
        const glm::vec3 root(out[0].x, 0.0f, out[0].z);
        for (glm::vec3& p : out) p -= root;
        return out;
    }

    Seam seam_of(const RawAnimation& loop, float h) const {
        auto built = build_clip(loop, sk, ClipEncoding::Float32);
        EXPECT_TRUE(built.ok());
        const AnimationClip& c = built.value();
        const float d = c.duration();
        const auto p0 = joints_at(c, 0.0f), p1 = joints_at(c, h), p2 = joints_at(c, 2.0f * h);
        const auto q0 = joints_at(c, d), q1 = joints_at(c, d - h), q2 = joints_at(c, d - 2.0f * h);
        Seam s;
        for (size_t j = 0; j < p0.size(); ++j) {
            s.pose += glm::length(p0[j] - q0[j]);
            const glm::vec3 v_start = (-3.0f * p0[j] + 4.0f * p1[j] - p2[j]) / (2.0f * h);
            const glm::vec3 v_end = (3.0f * q0[j] - 4.0f * q1[j] + q2[j]) / (2.0f * h);
            s.velocity += glm::length(v_start - v_end);
        }
        s.pose /= static_cast<float>(p0.size());
        s.velocity /= static_cast<float>(p0.size());
        return s;
    }

    Skeleton sk = test::humanoid_skeleton_for();
    WalkRig rig = test::humanoid_rig(sk);
};

TEST_F(LoopSeamTest, AWalkCutOffItsCycleMeetsItselfOnceClosed) {
    size_t cycle = 0;
    float h = 0.0f;
    const RawAnimation take = walk(3, &cycle, &h);
    // A cycle and two keys from mid-stance: a seam of the size find_best_loop still accepts (up to 3 cm, 0.25 m/s).
    const size_t first = 30, last = first + cycle + 2;
    const RawAnimation open = keys_between(take, first, last);
    const Seam before = seam_of(open, h);
    ASSERT_GT(before.pose, 0.005f) << "the cut is off the cycle";
    ASSERT_GT(before.velocity, 0.05f);
    // As cut_loop cuts it from the take (the take's velocities at both cut points matched), and alone (looped
    // whole: its ends met, velocities matched only beyond the jumps each track makes inside the loop).
    const RawAnimation cut_from_take = cut_loop(take, sk, LoopCut{take.tracks[0].rotations.times[first], take.tracks[0].rotations.times[last], 0, 0}, "loop");
    RawAnimation alone = open;
    const SeamClosing bent = close_loop_seam(alone);
    const Seam from_take = seam_of(cut_from_take, h), by_itself = seam_of(alone, h);
    std::printf("seam before %.2f cm, %.3f m/s; cut from the take %.6f cm, %.4f m/s; alone %.6f cm, %.4f m/s\n",
                static_cast<double>(100.0f * before.pose), static_cast<double>(before.velocity), static_cast<double>(100.0f * from_take.pose),
                static_cast<double>(from_take.velocity), static_cast<double>(100.0f * by_itself.pose), static_cast<double>(by_itself.velocity));
    // The ends' rotations are made equal to float rounding: the joints meet to far under a micrometre a bone.
    EXPECT_LT(from_take.pose, 1e-5f);
    EXPECT_LT(by_itself.pose, 1e-5f);
    // Velocities from the take: matched exactly for translations, to second order in the seam's difference for
    // rotations (the left offset's rate is not exactly its rotation vector's), and the parabola that measures them is
    // off by the cubic offset's third derivative times h squared. Bound: a tenth of the seam's jump.
    EXPECT_LT(from_take.velocity, 0.1f * before.velocity);
    // Alone, this mid-stance seam jumps less in every track than the track does at its heel strikes: velocities are
    // left (the value's fade has zero slope at the seam; the parabola sees its slope one and two keys in, a few %).
    EXPECT_LT(by_itself.velocity, 1.1f * before.velocity);
    std::printf("largest offset %.4f rad, %.2f mm\n", static_cast<double>(bent.max_rotation), static_cast<double>(1000.0f * bent.max_translation));
    // Keys further than the window from both ends are untouched, and the loop travels as far.
    for (size_t j = 0; j < open.tracks.size(); ++j) {
        const auto& a = open.tracks[j].rotations;
        const auto& b = alone.tracks[j].rotations;
        ASSERT_EQ(a.times, b.times);
        for (size_t k = 0; k < a.times.size(); ++k)
            if (a.times[k] > kSeamWindow && a.times[k] < open.duration - kSeamWindow) {
                ASSERT_EQ(a.values[k], b.values[k]) << "joint " << j << " key " << k;
            }
    }
    const auto& ro = open.tracks[0].translations.values;
    const auto& rc = alone.tracks[0].translations.values;
    EXPECT_FLOAT_EQ(rc.back().x - rc.front().x, ro.back().x - ro.front().x);
    EXPECT_FLOAT_EQ(rc.back().z - rc.front().z, ro.back().z - ro.front().z);
    EXPECT_NEAR(rc.back().y, rc.front().y, 1e-6f) << "the root's height meets itself";
}

TEST_F(LoopSeamTest, WholeCyclesCutAtAHeelStrikeKeepTheirKinks) {
    // Cut at the left heel strike, where the knee turns abruptly: the take has that kink at both cut points, so
    // there is nothing to match, and the loop's knee keeps it.
    size_t cycle = 0;
    float h = 0.0f;
    const RawAnimation take = walk(3, &cycle, &h);
    const RawAnimation open = keys_between(take, cycle, 2 * cycle);
    const LoopCut cut{take.tracks[0].rotations.times[cycle], take.tracks[0].rotations.times[2 * cycle], 0.0f, 0.0f};
    const RawAnimation closed = cut_loop(take, sk, cut, "loop");
    ASSERT_EQ(closed.tracks[1].rotations.values.size(), open.tracks[1].rotations.values.size());
    float largest = 0.0f;
    for (size_t j = 0; j < open.tracks.size(); ++j)
        for (size_t k = 0; k < open.tracks[j].rotations.values.size(); ++k)
            largest = std::max(largest, angle_between(open.tracks[j].rotations.values[k], closed.tracks[j].rotations.values[k]));
    std::printf("whole cycles cut from the take: largest rotation change %.2e rad\n", static_cast<double>(largest));
    // The take repeats exactly and the cut falls on its keys: the loop is its keys to float rounding, where matching
    // the knee's kink would move them by hundredths of a radian.
    EXPECT_LT(largest, 1e-5f);
}

TEST_F(LoopSeamTest, ACycleLoopedWholeKeepsItsOwnKinks) {
    // The generated walk is one cycle from left heel strike to the next, the knee turning abruptly at its ends: a jump
    // no larger than its steps inside, so only the (float-rounding) difference of its ends is closed.
    GaitClip g = make_gait_clip(sk, rig, find_humanoid_joints(sk), 1.4f, "g");
    const Seam before = seam_of(g.clip, g.clip.duration / static_cast<float>(g.clip.tracks[0].rotations.values.size() - 1));
    const SeamClosing bent = close_loop_seam(g.clip);
    std::printf("generated walk seam %.5f cm, %.4f m/s; closing moved keys by %.2e rad, %.2e m\n",
                static_cast<double>(100.0f * before.pose), static_cast<double>(before.velocity), static_cast<double>(bent.max_rotation),
                static_cast<double>(bent.max_translation));
    // Regression guards from the measured figures (7.8e-7 rad, 3e-8 m): what a kink smoothed away would move is
    // hundredths of a radian (0.066 rad when the knee's jump was matched).
    EXPECT_LT(bent.max_rotation, 1e-5f);
    EXPECT_LT(bent.max_translation, 1e-6f);
}

TEST_F(LoopSeamTest, TracksTooShortOrNotSpanningTheLoopAreLeft) {
    RawAnimation loop;
    loop.duration = 1.0f;
    loop.tracks.resize(2);
    loop.tracks[1].rotations.times = {0.0f, 1.0f};  // two keys: no velocity at the ends
    loop.tracks[1].rotations.values = {glm::quat(1, 0, 0, 0), glm::angleAxis(0.3f, glm::vec3(1, 0, 0))};
    loop.tracks[1].translations.times = {0.0f, 0.5f, 0.7f, 0.9f};  // ends before the loop does
    loop.tracks[1].translations.values = {glm::vec3(0), glm::vec3(1), glm::vec3(2), glm::vec3(3)};
    const RawAnimation before = loop;
    const SeamClosing bent = close_loop_seam(loop);
    EXPECT_EQ(bent.max_rotation, 0.0f);
    EXPECT_EQ(bent.max_translation, 0.0f);
    EXPECT_EQ(loop.tracks[1].rotations.values, before.tracks[1].rotations.values);
    EXPECT_EQ(loop.tracks[1].translations.values, before.tracks[1].translations.values);
}

}  // namespace
}  // namespace aloha
