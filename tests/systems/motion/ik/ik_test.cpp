// CCD and DLS: reachable targets, unreachable targets, orientation, DLS-vs-CCD convergence.
#include "systems/motion/ik/ccd.hpp"
#include "systems/motion/ik/dls.hpp"
#include "tests/systems/motion/ik/ik_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

using namespace aloha::ik;  // NOLINT

using test::PoseBuffers;

enum class Solver { Ccd, Dls };

IkResult solve(Solver s, const Skeleton& skel, std::span<const int> chain, PoseBuffers& pose, const IkTarget& t,
               const IkSettings& st, std::span<float> curve = {}) {
    return s == Solver::Ccd ? solve_ccd(skel, chain, pose.view(), t, st, curve)
                            : solve_dls(skel, chain, pose.view(), t, st, curve);
}

TEST(IkChain, BaseToEffectorOrEmpty) {
    const Skeleton skel = test::make_humanoid(false);
    const std::vector<int> arm = make_ik_chain(skel, skel.find("LeftShoulder"), skel.find("LeftWrist"));
    ASSERT_EQ(arm.size(), 3u);
    EXPECT_EQ(arm[0], skel.find("LeftShoulder"));
    EXPECT_EQ(arm[1], skel.find("LeftElbow"));
    EXPECT_EQ(arm[2], skel.find("LeftWrist"));
    EXPECT_TRUE(make_ik_chain(skel, skel.find("LeftWrist"), skel.find("LeftShoulder")).empty());
    EXPECT_TRUE(make_ik_chain(skel, skel.find("RightShoulder"), skel.find("LeftWrist")).empty());
    EXPECT_TRUE(make_ik_chain(skel, -1, 3).empty());
    EXPECT_EQ(make_ik_chain(skel, 3, 3).size(), 1u);
}

// Reachable targets (from random in-limit poses) are reached within the 1e-3 m tolerance, and the
// chain's model matrices stay consistent with its local rotations (float FK round-off ~1e-6 m).
// Returns how many of the reaches converged; with `require_all` every one must.
int expect_reaches(Solver s, bool limited, bool require_all) {
    const Skeleton skel = test::make_humanoid(limited);
    const auto reaches = test::make_reaches(skel, 12, 7u);
    int converged = 0;
    for (size_t i = 0; i < reaches.size(); ++i) {
        const auto& r = reaches[i];
        PoseBuffers pose = test::relaxed_pose(skel);
        IkTarget t;
        t.position = r.position;
        IkSettings st;
        st.max_iterations = 200;
        const float before = glm::length(matrix_position(pose.m[static_cast<size_t>(r.chain.back())]) - r.position);
        const IkResult res = solve(s, skel, r.chain, pose, t, st);
        converged += res.converged ? 1 : 0;
        if (require_all) {
            EXPECT_TRUE(res.converged) << "reach " << i << " error " << res.position_error;
            EXPECT_LE(res.position_error, 1e-3f) << "reach " << i;
        }
        EXPECT_LE(res.position_error, before);
        const glm::vec3 solved = matrix_position(pose.m[static_cast<size_t>(r.chain.back())]);
        test::compute_model(skel, pose);
        const glm::vec3 fk = matrix_position(pose.m[static_cast<size_t>(r.chain.back())]);
        EXPECT_LT(glm::length(fk - solved), 1e-5f);
        EXPECT_LE(glm::length(fk - r.position), res.position_error + 1e-5f);
    }
    return converged;
}

TEST(Ccd, ReachesArmAndLegTargetsFreeJoints) { expect_reaches(Solver::Ccd, false, true); }
// With limits CCD moves limited joints one Euler angle at a time and can stall in limit-induced
// local minima (a known CCD weakness); it must still converge on most reaches and never get worse.
TEST(Ccd, ReachesMostTargetsWithLimits) {
    const int converged = expect_reaches(Solver::Ccd, true, false);
    EXPECT_GE(converged, 36);  // of 48
    std::printf("CCD with limits: %d of 48 reaches within 1e-3 m\n", converged);
}
TEST(Dls, ReachesArmAndLegTargetsFreeJoints) { expect_reaches(Solver::Dls, false, true); }
TEST(Dls, ReachesArmAndLegTargetsWithLimits) { expect_reaches(Solver::Dls, true, true); }

