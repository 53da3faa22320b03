// Best-loop cutting: a take that stands, walks three cycles and stands again is cut to a whole number
// of gait cycles inside the walk with a seam far below the limits; a take that never repeats is
// refused with a note; the shared CMU "start, walk, stop" take (when present) gets a clear answer.
#include "engine/assets/bvh_loader.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/library/gait_clip.hpp"
#include "systems/motion/library/loop_cut.hpp"
#include "tests/common/test_assets.hpp"
#include "tests/common/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

class LoopCutTest : public ::testing::Test {
protected:
    // `stand` seconds of the rest pose, `cycles` gait cycles at 1.4 m/s, `stand` seconds of rest.
    RawAnimation stand_walk_stand(float stand, int cycles, float* period) const {
        const GaitClip g = make_gait_clip(sk, rig, find_humanoid_joints(sk), 1.4f, "g");
        *period = g.cycle.period;
        RawAnimation take;
        take.name = "stand_walk_stand";
        take.tracks.resize(static_cast<size_t>(sk.joint_count()));
        const float dt = 1.0f / 60.0f;
        float t = 0.0f;
        const glm::vec3 first_root = g.clip.tracks[0].translations.values.front();
        auto key = [&](size_t j, const glm::quat& r, const glm::vec3* root) {
            take.tracks[j].rotations.times.push_back(t);
            take.tracks[j].rotations.values.push_back(r);
            if (root) {
                take.tracks[j].translations.times.push_back(t);
                take.tracks[j].translations.values.push_back(*root);
            }
        };
        auto rest_keys = [&](float seconds, glm::vec3 root) {
            for (int k = 0; k < static_cast<int>(seconds / dt); ++k, t += dt)
                for (size_t j = 0; j < take.tracks.size(); ++j) key(j, sk.rest_rotations()[j], j == 0 ? &root : nullptr);
        };
        rest_keys(stand, sk.rest_translations()[0]);
        glm::vec3 root{};
        for (int c = 0; c < cycles; ++c) {
            const size_t n = g.clip.tracks[0].rotations.values.size();
            for (size_t k = (c == 0 ? 0 : 1); k < n; ++k, t += dt) {
                root = g.clip.tracks[0].translations.values[k] + glm::vec3(0.0f, 0.0f, g.cycle.stride * static_cast<float>(c));
                for (size_t j = 0; j < take.tracks.size(); ++j) key(j, g.clip.tracks[j].rotations.values[k], j == 0 ? &root : nullptr);
            }
        }
        (void)first_root;
        rest_keys(stand, glm::vec3(root.x, sk.rest_translations()[0].y, root.z));
        take.duration = t - dt;
        return take;
    }
    Skeleton sk = test::humanoid_skeleton_for();
    WalkRig rig = test::humanoid_rig(sk);
};

TEST_F(LoopCutTest, CutsWholeCyclesOutOfAStartWalkStopTake) {
    float period = 0.0f;
    const RawAnimation take = stand_walk_stand(1.0f, 3, &period);
    auto cut = find_best_loop(take, sk, 0.6f, 0.5f, "take");
    ASSERT_TRUE(cut.ok()) << cut.error().to_string();
    const LoopCut& c = cut.value();
    EXPECT_GE(c.start, 1.0f - 1e-3f) << "inside the walk, not the standing";
    EXPECT_LE(c.end, 1.0f + 3.0f * period + 1e-3f);
    const float cycles = (c.end - c.start) / period;
    EXPECT_NEAR(cycles, std::round(cycles), 1.5f / 30.0f / period) << "a whole number of cycles, to the search step";
    EXPECT_LT(c.pose_error, 0.01f);
    const RawAnimation loop = cut_loop(take, sk, c, "loop");
    auto built = build_clip(loop, sk);
    ASSERT_TRUE(built.ok()) << built.error().to_string();
    EXPECT_NEAR(built.value().root_speed(), 1.4f, 0.05f) << "the loop walks at the take's speed";
}

TEST_F(LoopCutTest, RefusesATakeThatNeverRepeats) {
    RawAnimation take;
    take.name = "reach_up";
    take.tracks.resize(static_cast<size_t>(sk.joint_count()));
    const int shoulder = sk.find("LeftShoulder");
    for (int k = 0; k <= 180; ++k) {  // 3 s: travels at 1 m/s while the arm rises steadily
        const float t = static_cast<float>(k) / 60.0f;
        take.tracks[0].translations.times.push_back(t);
        take.tracks[0].translations.values.push_back(sk.rest_translations()[0] + glm::vec3(0, 0, t));
        take.tracks[static_cast<size_t>(shoulder)].rotations.times.push_back(t);
        take.tracks[static_cast<size_t>(shoulder)].rotations.values.push_back(glm::angleAxis(t, glm::vec3(0, 0, 1)));
    }
    take.duration = 3.0f;
    auto cut = find_best_loop(take, sk, 0.6f, 0.5f, "reach.bvh");
    ASSERT_FALSE(cut.ok());
    EXPECT_NE(cut.error().to_string().find("reach.bvh"), std::string::npos);
    EXPECT_NE(cut.error().message.find("does not loop"), std::string::npos) << cut.error().message;
}

TEST(LoopCutShared, CmuStartWalkStopIsCutOrRefusedWithItsFigures) {
    ALOHA_REQUIRE_TEST_ASSET(path, "131_01.bvh");
    auto bvh = load_bvh(path);
    ASSERT_TRUE(bvh.ok()) << bvh.error().to_string();
    auto sk = build_skeleton(bvh.value().skeleton, path);
    ASSERT_TRUE(sk.ok());
    auto cut = find_best_loop(bvh.value().animation, sk.value(), 0.6f, 0.5f, path);
    if (!cut.ok()) {
        // A clear answer either way: refused, naming the file and the best loop it found.
        std::printf("131_01: %s\n", cut.error().message.c_str());
        EXPECT_EQ(cut.error().file, path);
        EXPECT_NE(cut.error().message.find("does not loop: its best loop"), std::string::npos) << cut.error().message;
        return;
    }
    std::printf("131_01 loop %.2f-%.2f s, seam %.1f cm, %.2f m/s\n", static_cast<double>(cut.value().start),
                static_cast<double>(cut.value().end), static_cast<double>(100.0f * cut.value().pose_error),
                static_cast<double>(cut.value().velocity_error));
    auto built = build_clip(cut_loop(bvh.value().animation, sk.value(), cut.value(), "loop"), sk.value());
    ASSERT_TRUE(built.ok());
    EXPECT_GT(built.value().root_speed(), 0.5f);
}

}  // namespace
}  // namespace aloha
