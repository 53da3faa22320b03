// The dynamic walker's stance feet stay planted (issue 15: skate <= 10 mm per metre walked at every
// animation level). The cause of its skate (docs/PERFORMANCE.md 'dynamic skate'): contacts on the foot
// joints stood the body below the gait, and leg motors tuned to their own subtree could not carry the
// body, which sank onto the balance aid; the feet, pressed with half the weight, slid under the
// friction limit while the aid dragged the pelvis along. Sole contacts and load-bearing leg gains
// (DynamicWalkSettings::contact_points, stance_gain) are checked here, and the old settings' skate
// is checked to be back if they are undone (so the test measures what it claims).
#include "systems/motion/dynamic/dynamic_hook.hpp"
#include "systems/motion/motion_metrics.hpp"
#include "tests/common/test_humanoid.hpp"
#include "tests/systems/motion/walk_request.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace aloha {
namespace {

constexpr float kDt = 1.0f / 60.0f;

// A dynamic walker (0) and the kinematic walk it tracks (1), the project humanoid of the plaza.
struct Walkers {
    Walkers(float speed, bool old_settings) : sk(test::humanoid_skeleton_for(HumanoidBody{1.75f, 0.5f})), mc(sk, clips, 2) {
        const WalkRig rig = test::humanoid_rig(sk);
        mc.set_walk_rig(rig);
        register_dynamic_walk_hook(mc, dyn);  // fills the sole contact points from the rig
        if (old_settings) {  // contacts on the joints near the ground, legs tuned to their subtree only
            dyn.settings.contact_points.clear();
            dyn.settings.stance_gain = 0.0f;
        }
        lods[0].walk = WalkMethod::Dynamic;
        lods[1].walk = WalkMethod::Kinematic;
        EXPECT_TRUE(mc.push_request(0, test::straight_walk(speed)));
        EXPECT_TRUE(mc.push_request(1, test::straight_walk(speed)));
        feet = {rig.ankle[0], rig.ankle[1], rig.toe[0], rig.toe[1]};
        soles = sole_offsets(sk, feet);
    }
    void step() { mc.update(kDt, lods, states, xs, vs); }
    glm::vec3 world(uint32_t c, const glm::vec3& p, int j) const {
        return xs[c].position + xs[c].rotation * glm::vec3(mc.poses().view(c).model[static_cast<size_t>(j)] * glm::vec4(p, 1.0f));
    }

    Skeleton sk;
    ClipLibrary clips;
    MotionController mc;
    DynamicHookContext dyn;
    std::vector<int> feet;
    std::vector<glm::vec3> soles;
    std::vector<AnimLod> lods{2};
    std::vector<MotionState> states{2};
    std::vector<Transform> xs{2};
    std::vector<Velocity> vs{2};
};

struct SkateFigures {
    float mm_per_m = 0.0f;   // the crowd meter's skate (systems/motion/motion_metrics.hpp)
    float foot_load = 0.0f;  // mean share of the body's weight the ground carries
};

SkateFigures walk(float speed, bool old_settings) {
    Walkers w(speed, old_settings);
    std::vector<glm::vec3> soles;
    std::vector<float> dts;
    float walked = 0.0f;
    glm::vec3 last_root(0.0f);
    double load = 0.0;
    const int frames = 360;  // 6 s
    for (int f = 0; f < frames; ++f) {
        w.step();
        for (size_t k = 0; k < w.feet.size(); ++k) soles.push_back(w.world(0, w.soles[k], w.feet[k]));
        const glm::vec3 root = w.world(0, glm::vec3(0.0f), 0);
        if (f > 0) walked += std::hypot(root.x - last_root.x, root.z - last_root.z);
        last_root = root;
        dts.push_back(f == 0 ? 0.0f : kDt);
        // Normal impulses of the last substep's contact rows (3 per touching point, normal first).
        const DynamicWalkState& st = w.dyn.characters[0].state;
        double normal = 0.0;
        for (size_t r = st.last_bilateral; r + 2 < st.last_rows; r += 3) normal += st.lambda[r];
        load += normal / (st.total_mass * 9.81 * kDt / st.settings.substeps);
        if (!old_settings) {
            EXPECT_EQ(w.dyn.diverged(), 0u);
        }
    }
    double skate = 0.0;
    for (const float d : contact_travel(soles, w.feet.size(), dts, ContactThresholds{})) skate += d;
    return {static_cast<float>(1000.0 * skate / walked), static_cast<float>(load / frames)};
}

TEST(DynamicSkate, StanceFeetStayPlanted) {
    for (const float speed : {0.6f, 1.0f, 1.4f}) {
        const SkateFigures now = walk(speed, false);
        std::printf("%.1f m/s: skate %.2f mm/m, ground carries %.2f of the weight\n", speed, now.mm_per_m, now.foot_load);
        // Issue 15's bar. Seen 2.3-3.9 mm/m (0.6-1.4 m/s).
        EXPECT_LE(now.mm_per_m, 10.0f) << speed << " m/s";
        // The legs carry the body (1 at rest; the gait's bob adds or removes a little): the balance aid
        // does not hold it up. Regression guard: seen 0.97-1.05; the old gains gave 0.51-0.62.
        EXPECT_GT(now.foot_load, 0.85f) << speed << " m/s";
        EXPECT_LT(now.foot_load, 1.2f) << speed << " m/s";
    }
}

TEST(DynamicSkate, OldSettingsSkate) {
    // Joint contacts and subtree-only gains: the skate the fix removed (seen 60-88 mm/m at 0.6-1.0 m/s).
    const SkateFigures old = walk(0.6f, true);
    std::printf("old settings, 0.6 m/s: skate %.2f mm/m, ground carries %.2f of the weight\n", old.mm_per_m, old.foot_load);
    EXPECT_GT(old.mm_per_m, 30.0f);
    EXPECT_LT(old.foot_load, 0.75f);
}

}  // namespace
}  // namespace aloha
