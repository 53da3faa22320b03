// Exploratory: single dynamic walker skate.
#include "systems/motion/motion_metrics.hpp"
#include "tests/systems/motion/dynamic/two_walkers.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace aloha {
namespace {

TEST(DynamicSkate, Probe) {
    for (const float speed : {0.6f, 1.0f, 1.4f}) {
        test::TwoWalkers s(WalkMethod::Dynamic, WalkMethod::Kinematic, speed);
        const WalkRig rig = resolve_walk_rig(s.sk, "humanoid").value();
        std::vector<int> feet{rig.ankle[0], rig.ankle[1], rig.toe[0], rig.toe[1]};
        const std::vector<glm::vec3> off = sole_offsets(s.sk, feet);
        FootSkateMeter m[2];
        for (int f = 0; f < 600; ++f) {
            s.step();
            for (uint32_t c = 0; c < 2; ++c) {
                std::vector<glm::vec3> soles;
                for (size_t k = 0; k < feet.size(); ++k)
                    soles.push_back(s.xs[c].position + s.xs[c].rotation * glm::vec3(s.mc.poses().view(c).model[static_cast<size_t>(feet[k])] * glm::vec4(off[k], 1.0f)));
                if (f >= 60) m[c].add(soles, s.pelvis(c), test::TwoWalkers::kDt);
            }
            if (f % 60 == 0)
                std::printf("f %d pelvis dyn %.3f %.3f %.3f kin %.3f %.3f %.3f\n", f, s.pelvis(0).x, s.pelvis(0).y, s.pelvis(0).z,
                            s.pelvis(1).x, s.pelvis(1).y, s.pelvis(1).z);
        }
        std::printf("speed %.1f: dynamic %.2f mm/m (walked %.1f), kinematic %.2f mm/m, diverged %zu\n", speed,
                    m[0].mm_per_metre(), m[0].walked_m(), m[1].mm_per_metre(), s.dyn.diverged());
    }
}

}  // namespace
}  // namespace aloha
