// Local-to-model, blending and the batched pose pool job.
#include "systems/motion/blend.hpp"
#include "systems/motion/clip_quant.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/pose_pool.hpp"
#include "tests/systems/motion/motion_test_util.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <utility>

namespace aloha {
namespace {

void expect_vec_near(const glm::vec3& a, const glm::vec3& b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(LocalToModel, HandComputedThreeJointChain) {
    const int16_t parents[3] = {-1, 0, 1};
    const glm::quat rz = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
    const glm::vec3 t[3] = {{1, 0, 0}, {2, 0, 0}, {1, 0, 0}};
    const glm::quat r[3] = {rz, rz, glm::quat(1, 0, 0, 0)};
    const glm::vec3 s[3] = {{1, 1, 1}, {2, 2, 2}, {1, 1, 1}};
    const glm::mat4 root = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5));
    glm::mat4 model[3];
    LocalToModelJob job{parents, t, r, s, &root, model};
    ASSERT_TRUE(job.Validate());
    job.Run();
    // By hand: origin0 = (1,0,0); origin1 = R0*(2,0,0)+(1,0,0) = (1,2,0);
    // origin2 = origin1 + R0*R1*S1*(1,0,0) = (1,2,0) + (-2,0,0) = (-1,2,0); x axis of 2 = (-2,0,0).
    // The root adds z = 5. cos(90 deg) in float is ~4e-8, so errors stay below 1e-6 * 4 (largest value).
    const float tol = 4e-6f;
    expect_vec_near(glm::vec3(model[0][3]), {1, 0, 5}, tol);
    expect_vec_near(glm::vec3(model[1][3]), {1, 2, 5}, tol);
    expect_vec_near(glm::vec3(model[2][3]), {-1, 2, 5}, tol);
    expect_vec_near(glm::vec3(model[2][0]), {-2, 0, 0}, tol);
    expect_vec_near(glm::vec3(model[1][1]), {0, -2, 0}, tol);  // y axis of 1: R0*R1*(0,2,0), 180 deg about z
    EXPECT_FLOAT_EQ(model[2][3][3], 1.0f);
    // compose_trs matches GLM's reference construction.
    const glm::mat4 ref = glm::translate(glm::mat4(1.0f), t[1]) * glm::mat4_cast(r[1]) * glm::scale(glm::mat4(1.0f), s[1]);
    const glm::mat4 got = compose_trs(t[1], r[1], s[1]);
    for (int c = 0; c < 4; ++c)
        for (int k = 0; k < 4; ++k) EXPECT_NEAR(got[c][k], ref[c][k], 1e-6f);
}

TEST(LocalToModel, ValidateRejectsChildBeforeParent) {
    const int16_t parents[2] = {1, -1};
    glm::vec3 t[2], s[2];
    glm::quat r[2];
    glm::mat4 m[1];
    LocalToModelJob job{parents, t, r, s, nullptr, m};
    std::vector<std::string> errors;
    EXPECT_FALSE(job.Validate(&errors));
    EXPECT_EQ(errors.size(), 2u);  // model too short + parent order
}

// The AVX2 local-to-model (chosen at run time) evaluates the portable loop's expressions in the same
// order, so the two must agree bit for bit: random trees (parents before children, several roots), random
// rotations (some not normalised, some with zero components), signed and zero scales, a general root
// matrix (non-zero last row), and 1-5, 8, 9, 64 and 200 joints (partial and full last chunks of 8, whose
// last joint is read exactly).
TEST(LocalToModel, Avx2MatchesPortableBits) {
    if (!clip_simd::avx2_available()) GTEST_SKIP() << "CPU has no AVX2: only the portable loop runs";
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-2.0f, 2.0f);
    auto pick = [&](float v) { return (rng() % 5 == 0) ? ((rng() % 2) ? 0.0f : -0.0f) : v; };
    glm::mat4 root;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) root[c][r] = u(rng);
    for (size_t n : {1u, 2u, 3u, 4u, 5u, 8u, 9u, 64u, 200u}) {
        std::vector<int16_t> parents(n);
        std::vector<glm::vec3> t(n), s(n);
        std::vector<glm::quat> r(n);
        for (size_t j = 0; j < n; ++j) {
            const size_t up = rng() % 2 ? j - 1 : rng() % std::max<size_t>(j, 1);  // chains and branches
            parents[j] = (j == 0 || rng() % 7 == 0) ? int16_t{-1} : static_cast<int16_t>(up);
            t[j] = glm::vec3(pick(u(rng)), pick(u(rng)), pick(u(rng)));
            s[j] = glm::vec3(pick(u(rng)), pick(u(rng)), pick(u(rng)));
            const glm::quat q(pick(u(rng)), pick(u(rng)), pick(u(rng)), pick(u(rng)));
            r[j] = rng() % 3 == 0 ? q : glm::normalize(q + glm::quat(1e-3f, 0.0f, 0.0f, 0.0f));
        }
        const glm::mat4* tops[2] = {nullptr, &root};
        for (const glm::mat4* top : tops) {
            std::vector<glm::mat4> fast(n), portable(n);
            local_to_model(parents.data(), t.data(), r.data(), s.data(), top, fast.data(), n, true);
            local_to_model(parents.data(), t.data(), r.data(), s.data(), top, portable.data(), n, false);
            EXPECT_EQ(std::memcmp(fast.data(), portable.data(), n * sizeof(glm::mat4)), 0)
                << n << " joints, root " << (top ? "general" : "identity");
        }
    }
}

