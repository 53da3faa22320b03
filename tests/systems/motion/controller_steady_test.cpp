// Phase 1's steady step (controller_steady.cpp) and its walk in element order: a crowd of looping clips,
// straight clip walks and reaches, in host arrays whose order changes as a regrouping host's does, gives
// the same bits with the steady step on as with every step the full one, and as in arrays that keep
// their order.
#include "systems/motion/ik/ik_hooks.hpp"
#include "tests/systems/motion/generated_gait_fixture.hpp"

#include <cstring>
#include <numeric>
#include <random>

namespace aloha {
namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr size_t kCount = 60;

using SteadyStep = test::GeneratedGait;

// One controller over host arrays in a changing element order (rows move with their character).
struct Crowd {
    MotionController mc;
    IkHookContext ik;
    std::vector<uint32_t> element;  // element of character c
    std::vector<AnimLod> lods{kCount};
    std::vector<MotionState> states{kCount};
    std::vector<Transform> xs{kCount};
    std::vector<Velocity> vs{kCount};
    std::vector<uint8_t> use;  // PoseUse per element

    Crowd(const Skeleton& sk, const WalkRig& rig, const ClipLibrary& clips, const std::vector<ClipId>& gaits, bool steady)
        : mc(sk, clips, kCount), element(kCount), use(kCount) {
        mc.set_walk_rig(rig);
        mc.set_walk_clips(gaits);
        register_ik_hooks(mc, ik);
        mc.set_steady_steps(steady);
        mc.set_step_block(7);  // phase 1 in several blocks
        std::iota(element.begin(), element.end(), 0u);
        std::shuffle(element.begin(), element.end(), std::mt19937(5));  // fixed seed
        for (uint32_t c = 0; c < kCount; ++c) {
            const uint32_t e = element[c];
            lods[e].walk = WalkMethod::ClipPlayback;
            lods[e].update_interval = static_cast<uint8_t>(1 + c % 4);
            use[e] = static_cast<uint8_t>(c % 3);  // unseen, posed at updates, every frame
            xs[e].position = glm::vec3(static_cast<float>(c % 8), 0.0f, static_cast<float>(c / 8));
            MotionRequest r;
            if (c % 3 == 0) {
                const float a = 0.1f * static_cast<float>(c);
                r = test::straight_walk(1.0f + 0.05f * static_cast<float>(c % 5), glm::vec3(std::sin(a), 0.0f, std::cos(a)));
            } else if (c % 3 == 1) {
                r.kind = RequestKind::PlayClip;
                r.clip = gaits[0];
                r.start_time = 0.01f * static_cast<float>(c);
                r.duration = c % 10 == 1 ? 0.5f : -1.0f;  // some end (then rest: the active set shrinks)
            } else {
                r.kind = RequestKind::Reach;
                r.effector = static_cast<int16_t>(sk.find(c % 2 ? "RightWrist" : "LeftWrist"));
                r.target = xs[e].position + glm::vec3(0.3f, 1.2f, 0.3f);
            }
            EXPECT_TRUE(mc.push_request(c, r));
        }
    }
    // Swaps the elements of characters a and b, moving their rows (what a regroup does).
    void swap(uint32_t a, uint32_t b) {
        const uint32_t ea = element[a], eb = element[b];
        std::swap(lods[ea], lods[eb]), std::swap(states[ea], states[eb]), std::swap(xs[ea], xs[eb]);
        std::swap(vs[ea], vs[eb]), std::swap(use[ea], use[eb]);
        std::swap(element[a], element[b]);
    }
    size_t step() {
        mc.set_pose_use(use);
        return mc.update_parallel(kDt, lods, states, xs, vs, element, 4);
    }
};

bool same_bits(const void* a, const void* b, size_t bytes) { return std::memcmp(a, b, bytes) == 0; }

TEST_F(SteadyStep, EqualsTheFullStepBitForBitWhileTheHostRegroups) {
    Crowd on(sk, rig, clips, gaits, true), off(sk, rig, clips, gaits, false), fixed(sk, rig, clips, gaits, true);
    std::mt19937 rng(11);  // fixed seed: the same regroups for both
    size_t steady_max = 0;
    for (int frame = 0; frame < 150; ++frame) {
        if (frame % 5 == 4) {  // a regroup: a few characters trade places
            for (int k = 0; k < 4; ++k) {
                const auto a = static_cast<uint32_t>(rng() % kCount), b = static_cast<uint32_t>(rng() % kCount);
                on.swap(a, b), off.swap(a, b);
            }
        }
        if (frame == 40) {  // the host turns a walker, changes a level and interrupts a reach
            for (Crowd* c : {&on, &off, &fixed}) {
                c->xs[c->element[3]].rotation = glm::angleAxis(1.0f, glm::vec3(0.0f, 1.0f, 0.0f));
                c->lods[c->element[6]].update_interval = 3;
                c->lods[c->element[9]].walk = WalkMethod::Kinematic;
                MotionRequest clip;
                clip.kind = RequestKind::PlayClip;
                clip.clip = gaits[0];
                EXPECT_TRUE(c->mc.interrupt(5, clip));
            }
        }
        const size_t posed = on.step();
        ASSERT_EQ(posed, off.step()) << "frame " << frame;
        ASSERT_EQ(posed, fixed.step()) << "frame " << frame;
        ASSERT_EQ(off.mc.steady_count(), 0u);
        steady_max = std::max(steady_max, on.mc.steady_count());
    }
    // Most of the crowd was stepped steadily, and some of it came to rest.
    EXPECT_GT(steady_max, kCount / 2);
    EXPECT_LT(on.mc.active().size(), kCount);
    const size_t joints = static_cast<size_t>(sk.joint_count());
    for (const Crowd* other : {&off, &fixed}) {
        for (uint32_t c = 0; c < kCount; ++c) {
            const ConstPoseView pa = on.mc.poses().view(c), pb = other->mc.poses().view(c);
            ASSERT_TRUE(same_bits(pa.model.data(), pb.model.data(), joints * sizeof(glm::mat4))) << "character " << c;
            const uint32_t e = on.element[c], f = other->element[c];
            ASSERT_TRUE(same_bits(&on.xs[e], &other->xs[f], sizeof(Transform))) << c;
            ASSERT_TRUE(same_bits(&on.vs[e], &other->vs[f], sizeof(Velocity))) << c;
            ASSERT_TRUE(same_bits(&on.states[e], &other->states[f], sizeof(MotionState))) << c;
            ASSERT_EQ(on.mc.stale(c), other->mc.stale(c)) << c;
        }
    }
    // The walkers really walked (root motion came from the steady step for most frames).
    EXPECT_GT(glm::length(on.xs[on.element[0]].position - glm::vec3(0.0f)), 1.0f);
}

}  // namespace
}  // namespace aloha
