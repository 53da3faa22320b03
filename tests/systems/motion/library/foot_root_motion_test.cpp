// Root motion from the feet of an in-place cycle: the built-in humanoid's generated walks and run, their root's
// horizontal travel taken out as an "In Place" export does, get back a travel close to the one taken out, and the
// foot on the ground stays where it is; a travelling clip, an idle and a backward walk are refused, naming the clip.
#include "systems/motion/clip.hpp"
#include "systems/motion/library/foot_root_motion.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "systems/motion/local_to_model.hpp"
#include "tests/common/clip_pose.hpp"
#include "tests/common/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace aloha {
namespace {

// `clip` with its root's horizontal travel taken out (the root stays over the origin): an in-place export.
RawAnimation in_place(const RawAnimation& clip) {
    RawAnimation out = clip;
    for (glm::vec3& p : out.tracks[0].translations.values) p.x = 0.0f, p.z = 0.0f;
    return out;
}

// `clip` played backwards: a walk that travels the other way from where it faces.
RawAnimation reversed(const RawAnimation& clip) {
    RawAnimation out = clip;
    for (RawJointTracks& t : out.tracks) {
        auto flip = [&](auto& track) {
            std::reverse(track.values.begin(), track.values.end());
            std::vector<float> times;
            for (auto it = track.times.rbegin(); it != track.times.rend(); ++it) times.push_back(clip.duration - *it);
            track.times = times;
        };
        flip(t.translations);
        flip(t.rotations);
        flip(t.scales);
    }
    return out;
}

class FootRootMotionTest : public ::testing::Test {
protected:
    Skeleton sk = test::humanoid_skeleton_for();
    WalkRig rig = test::humanoid_rig(sk);
    MotionLibrary lib = make_motion_library(sk, rig, "h");
    std::array<int, 4> feet{rig.ankle[0], rig.ankle[1], rig.toe[0], rig.toe[1]};
};

// Per 1/60 s step of the result, the foot joint that supports (ankle or toe, the one nearest the lowest it comes, within
// 2 cm of it) does not move horizontally in model space: the root took its slide (exact but for float rounding, 1e-5 m allowed: the steps are
// the result's own keys, sampled where they were made). A walk, a foot always down, gets back the travel taken out
// (path within 1e-5 m; measured 4.8e-7); a run's flight is bridged at the last stance velocity: its speed within 3%
// and its path within 2 cm of the generated one's (regression guards; measured 0.8% and 1.5 cm).
TEST_F(FootRootMotionTest, InPlaceCycleGetsBackTheTravelItsFeetMake) {
    for (const size_t g : {size_t{2}, size_t{3}, size_t{6}}) {  // walk 1.10, walk 1.40, run 2.60
        const RawAnimation& gait = lib.gaits[g];
        FootRootMotionReport report;
        Result<RawAnimation> moved = root_motion_from_feet(in_place(gait), sk, feet, 0.5f, "test", 60.0f, &report);
        ASSERT_TRUE(moved.ok()) << moved.error().to_string();
        const AnimationClip made = build_clip(moved.value(), sk, ClipEncoding::Float32).value();
        const AnimationClip original = build_clip(gait, sk, ClipEncoding::Float32).value();
        const float keys = std::round(made.duration() * 60.0f);
        float path_error = 0.0f, slide = 0.0f;
        std::vector<std::array<glm::vec3, 4>> points;  // ankles and toes at every key
        std::array<float, 4> lowest{1e9f, 1e9f, 1e9f, 1e9f};
        const glm::vec3 made_start = test::clip_model_positions(made, sk, 0.0f)[0], start = test::clip_model_positions(original, sk, 0.0f)[0];
        for (int k = 0; k <= static_cast<int>(keys); ++k) {
            const float t = made.duration() * static_cast<float>(k) / keys;
            const std::vector<glm::vec3> p = test::clip_model_positions(made, sk, t), q = test::clip_model_positions(original, sk, t);
            points.emplace_back();
            for (size_t i = 0; i < 4; ++i) {
                points.back()[i] = p[static_cast<size_t>(feet[i])];
                lowest[i] = std::min(lowest[i], points.back()[i].y);
            }
            const glm::vec3 d = (p[0] - made_start) - (q[0] - start);
            path_error = std::max(path_error, glm::length(glm::vec2(d.x, d.z)));
        }
        for (size_t k = 1; k < points.size(); ++k) {
            size_t s = 0;
            float best = 1e9f;
            for (size_t i = 0; i < 4; ++i) {
                const float above = 0.5f * (points[k - 1][i].y + points[k][i].y) - lowest[i];
                if (above < best) best = above, s = i;
            }
            if (best > 0.02f) continue;  // in flight
            slide = std::max(slide, glm::length(glm::vec2(points[k][s].x - points[k - 1][s].x, points[k][s].z - points[k - 1][s].z)));
        }
        std::printf("[figure] %s in place: speed %.3f m/s found against %.3f, root path within %.2g m, supporting foot joint slides %.2g m a step, "
                    "flight %.0f%%\n",
                    gait.name.c_str(), static_cast<double>(report.speed), static_cast<double>(original.root_speed()),
                    static_cast<double>(path_error), static_cast<double>(slide), static_cast<double>(100.0f * report.flight_share));
        EXPECT_LE(slide, 1e-5f) << gait.name;
        if (report.flight_share == 0.0f) {
            // A walk always has a foot down, and the generated gait plants it: the travel taken out comes back exactly.
            EXPECT_LE(path_error, 1e-5f) << gait.name;
            EXPECT_NEAR(report.speed, original.root_speed(), 1e-4f) << gait.name;
        } else {
            // Through a run's flight the body keeps its last stance velocity, which the gait's does not quite.
            EXPECT_NEAR(report.speed, original.root_speed(), 0.03f * original.root_speed()) << gait.name;
            EXPECT_LE(path_error, 0.02f) << gait.name;
        }
    }
}

TEST_F(FootRootMotionTest, RefusesWhatIsNoInPlaceWalk) {
    auto message = [&](const RawAnimation& clip) {
        Result<RawAnimation> r = root_motion_from_feet(clip, sk, feet, 0.5f, "take.bvh");
        return r.ok() ? std::string("(made)") : r.error().to_string();
    };
    const RawAnimation& walk = lib.gaits[3];
    EXPECT_NE(message(walk).find("clip '" + walk.name + "' travels (1.4"), std::string::npos) << message(walk);
    EXPECT_NE(message(walk).find("it has root motion of its own"), std::string::npos);
    EXPECT_NE(message(walk).find("take.bvh"), std::string::npos);
    EXPECT_NE(message(lib.idle).find("its feet carry the body forward at"), std::string::npos) << message(lib.idle);
    const std::string back = message(reversed(in_place(walk)));
    EXPECT_NE(back.find("its feet carry the body forward at -1.4"), std::string::npos) << back;
    EXPECT_NE(back.find("a walk needs 0.50 m/s or more"), std::string::npos) << back;
    EXPECT_EQ(message(in_place(walk)), "(made)");  // the same walk in place is one
    const int none[] = {-1, -1};
    EXPECT_NE(root_motion_from_feet(in_place(walk), sk, none, 0.5f, "take.bvh").error().to_string().find("no foot joints"), std::string::npos);
}

}  // namespace
}  // namespace aloha
