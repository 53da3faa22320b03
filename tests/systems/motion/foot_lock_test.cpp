// Foot lock: the generated walk through the controller, switching between the kinematic walk and the
// clip level at update intervals 4 and 8 (inertialized), keeps every planted foot within 5 mm of where
// it touched down (issue 15's bound), at 30, 60 and 120 Hz; without the lock the same walk slides.
#include "systems/motion/controller.hpp"
#include "systems/motion/foot_lock.hpp"
#include "systems/motion/motion_metrics.hpp"
#include "tests/systems/motion/generated_gait_fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <vector>
#include <cstdio>

namespace aloha {
namespace {

AnimLod level(uint8_t index, WalkMethod walk, uint8_t interval) {
    AnimLod l;
    l.level = index;
    l.walk = walk;
    l.ik = IkSolver::None;
    l.update_interval = interval;
    l.crossfade_s = 0.2f;
    return l;
}

// The sole points the crowd meter measures (sole_offsets under ankles and toes), world, frame after frame;
// contact as issue 15 defines it (ContactThresholds: within 5 mm of the lowest height the point reaches
// in the recording, slower than 0.5 m/s).
struct SoleRecording {
    size_t feet = 4;
    std::vector<glm::vec3> points;  // frame-major
    std::vector<float> dts;
    /// Total horizontal travel in contact (m): the crowd meter's skate.
    [[nodiscard]] float skate() const {
        float sum = 0.0f;
        for (const float step : contact_travel(points, feet, dts, ContactThresholds{})) sum += step;
        return sum;
    }
    /// Largest horizontal distance a point in contact got from where its contact began (m).
    [[nodiscard]] float worst_excursion() const {
        const ContactThresholds t;
        const size_t frames = dts.size();
        float worst = 0.0f;
        for (size_t i = 0; i < feet; ++i) {
            float lowest = 1e9f;
            for (size_t f = 0; f < frames; ++f) lowest = std::min(lowest, points[f * feet + i].y);
            glm::vec2 start(0.0f);
            bool down = false;
            for (size_t f = 1; f < frames; ++f) {
                const glm::vec3 &a = points[(f - 1) * feet + i], &b = points[f * feet + i];
                const glm::vec2 p(b.x, b.z);
                const bool on = a.y <= lowest + t.height && b.y <= lowest + t.height &&
                                glm::length(p - glm::vec2(a.x, a.z)) < t.speed * dts[f];
                if (on && !down) start = glm::vec2(a.x, a.z);
                if (on) worst = std::max(worst, glm::length(p - start));
                down = on;
            }
        }
        return worst;
    }
};

class FootLockWalk : public test::GeneratedGait {
protected:
    void record(SoleRecording& r, const MotionController& mc, const Transform& x, float dt) const {
        const std::vector<int> feet = {rig.ankle[0], rig.ankle[1], rig.toe[0], rig.toe[1]};
        const std::vector<glm::vec3> soles = sole_offsets(sk, feet);
        const auto model = mc.poses().view(0).model;
        for (size_t i = 0; i < feet.size(); ++i)
            r.points.push_back(x.position + x.rotation * glm::vec3(model[static_cast<size_t>(feet[i])] * glm::vec4(soles[i], 1.0f)));
        r.dts.push_back(dt);
    }
    // Walks 8 s at 1.4 m/s with frames of `dt`, the level changing every 0.55 s (not a multiple of the
    // step, so changes fall at every phase of the gait): kinematic (1) -> clip (8) -> clip (4) -> clip (8)
    // -> kinematic... `lock` turns the foot lock on or off.
    SoleRecording walk(float dt, bool lock, size_t* changes = nullptr) {
        Walker w(*this, 1.4f);
        w.mc.set_foot_lock(lock);
        SoleRecording r;
        const AnimLod ladder[4] = {level(0, WalkMethod::Kinematic, 1), level(1, WalkMethod::ClipPlayback, 8),
                                   level(2, WalkMethod::ClipPlayback, 4), level(1, WalkMethod::ClipPlayback, 8)};
        size_t switches = 0;
        for (int f = 0; f < static_cast<int>(std::lround(8.0f / dt)); ++f) {
            const AnimLod& now = ladder[static_cast<int>(static_cast<float>(f) * dt / 0.55f) % 4];
            switches += f > 0 && now.level != w.lod().level;
            w.lod() = now;
            w.step(dt);
            record(r, w.mc, w.xs[0], dt);
        }
        if (changes) *changes = switches;
        return r;
    }
};

// Interval-8 updates and the blends of level changes: a planted foot stays within 5 mm of where it
// touched down with the lock, at any frame rate; without it the same walk slides (the test is not
// passed by accident).
TEST_F(FootLockWalk, PlantedFeetStayWithin5mmThroughThrottlingAndSwitches) {
    for (float hz : {30.0f, 60.0f, 120.0f}) {
        size_t changes = 0;
        const SoleRecording locked = walk(1.0f / hz, true, &changes);
        const SoleRecording free = walk(1.0f / hz, false);
        std::printf("%.0f Hz, %zu level changes: worst contact excursion %.2f mm with the lock, %.2f mm without; "
                    "skate %.3f / %.3f mm per metre\n",
                    static_cast<double>(hz), changes, static_cast<double>(1000.0f * locked.worst_excursion()),
                    static_cast<double>(1000.0f * free.worst_excursion()),
                    static_cast<double>(1000.0f * locked.skate() / 11.2f), static_cast<double>(1000.0f * free.skate() / 11.2f));
        EXPECT_GE(changes, 13u) << hz << " Hz";
        EXPECT_LE(locked.worst_excursion(), 0.005f) << hz << " Hz";
        EXPECT_GT(free.worst_excursion(), 0.005f) << hz << " Hz";
        EXPECT_LT(locked.skate(), free.skate()) << hz << " Hz";
    }
}

// The lock's state follows the gait: each foot is held for part of the cycle and let go for the rest
// (a foot held for good would be dragged along by the leg IK and never swing).
TEST_F(FootLockWalk, FeetAreHeldInStanceAndReleasedInSwing) {
    Walker w(*this, 1.4f);
    w.lod() = level(1, WalkMethod::ClipPlayback, 8);
    int held[2] = {0, 0}, frames = 0;
    for (; frames < 240; ++frames) {
        w.step(1.0f / 60.0f);
        for (int side = 0; side < 2; ++side) held[side] += w.mc.foot_lock()->locked(0, side) ? 1 : 0;
    }
    for (int side = 0; side < 2; ++side) {
        EXPECT_GT(held[side], frames / 4) << "side " << side;
        EXPECT_LT(held[side], frames * 9 / 10) << "side " << side;
    }
}

// A path with right-angle and sharper turns (the walker turns at up to 6 rad/s at a waypoint): the
// turning body sweeps the planted feet round, which the lock holds. Bar: issue 15's 10 mm per metre, and
// less than without the lock, at update intervals 1, 4 and 8.
TEST_F(FootLockWalk, TurningPathSkatesLessWithTheLock) {
    for (uint8_t interval : {uint8_t{1}, uint8_t{4}, uint8_t{8}}) {
        float mm_per_m[2] = {0.0f, 0.0f};
        for (int lock = 0; lock < 2; ++lock) {
            Walker w(*this, 1.3f);
            w.mc.set_foot_lock(lock != 0);
            MotionRequest r = test::straight_walk(1.3f);
            r.path = w.mc.add_path({{0, 0, 4}, {3, 0, 4}, {3, 0, 0}, {-2, 0, 3}, {0, 0, 8}, {5, 0, 8}});
            ASSERT_TRUE(w.mc.interrupt(0, r));
            w.lod() = level(1, WalkMethod::ClipPlayback, interval);
            SoleRecording rec;
            glm::vec3 last(0.0f);
            float walked = 0.0f;
            for (int f = 0; f < 900; ++f) {
                w.step(1.0f / 60.0f);
                record(rec, w.mc, w.xs[0], 1.0f / 60.0f);
                walked += glm::length(glm::vec2(w.xs[0].position.x - last.x, w.xs[0].position.z - last.z));
                last = w.xs[0].position;
            }
            mm_per_m[lock] = 1000.0f * rec.skate() / walked;
        }
        std::printf("interval %d: %.2f mm/m without the lock, %.2f with\n", interval, static_cast<double>(mm_per_m[0]),
                    static_cast<double>(mm_per_m[1]));
        EXPECT_LE(mm_per_m[1], 10.0f) << "interval " << int{interval};
        EXPECT_LT(mm_per_m[1], mm_per_m[0]) << "interval " << int{interval};
    }
}

// A walker nobody looks at (PoseUse::Unseen: its clip pose is left stale) walks on for 3 s and is then
// seen again, as a crowd character is when it comes out of an impostor or out of view. Its feet are
// then metres from where the lock last held them: the lock must start afresh, not pull the legs towards
// the old spot (which drew crowd_10k's skinned walkers with their legs stretched out behind them). Bar:
// every offset within the lock's reach margin (max_offset leg lengths, its documented bound) and every
// ankle within a leg's length of its hip (a leg cannot reach further), on each frame after it is seen.
TEST_F(FootLockWalk, SeenAgainAfterWalkingUnseenStartsAfresh) {
    for (float hz : {30.0f, 60.0f}) {
        Walker w(*this, 1.4f);
        w.lod() = level(1, WalkMethod::ClipPlayback, 4);
        std::vector<uint8_t> use(1, static_cast<uint8_t>(PoseUse::EveryFrame));
        w.mc.set_pose_use(use);
        const float dt = 1.0f / hz;
        const float margin = w.mc.foot_lock()->params().max_offset * rig.leg_length * w.xs[0].scale;
        float worst_offset = 0.0f, worst_reach = 0.0f;
        size_t held = 0;
        for (int f = 0; f < static_cast<int>(std::lround(7.0f / dt)); ++f) {
            const float t = static_cast<float>(f) * dt;
            use[0] = static_cast<uint8_t>(t >= 2.0f && t < 5.0f ? PoseUse::Unseen : PoseUse::EveryFrame);
            w.step(dt);
            if (t < 5.0f) continue;
            const auto model = w.mc.poses().view(0).model;
            for (int side = 0; side < 2; ++side) {
                held += w.mc.foot_lock()->locked(0, side) ? 1 : 0;
                worst_offset = std::max(worst_offset, glm::length(w.mc.foot_lock()->offset(0, side)));
                const glm::vec3 hip(model[static_cast<size_t>(rig.hip[static_cast<size_t>(side)])][3]);
                const glm::vec3 ankle(model[static_cast<size_t>(rig.ankle[static_cast<size_t>(side)])][3]);
                worst_reach = std::max(worst_reach, glm::length(ankle - hip) / rig.leg_length);
            }
        }
        std::printf("%.0f Hz, seen again after 3 s unseen: largest offset %.1f mm (margin %.1f), largest hip-ankle "
                    "distance %.3f leg lengths, %zu foot-frames held\n",
                    static_cast<double>(hz), static_cast<double>(1000.0f * worst_offset), static_cast<double>(1000.0f * margin),
                    static_cast<double>(worst_reach), held);
        EXPECT_LE(worst_offset, margin * 1.0001f) << hz << " Hz";
        EXPECT_LE(worst_reach, 1.0f + 1e-3f) << hz << " Hz";
        EXPECT_GT(held, 0u) << hz << " Hz: the lock works again once the walker is seen";
    }
}

// Whatever the gap since the last apply, a held foot's offset never passes the reach margin: a walker
// that jumps 3 m between two applies (a long gap, a teleport) has its foot let go at the margin.
TEST_F(FootLockWalk, OffsetNeverPassesTheReachMargin) {
    Walker w(*this, 1.4f);
    w.lod() = level(0, WalkMethod::Kinematic, 1);
    for (int f = 0; f < 60; ++f) w.step(1.0f / 60.0f);
    FootLock lock(sk, rig, 1);
    std::vector<glm::mat4> model(w.mc.poses().view(0).model.begin(), w.mc.poses().view(0).model.end());
    Transform at = w.xs[0];
    at.position = glm::vec3(0.0f);
    lock.apply(0, 1.0f / 60.0f, at, model);
    lock.apply(0, 1.0f / 60.0f, at, model);  // standing still: whatever is down is held
    at.position.z += 3.0f;
    std::vector<glm::mat4> moved(w.mc.poses().view(0).model.begin(), w.mc.poses().view(0).model.end());
    lock.apply(0, 2.0f, at, moved);
    const float margin = lock.params().max_offset * rig.leg_length * at.scale;
    for (int side = 0; side < 2; ++side) {
        EXPECT_LE(glm::length(lock.offset(0, side)), margin * 1.0001f) << "side " << side;
        EXPECT_FALSE(lock.locked(0, side) && glm::length(lock.offset(0, side)) >= margin * 0.9999f) << "side " << side;
    }
}

}  // namespace
}  // namespace aloha
