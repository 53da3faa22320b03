// Idle, turn on the spot and wave: each loops with no seam, feet stay planted where they should,
// the turn makes a full revolution and the wave raises the right hand above the shoulder.
#include "systems/motion/clip.hpp"
#include "systems/motion/library/idle_clips.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/sampling.hpp"
#include "tests/common/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

class GeneratedClips : public ::testing::Test {
protected:
    std::vector<glm::mat4> model_at(const AnimationClip& clip, float t) const {
        const size_t n = static_cast<size_t>(sk.joint_count());
        std::vector<glm::vec3> tr(n), sc(n);
        std::vector<glm::quat> ro(n);
        int k = 0;
        float a = 0.0f;
        find_key(clip, std::clamp(t, 0.0f, clip.duration()), nullptr, &k, &a);
        sample_blocks(clip, k, a, tr.data(), ro.data(), sc.data());
        std::vector<glm::mat4> model(n);
        local_to_model(sk.parents().data(), tr.data(), ro.data(), sc.data(), nullptr, model.data(), n);
        return model;
    }
    AnimationClip built(const RawAnimation& raw) const {
        auto c = build_clip(raw, sk);
        EXPECT_TRUE(c.ok()) << (c.ok() ? "" : c.error().to_string());
        return c.ok() ? std::move(c.value()) : AnimationClip{};
    }
    static float max_joint_distance(const std::vector<glm::mat4>& a, const std::vector<glm::mat4>& b) {
        float m = 0.0f;
        for (size_t j = 0; j < a.size(); ++j) m = std::max(m, glm::length(glm::vec3(a[j][3]) - glm::vec3(b[j][3])));
        return m;
    }
    Skeleton sk = test::humanoid_skeleton_for();
    WalkRig rig = test::humanoid_rig(sk);
    HumanoidJoints joints = find_humanoid_joints(sk);
};

TEST_F(GeneratedClips, IdleLoopsWithFeetPlanted) {
    const AnimationClip idle = built(make_idle_clip(sk, rig, joints, "idle"));
    EXPECT_NEAR(idle.duration(), kIdleSeconds, 1e-4f);
    EXPECT_LT(max_joint_distance(model_at(idle, 0.0f), model_at(idle, idle.duration())), 1e-4f);
    const auto first = model_at(idle, 0.0f);
    float foot_travel = 0.0f, pelvis_travel = 0.0f;
    for (float t = 0.0f; t <= idle.duration(); t += 0.05f) {
        const auto m = model_at(idle, t);
        for (int s = 0; s < 2; ++s) {
            const size_t a = static_cast<size_t>(rig.ankle[s]);
            foot_travel = std::max(foot_travel, glm::length(glm::vec3(m[a][3]) - glm::vec3(first[a][3])));
        }
        pelvis_travel = std::max(pelvis_travel, std::abs(m[0][3].x - first[0][3].x));
    }
    EXPECT_LT(foot_travel, 1e-3f) << "feet stay where they stand";
    EXPECT_GT(pelvis_travel, 0.02f) << "the weight shifts from foot to foot";
}

TEST_F(GeneratedClips, TurnMakesOneRevolutionStepping) {
    const AnimationClip turn = built(make_turn_clip(sk, rig, joints, "turn"));
    EXPECT_LT(max_joint_distance(model_at(turn, 0.0f), model_at(turn, turn.duration())), 1e-4f);
    // Heading of the pelvis sweeps monotonically through a full turn.
    float swept = 0.0f, last = 0.0f;
    for (float t = 0.0f; t <= turn.duration() + 1e-4f; t += 0.02f) {
        const auto m = model_at(turn, t);
        const glm::vec3 f = glm::vec3(m[0][2]);
        const float heading = std::atan2(f.x, f.z);
        if (t > 0.0f) {
            float d = heading - last;
            if (d < -3.14159f) d += 6.28319f;
            if (d > 3.14159f) d -= 6.28319f;
            EXPECT_GE(d, 0.0f);
            swept += d;
        }
        last = heading;
    }
    EXPECT_NEAR(swept, 6.2832f, 0.05f);
    // Each foot is still for most of the time (it only moves during its own steps).
    for (int s = 0; s < 2; ++s) {
        int still = 0, samples = 0;
        const size_t a = static_cast<size_t>(rig.ankle[s]);
        for (float t = 0.0f; t + 0.01f <= turn.duration(); t += 0.01f, ++samples)
            if (glm::length(glm::vec3(model_at(turn, t + 0.01f)[a][3]) - glm::vec3(model_at(turn, t)[a][3])) < 1e-4f) ++still;
        EXPECT_GT(still, samples / 2) << "side " << s;
    }
}

TEST_F(GeneratedClips, WaveRaisesTheRightHandAndReturns) {
    const AnimationClip wave = built(make_wave_clip(sk, rig, joints, "wave"));
    const auto start = model_at(wave, 0.0f), mid = model_at(wave, 0.5f * wave.duration());
    EXPECT_LT(max_joint_distance(start, model_at(wave, wave.duration())), 1e-4f);
    const size_t wrist = static_cast<size_t>(joints.wrist[1]), shoulder = static_cast<size_t>(joints.shoulder[1]);
    EXPECT_LT(start[wrist][3].y, start[shoulder][3].y) << "hand hangs at the start";
    EXPECT_GT(mid[wrist][3].y, mid[shoulder][3].y + 0.1f) << "hand is raised above the shoulder mid-wave";
}

TEST_F(GeneratedClips, LibraryNamesAndBuilds) {
    const MotionLibrary lib = make_motion_library(sk, rig, "h");
    ASSERT_EQ(lib.gaits.size(), std::size(kLibraryGaitSpeeds));
    EXPECT_EQ(lib.gaits.front().name, "h.walk_0.50");
    EXPECT_EQ(lib.gaits.back().name, "h.run_3.00");
    for (const RawAnimation& g : lib.gaits) EXPECT_TRUE(build_clip(g, sk).ok()) << g.name;
    EXPECT_EQ(lib.idle.name, "h.idle");
}

TEST_F(GeneratedClips, CyclesRepeatWithoutAJump) {
    // Played looping, a clip whose ends do not meet is inertialized at each wrap and never takes the controller's
    // steady step: the generated cycles (what crowds walk, run and idle in) and the turn (one whole revolution,
    // travel aside) must meet. The wave starts and ends at rest.
    const MotionLibrary lib = make_motion_library(sk, rig, "h");
    for (const RawAnimation& g : lib.gaits) EXPECT_TRUE(build_clip(g, sk).value().ends_meet()) << g.name;
    for (const RawAnimation* c : {&lib.idle, &lib.turn, &lib.wave}) EXPECT_TRUE(build_clip(*c, sk).value().ends_meet()) << c->name;
}

}  // namespace
}  // namespace aloha
