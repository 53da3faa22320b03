// Test helper: every joint's model position in a built clip at one time (sampled as the motion system samples,
// then chained through the skeleton's parents with their scales).
#pragma once

#include "engine/anim/skeleton.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/sampling.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <vector>

namespace aloha::test {

/// Model positions of every joint of `sk` in `clip` at time `t` (clamped into the clip by find_key's caller's
/// contract: 0 <= t <= duration).
inline std::vector<glm::vec3> clip_model_positions(const AnimationClip& clip, const Skeleton& sk, float t) {
    const size_t n = static_cast<size_t>(sk.joint_count());
    std::vector<glm::vec3> tr(n), sc(n), pos(n), scale(n);
    std::vector<glm::quat> ro(n), model(n);
    int k = 0;
    float a = 0.0f;
    find_key(clip, t, nullptr, &k, &a);
    sample_blocks(clip, k, a, tr.data(), ro.data(), sc.data());
    for (size_t j = 0; j < n; ++j) {
        const int p = sk.parents()[j];
        if (p < 0) {
            model[j] = ro[j];
            pos[j] = tr[j];
            scale[j] = sc[j];
            continue;
        }
        const auto q = static_cast<size_t>(p);
        model[j] = model[q] * ro[j];
        pos[j] = pos[q] + model[q] * (scale[q] * tr[j]);
        scale[j] = scale[q] * sc[j];
    }
    return pos;
}

}  // namespace aloha::test
