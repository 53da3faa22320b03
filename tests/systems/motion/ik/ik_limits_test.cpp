// Joint limits (Euler XYZ relative to rest) and the job forms' validation.
#include "systems/motion/ik/ccd.hpp"
#include "systems/motion/ik/dls.hpp"
#include "systems/motion/ik/joint_limits.hpp"
#include "tests/systems/motion/ik/ik_test_util.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

using namespace aloha::ik;  // NOLINT

using test::PoseBuffers;

// Euler round trip: float quaternion -> angles error is ~1e-6 rad away from gimbal lock.
TEST(JointLimits, EulerRoundTrip) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> d(-1.4f, 1.4f);
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 e(2.0f * d(rng), d(rng), 2.0f * d(rng));
        const glm::vec3 back = euler_xyz(quat_from_euler_xyz(e));
        EXPECT_NEAR(back.x, e.x, 2e-5f);
        EXPECT_NEAR(back.y, e.y, 2e-5f);
        EXPECT_NEAR(back.z, e.z, 2e-5f);
    }
}

TEST(JointLimits, ClampKeepsInsideAndLeavesFreeJoints) {
    const JointLimit limit{{-0.1f, -0.2f, 0.0f}, {0.1f, 0.2f, 2.0f}, true};
    const glm::quat rest = glm::angleAxis(0.3f, glm::normalize(glm::vec3(1, 1, 0)));
    const glm::quat local = rest * quat_from_euler_xyz({0.5f, -0.6f, 2.5f});
    const glm::vec3 e = relative_euler_xyz(rest, clamp_to_limit(limit, rest, local));
    EXPECT_NEAR(e.x, 0.1f, 1e-5f);
    EXPECT_NEAR(e.y, -0.2f, 1e-5f);
    EXPECT_NEAR(e.z, 2.0f, 1e-5f);
    const JointLimit free_joint{};
    const glm::quat out = clamp_to_limit(free_joint, rest, local);
    EXPECT_EQ(out, local);
}

// Limits hold at the end of every solve (to 1e-5 rad, the Euler round-trip error above), for
// reachable and unreachable targets, with and without orientation.
TEST(JointLimits, RespectedAfterCcdAndDls) {
    const Skeleton skel = test::make_humanoid(true);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> d(-1.5f, 1.5f);
    const char* chains[4][2] = {{"LeftShoulder", "LeftWrist"}, {"RightShoulder", "RightWrist"},
                                {"LeftHip", "LeftAnkle"}, {"RightHip", "RightAnkle"}};
    for (auto& c : chains) {
        const std::vector<int> chain = make_ik_chain(skel, skel.find(c[0]), skel.find(c[1]));
        for (int i = 0; i < 20; ++i) {
            IkTarget t;
            t.position = glm::vec3(d(rng), 1.0f + d(rng), d(rng));  // often unreachable or out of limits
            t.orientation = glm::normalize(glm::quat(d(rng), d(rng), d(rng), d(rng)));
            t.use_orientation = (i % 2) == 1;
            IkSettings st;
            st.max_iterations = 30;
            for (int solver = 0; solver < 2; ++solver) {
                PoseBuffers pose = test::relaxed_pose(skel);
                const IkResult r = solver == 0 ? solve_ccd(skel, chain, pose.view(), t, st)
                                               : solve_dls(skel, chain, pose.view(), t, st);
                EXPECT_FALSE(std::isnan(r.position_error));
                for (int j : chain) {
                    const auto u = static_cast<size_t>(j);
                    const JointLimit& l = skel.limits()[u];
                    const glm::vec3 e = relative_euler_xyz(skel.rest_rotations()[u], pose.r[u]);
                    for (int a = 0; a < 3; ++a) {
                        EXPECT_GE(e[a], l.min_angles[a] - 1e-5f) << skel.names()[u] << " axis " << a;
                        EXPECT_LE(e[a], l.max_angles[a] + 1e-5f) << skel.names()[u] << " axis " << a;
                    }
                }
            }
        }
    }
}

TEST(IkJobs, ValidateListsEveryFailureAndRunSolves) {
    const Skeleton skel = test::make_humanoid(true);
    PoseBuffers pose = test::relaxed_pose(skel);
    const std::vector<int> chain = make_ik_chain(skel, skel.find("LeftShoulder"), skel.find("LeftWrist"));
    IkResult result;
    CcdJob ccd{&skel, chain, pose.view(), IkTarget{}, IkSettings{}, {}, &result};
    ccd.target.position = matrix_position(pose.m[static_cast<size_t>(chain[2])]) + glm::vec3(-0.05f, 0.05f, 0.05f);
    ccd.settings.max_iterations = 100;
    std::vector<std::string> errors;
    EXPECT_TRUE(ccd.Validate(&errors));
    EXPECT_TRUE(errors.empty());
    ccd.Run();
    EXPECT_TRUE(result.converged);

    const std::vector<int> broken = {chain[0], chain[2], 999};
    DlsJob dls{&skel, broken, pose.view(), IkTarget{}, IkSettings{}, {}, nullptr};
    dls.pose.model = {};
    dls.settings.max_iterations = -1;
    errors.clear();
    EXPECT_FALSE(dls.Validate(&errors));
    // chain[1] not a child, chain[2] not a joint, model size, negative iterations.
    EXPECT_EQ(errors.size(), 4u);
    DlsJob null_skel{};
    EXPECT_FALSE(null_skel.Validate());
}

}  // namespace
}  // namespace aloha