// Unreachable targets: the arm ends straight toward the target, so the remaining distance is
// |target - shoulder| - chain length (to 1e-3 m); errors never grow after the first iterations
// (1e-6 m slack = float round-off on ~1 m quantities); nothing becomes NaN.
void expect_unreachable(Solver s) {
    const Skeleton skel = test::make_humanoid(true);
    const std::vector<int> chain = make_ik_chain(skel, skel.find("LeftShoulder"), skel.find("LeftWrist"));
    const float len = test::chain_length(skel, chain);
    const glm::vec3 dirs[] = {{1, 0, 0}, {0.6f, 0.8f, 0}, {0.3f, -0.2f, 0.9f}, {0.5f, 0.5f, -0.7f}, {0, -1, 0}};
    for (const glm::vec3& d : dirs) {
        PoseBuffers pose = test::relaxed_pose(skel);
        // Start bent so the solver has work to do.
        pose.r[static_cast<size_t>(chain[1])] = glm::angleAxis(1.0f, glm::vec3(0, 0, 1));
        test::compute_model(skel, pose);
        const glm::vec3 base = matrix_position(pose.m[static_cast<size_t>(chain[0])]);
        IkTarget t;
        t.position = base + glm::normalize(d) * (len + 0.3f);
        IkSettings st;
        st.max_iterations = 60;
        std::vector<float> curve(static_cast<size_t>(st.max_iterations), -1.0f);
        const IkResult res = solve(s, skel, chain, pose, t, st, curve);
        EXPECT_FALSE(res.converged);
        EXPECT_FALSE(std::isnan(res.position_error));
        EXPECT_NEAR(res.position_error, glm::length(t.position - base) - len, 1e-3f) << d.x << " " << d.y << " " << d.z;
        for (int k = 5; k + 1 < res.iterations; ++k)
            EXPECT_LE(curve[static_cast<size_t>(k + 1)], curve[static_cast<size_t>(k)] + 1e-6f) << "iteration " << k;
        // Settled: the last iterations change the error by less than 1e-5 m.
        EXPECT_LT(std::abs(curve[static_cast<size_t>(res.iterations - 1)] - curve[static_cast<size_t>(res.iterations - 2)]), 1e-5f);
        for (int j : chain) EXPECT_FALSE(std::isnan(pose.r[static_cast<size_t>(j)].w));
    }
}

TEST(Ccd, UnreachableEndsStraightWithoutOscillation) { expect_unreachable(Solver::Ccd); }
TEST(Dls, UnreachableEndsStraightWithoutOscillation) { expect_unreachable(Solver::Dls); }

// With orientation (eq. 11) on targets produced by in-limit poses (so position and orientation are
// jointly reachable): the orientation error drops below 0.05 rad (~3 degrees, the eye's threshold
// for a hand pose) and the position stays within 5 mm.
void expect_orientation(Solver s, bool limited) {
    const Skeleton skel = test::make_humanoid(limited);
    const auto reaches = test::make_reaches(skel, 6, 11u);
    for (size_t i = 0; i < reaches.size(); ++i) {
        const auto& r = reaches[i];
        PoseBuffers pose = test::relaxed_pose(skel);
        IkTarget t;
        t.position = r.position;
        t.orientation = r.orientation;
        t.use_orientation = true;
        IkSettings st;
        st.max_iterations = 200;
        st.tolerance = 1e-4f;
        const float before = rotation_angle_between(matrix_rotation(pose.m[static_cast<size_t>(r.chain.back())]), r.orientation);
        const IkResult res = solve(s, skel, r.chain, pose, t, st);
        EXPECT_LT(res.orientation_error, 0.05f) << "reach " << i << " started at " << before;
        EXPECT_LT(res.position_error, 5e-3f) << "reach " << i;
    }
}

TEST(Ccd, OrientationErrorReducedFreeJoints) { expect_orientation(Solver::Ccd, false); }
TEST(Dls, OrientationErrorReducedFreeJoints) { expect_orientation(Solver::Dls, false); }
TEST(Dls, OrientationErrorReducedWithLimits) { expect_orientation(Solver::Dls, true); }

// DLS converges faster: over the same reaches at 1e-4 m (free joints, so both converge), DLS
// needs fewer iterations in total.
TEST(Dls, FewerIterationsThanCcdAtHighAccuracy) {
    const Skeleton skel = test::make_humanoid(false);
    const auto reaches = test::make_reaches(skel, 10, 3u);
    int ccd_total = 0;
    int dls_total = 0;
    int dls_converged = 0;
    int ccd_converged = 0;
    for (const auto& r : reaches) {
        IkTarget t;
        t.position = r.position;
        IkSettings st;
        st.max_iterations = 5000;  // CCD's linear convergence needs many sweeps at 1e-4 m
        st.tolerance = 1e-4f;
        PoseBuffers a = test::relaxed_pose(skel);
        const IkResult c = solve_ccd(skel, r.chain, a.view(), t, st);
        ccd_total += c.iterations;
        ccd_converged += c.converged ? 1 : 0;
        PoseBuffers b = test::relaxed_pose(skel);
        const IkResult d = solve_dls(skel, r.chain, b.view(), t, st);
        dls_total += d.iterations;
        dls_converged += d.converged ? 1 : 0;
    }
    EXPECT_EQ(dls_converged, static_cast<int>(reaches.size()));
    EXPECT_EQ(ccd_converged, static_cast<int>(reaches.size()));
    EXPECT_LT(dls_total, ccd_total);
    std::printf("iterations to 1e-4 m over %zu reaches: CCD %d, DLS %d\n", reaches.size(), ccd_total, dls_total);
}

TEST(Ik, AlreadyAtTargetTakesNoIteration) {
    const Skeleton skel = test::make_humanoid(true);
    const std::vector<int> chain = make_ik_chain(skel, skel.find("LeftHip"), skel.find("LeftAnkle"));
    PoseBuffers pose = test::relaxed_pose(skel);
    IkTarget t;
    t.position = matrix_position(pose.m[static_cast<size_t>(chain.back())]);
    for (Solver s : {Solver::Ccd, Solver::Dls}) {
        const IkResult r = solve(s, skel, chain, pose, t, IkSettings{});
        EXPECT_EQ(r.iterations, 0);
        EXPECT_TRUE(r.converged);
    }
}

}  // namespace
}  // namespace aloha
