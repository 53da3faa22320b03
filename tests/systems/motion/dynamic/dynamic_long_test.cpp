// Long runs of the dynamic walk: drift over 10,000 steps and 60 s of tracked, upright walking.
#include "systems/motion/dynamic/dynamic_walk.hpp"
#include "systems/motion/ik/chain_fk.hpp"
#include "tests/systems/motion/dynamic/walk_target.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace aloha {
namespace {

struct Runner {
    Skeleton skel = test::make_humanoid(true);
    test::PoseBuffers out = test::rest_pose(skel);
    std::vector<glm::quat> target = std::vector<glm::quat>(out.r.size());
    test::WalkParams walk;
    DynamicWalkState state;

    explicit Runner(const DynamicWalkSettings& settings) {
        const glm::vec3 root0 = test::walk_target(skel, 0.0f, walk, target);
        out.r = target;
        out.t[0] = root0;
        test::compute_model(skel, out);
        EXPECT_TRUE(init_dynamic_walk(skel, out.cview(), glm::mat4(1.0f), state, settings).ok());
    }
    glm::vec3 step(int i) {
        const glm::vec3 root = test::walk_target(skel, static_cast<float>(i) / 60.0f, walk, target);
        step_dynamic_walk(skel, target, root, 1.0f / 60.0f, state, out.view(), nullptr);
        return root;
    }
};

// 10,000 steps at 1/60 s (default 2 substeps): the largest joint separation ever seen stays
// under 1 mm (post-stabilisation keeps it near float round-off, ~1e-5 m).
TEST(DynamicWalkLong, DriftUnderOneMillimetreOver10000Steps) {
    Runner run(DynamicWalkSettings{});
    float worst = 0.0f;
    for (int i = 1; i <= 10000; ++i) {
        run.step(i);
        worst = std::max(worst, max_constraint_error(run.state));
        if (!std::isfinite(worst)) break;
    }
    EXPECT_LT(worst, 1e-3f);
    std::printf("max joint separation over 10000 steps: %.3g m\n", worst);
}

// 60 s of walking with default settings: upright, tracks the target, yet really simulated.
TEST(DynamicWalkLong, SixtySecondsUprightAndTracking) {
    Runner run(DynamicWalkSettings{});
    const int hips = run.skel.find("Hips");
    const int head = run.skel.find("Head");
    double angle_sum = 0.0;
    double root_err_sum = 0.0;
    float worst_tilt = 0.0f;
    float worst_root = 0.0f;
    float min_head_height = 1e9f;
    float worst_drift = 0.0f;
    bool finite = true;
    size_t samples = 0;
    const int steps = 3600;
    for (int i = 1; i <= steps; ++i) {
        const glm::vec3 root = run.step(i);
        const auto& m = run.out.m;
        const glm::vec3 up = glm::normalize(glm::vec3(m[static_cast<size_t>(hips)][1]));
        worst_tilt = std::max(worst_tilt, std::acos(std::clamp(up.y, -1.0f, 1.0f)));
        min_head_height = std::min(min_head_height, m[static_cast<size_t>(head)][3].y - m[static_cast<size_t>(hips)][3].y);
        const float root_err = glm::length(run.out.t[static_cast<size_t>(hips)] - root);
        worst_root = std::max(worst_root, root_err);
        root_err_sum += root_err;
        worst_drift = std::max(worst_drift, max_constraint_error(run.state));
        for (const DynamicBody& b : run.state.bodies) {
            const auto j = static_cast<size_t>(b.joint);
            finite = finite && std::isfinite(b.x.x + b.x.y + b.x.z + b.q.w);
            if (b.parent < 0) continue;
            angle_sum += ik::rotation_angle_between(run.out.r[j], run.target[j]);
            ++samples;
        }
        if (!finite) break;
    }
    const double mean_angle = angle_sum / static_cast<double>(samples);
    const double mean_root = root_err_sum / steps;
    std::printf("60 s walk: mean joint angle error %.4f rad, mean root error %.4f m (max %.4f), max tilt %.3f rad, "
                "min head-over-pelvis %.3f m, max drift %.3g m\n",
                mean_angle, mean_root, worst_root, worst_tilt, min_head_height, worst_drift);
    EXPECT_TRUE(finite);
    EXPECT_LT(worst_drift, 1e-3f);
    EXPECT_LT(worst_tilt, 0.5f);              // pelvis within ~29 degrees of vertical throughout
    EXPECT_GT(min_head_height, 0.3f);         // head stays well above the pelvis (rest: 0.56 m)
    EXPECT_GT(mean_angle, 0.01);              // really simulated: lags and deflects from the target
    EXPECT_LT(mean_angle, 0.25);              // but tracks it (gait amplitudes are 0.3-0.7 rad)
    EXPECT_LT(mean_root, 0.15);               // pelvis follows the root target (sag + lag)
    EXPECT_LT(worst_root, 0.3f);
}

}  // namespace
}  // namespace aloha
