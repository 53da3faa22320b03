// Motion controller integration: arrays in a host order (element_of_character), parallel chunked
// evaluation equal to the serial one bit for bit, throttled updates spread over their interval.
#include "tests/systems/motion/crowd_scene.hpp"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>

namespace aloha {
namespace {

constexpr float kDt = 1.0f / 60.0f;

// Host arrays for a scene, optionally in a shuffled element order.
struct Host {
    std::vector<uint32_t> element;  // element of character c (empty = identity)
    std::vector<AnimLod> lods;
    std::vector<MotionState> states;
    std::vector<Transform> xs;
    std::vector<Velocity> vs;
    Host(const test::CrowdScene& scene, std::vector<uint32_t> order)
        : element(std::move(order)), lods(scene.lods.size()), states(lods.size()), xs(lods.size()), vs(lods.size()) {
        for (size_t c = 0; c < lods.size(); ++c) {
            const size_t e = element.empty() ? c : element[c];
            lods[e] = scene.lods[c];
            xs[e].position = glm::vec3(static_cast<float>(c % 10), 0.0f, static_cast<float>(c / 10));
        }
    }
    size_t element_of(size_t c) const { return element.empty() ? c : element[c]; }
};

bool same_bits(const void* a, const void* b, size_t bytes) { return std::memcmp(a, b, bytes) == 0; }

// Every pose slot, character state, transform and velocity equal bit for bit.
void expect_identical(const test::CrowdScene& a, const Host& ha, const test::CrowdScene& b, const Host& hb) {
    const size_t joints = static_cast<size_t>(a.sk.joint_count());
    for (size_t c = 0; c < a.lods.size(); ++c) {
        const ConstPoseView pa = a.mc->poses().view(c), pb = b.mc->poses().view(c);
        ASSERT_TRUE(same_bits(pa.rotations.data(), pb.rotations.data(), joints * sizeof(glm::quat))) << "character " << c;
        ASSERT_TRUE(same_bits(pa.translations.data(), pb.translations.data(), joints * sizeof(glm::vec3))) << c;
        ASSERT_TRUE(same_bits(pa.model.data(), pb.model.data(), joints * sizeof(glm::mat4))) << c;
        const size_t ea = ha.element_of(c), eb = hb.element_of(c);
        ASSERT_TRUE(same_bits(&ha.xs[ea], &hb.xs[eb], sizeof(Transform))) << c;
        ASSERT_TRUE(same_bits(&ha.vs[ea], &hb.vs[eb], sizeof(Velocity))) << c;
        ASSERT_EQ(ha.states[ea].frames_since_update, hb.states[eb].frames_since_update) << c;
        ASSERT_EQ(ha.states[ea].time, hb.states[eb].time) << c;
        ASSERT_EQ(ha.states[ea].active, hb.states[eb].active) << c;
    }
}

TEST(MotionIntegration, ShuffledHostArraysGiveIdenticalPoses) {
    constexpr size_t kCount = 48;
    test::CrowdScene a(kCount), b(kCount);
    std::vector<uint32_t> order(kCount);
    std::iota(order.begin(), order.end(), 0u);
    std::mt19937 rng(7);  // fixed seed: deterministic shuffle
    std::shuffle(order.begin(), order.end(), rng);
    Host ha(a, {}), hb(b, order);
    for (int frame = 0; frame < 75; ++frame) {
        const size_t pa = a.mc->update(kDt, ha.lods, ha.states, ha.xs, ha.vs);
        MotionUpdateJob job{b.mc.get(), kDt, hb.lods, hb.states, hb.xs, hb.vs, hb.element};
        ASSERT_TRUE(job.Validate());
        ASSERT_EQ(job.Run(), pa);
    }
    expect_identical(a, ha, b, hb);
    // The scene really moved: walkers left their start and something was posed away from rest.
    EXPECT_GT(ha.xs[0].position.z, 0.5f);
}

TEST(MotionIntegration, ParallelChunksEqualSerialBitForBit) {
    constexpr size_t kCount = 64;
    // every 16th character walks dynamically: the dynamic and IK hooks run inside the chunks
    test::CrowdScene a(kCount, 16), b(kCount, 16), c(kCount, 16);
    std::vector<uint32_t> order(kCount);
    for (size_t i = 0; i < kCount; ++i) order[i] = static_cast<uint32_t>(kCount - 1 - i);  // reversed host order
    Host ha(a, {}), hb(b, order), hc(c, {});
    b.mc->set_step_block(5), c.mc->set_step_block(7);  // phase 1 in blocks too (default: 2048 characters)
    tbb::task_arena three(3);  // another thread count (oversubscribed on small machines: still correct)
    size_t posed_total = 0;
    for (int frame = 0; frame < 50; ++frame) {
        const size_t pa = a.mc->update(kDt, ha.lods, ha.states, ha.xs, ha.vs);
        const size_t pb = b.mc->update_parallel(kDt, hb.lods, hb.states, hb.xs, hb.vs, hb.element, 3);
        size_t pc = 0;
        three.execute([&] { pc = c.mc->update_parallel(kDt, hc.lods, hc.states, hc.xs, hc.vs, {}, 1); });
        ASSERT_EQ(pa, pb);
        ASSERT_EQ(pa, pc);
        posed_total += pa;
    }
    expect_identical(a, ha, b, hb);
    expect_identical(a, ha, c, hc);
    EXPECT_GT(b.dyn.simulated(), 0u);
    EXPECT_GE(c.mc->worker_slots(), 3u);  // one scratch pose per thread of the arena
    EXPECT_GT(posed_total, 50u * 3u);     // more due characters than one chunk: the work was split
}

TEST(MotionIntegration, ThrottledUpdatesAreSpreadOverTheInterval) {
    constexpr size_t kCount = 120;
    constexpr int kInterval = 4;
    test::CrowdScene scene(1);  // for the skeleton and clip only
    MotionController mc(scene.sk, scene.clips, kCount);
    std::vector<AnimLod> lods(kCount);
    std::vector<MotionState> states(kCount);
    std::vector<Transform> xs(kCount);
    std::vector<Velocity> vs(kCount);
    for (size_t c = 0; c < kCount; ++c) {
        lods[c].update_interval = kInterval;
        MotionRequest r;
        r.kind = RequestKind::PlayClip;
        r.clip = scene.wave;
        ASSERT_TRUE(mc.push_request(static_cast<uint32_t>(c), r));
    }
    // Frame 0 poses everyone (their requests start); afterwards ids spread over 4 phases, so
    // exactly kCount / kInterval characters are posed per frame and each every kInterval frames.
    EXPECT_EQ(mc.update(kDt, lods, states, xs, vs), kCount);
    std::vector<int> last(kCount, 0);
    for (int frame = 1; frame <= 24; ++frame) {
        EXPECT_EQ(mc.update(kDt, lods, states, xs, vs), kCount / kInterval) << "frame " << frame;
        for (size_t c = 0; c < kCount; ++c) {
            if (states[c].frames_since_update != 0) continue;
            if (frame > kInterval) {
                EXPECT_EQ(frame - last[c], kInterval) << "character " << c;
            }
            last[c] = frame;
        }
    }
}

TEST(MotionIntegration, JobValidatesTheElementMap) {
    test::CrowdScene scene(4);
    Host h(scene, {0, 1, 2, 2});
    MotionUpdateJob job{scene.mc.get(), kDt, h.lods, h.states, h.xs, h.vs, h.element};
    std::vector<std::string> errors;
    EXPECT_FALSE(job.Validate(&errors));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("element_of_character[3]"), std::string::npos);
    h.element = {0, 1, 9};
    job.element_of_character = h.element;
    errors.clear();
    EXPECT_FALSE(job.Validate(&errors));
    EXPECT_EQ(errors.size(), 1u);  // too short
    h.element = {3, 0, 1, 7};
    job.element_of_character = h.element;
    errors.clear();
    EXPECT_FALSE(job.Validate(&errors));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("out of range"), std::string::npos);
}

}  // namespace
}  // namespace aloha