// local_to_model_many (poses run in pairs joint by joint by the AVX2 form) gives every pose the bits of
// its own portable local_to_model call, for 1..7 poses (pairs and a single left over) of 1..70 joints.
TEST(LocalToModel, ManyPosesMatchOneCallEach) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-2.0f, 2.0f);
    for (size_t n : {1u, 7u, 8u, 9u, 70u}) {
        std::vector<int16_t> parents(n);
        for (size_t j = 0; j < n; ++j)
            parents[j] = j == 0 ? int16_t{-1} : static_cast<int16_t>(rng() % 2 ? j - 1 : rng() % j);
        for (size_t poses = 1; poses <= 7; ++poses) {
            std::vector<glm::vec3> t(n * poses), s(n * poses);
            std::vector<glm::quat> r(n * poses);
            for (size_t i = 0; i < n * poses; ++i) {
                t[i] = glm::vec3(u(rng), u(rng), u(rng));
                s[i] = glm::vec3(u(rng), u(rng), u(rng));
                r[i] = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)) + glm::quat(1e-3f, 0.0f, 0.0f, 0.0f));
            }
            std::vector<glm::mat4> many(n * poses), one(n * poses);
            std::vector<PosePointers> ptrs(poses);
            for (size_t c = 0; c < poses; ++c) {
                ptrs[c] = PosePointers{&t[c * n], &r[c * n], &s[c * n], &many[c * n]};
                local_to_model(parents.data(), &t[c * n], &r[c * n], &s[c * n], nullptr, &one[c * n], n, false);
            }
            local_to_model_many(parents.data(), ptrs.data(), poses, n);
            EXPECT_EQ(std::memcmp(many.data(), one.data(), n * poses * sizeof(glm::mat4)), 0)
                << poses << " poses of " << n << " joints";
        }
    }
}

TEST(Blend, WeightsZeroAndOneGiveTheInputsExactly) {
    const glm::vec3 at[2] = {{1, 2, 3}, {0.1f, 0.2f, 0.3f}}, bt[2] = {{-1, 5, 0}, {7, 8, 9}};
    const glm::quat ar[2] = {glm::angleAxis(0.3f, glm::vec3(1, 0, 0)), glm::angleAxis(1.0f, glm::vec3(0, 1, 0))};
    const glm::quat br[2] = {-glm::angleAxis(1.3f, glm::vec3(1, 0, 0)), glm::angleAxis(-1.0f, glm::vec3(0, 0, 1))};
    const glm::vec3 as[2] = {{1, 1, 1}, {2, 2, 2}}, bs[2] = {{3, 3, 3}, {1, 1, 1}};
    glm::vec3 ot[2], os[2];
    glm::quat orr[2];
    BlendJob job{at, ar, as, bt, br, bs, 0.0f, ot, orr, os};
    ASSERT_TRUE(job.Validate());
    job.Run();
    for (int j = 0; j < 2; ++j) {
        EXPECT_EQ(ot[j], at[j]);
        EXPECT_EQ(orr[j], ar[j]);
        EXPECT_EQ(os[j], as[j]);
    }
    job.weight = 1.0f;
    job.Run();
    for (int j = 0; j < 2; ++j) {
        EXPECT_EQ(ot[j], bt[j]);
        EXPECT_EQ(orr[j], br[j]);
        EXPECT_EQ(os[j], bs[j]);
    }
    // Half way, joint 0: br is the negated 1.3 rad rotation; the hemisphere fix blends 0.3 and 1.3
    // about the same axis, whose nlerp midpoint is exactly 0.8 rad (symmetric about the middle).
    job.weight = 0.5f;
    job.Run();
    EXPECT_NEAR(glm::angle(orr[0]), 0.8f, 1e-5f);
    expect_vec_near(ot[0], {0, 3.5f, 1.5f}, 1e-6f);
    job.weight = 1.5f;
    EXPECT_FALSE(job.Validate());
}

TEST(PosePool, BatchEqualsPerCharacterJobs) {
    const Skeleton sk = build_skeleton(test::make_humanoid64(), "h64").value();
    ASSERT_EQ(sk.joint_count(), 64);
    const AnimationClip clip = build_clip(test::make_wave_clip(sk, 61, 2.0f), sk).value();
    PosePool pool(64, 3, &sk);
    const float times[2] = {0.37f, 2.9f};
    const uint32_t slots[2] = {2, 0};
    SamplingCache caches[2];
    AnimateBatchJob batch{&clip, &sk, true, times, slots, caches, &pool};
    std::vector<std::string> errors;
    ASSERT_TRUE(batch.Validate(&errors));
    batch.Run();
    std::vector<glm::vec3> t(64), s(64);
    std::vector<glm::quat> r(64);
    std::vector<glm::mat4> m(64);
    for (int i = 0; i < 2; ++i) {
        SampleJob sj{&clip, times[i], true, nullptr, t, r, s};
        sj.Run();
        LocalToModelJob lj{sk.parents(), t, r, s, nullptr, m};
        lj.Run();
        const ConstPoseView v = std::as_const(pool).view(slots[i]);
        for (size_t j = 0; j < 64; ++j) EXPECT_EQ(v.model[j], m[j]);  // same code path: same bits
    }
    // Slot 1 was not in the batch: still the rest pose.
    EXPECT_EQ(pool.view(1).translations[5], sk.rest_translations()[5]);
    const uint32_t bad_slots[2] = {2, 7};
    batch.slots = bad_slots;
    EXPECT_FALSE(batch.Validate());
}

}  // namespace
}  // namespace aloha
