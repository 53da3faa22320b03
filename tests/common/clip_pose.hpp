// Test helper: every joint's model position in a built clip at one time, sampled and chained to model space as the
// motion system does (sample_blocks, local_to_model).
#pragma once

#include "engine/anim/skeleton.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/sampling.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <vector>

namespace aloha::test {

/// Model positions of every joint of `sk` in `clip` at time `t` (clamped into the clip by find_key's caller's
/// contract: 0 <= t <= duration).
inline std::vector<glm::vec3> clip_model_positions(const AnimationClip& clip, const Skeleton& sk, float t) {
    const size_t n = static_cast<size_t>(sk.joint_count());
    std::vector<glm::vec3> tr(n), sc(n), pos(n);
    std::vector<glm::quat> ro(n);
    std::vector<glm::mat4> model(n);
    int k = 0;
    float a = 0.0f;
    find_key(clip, t, nullptr, &k, &a);
    sample_blocks(clip, k, a, tr.data(), ro.data(), sc.data());
    local_to_model(sk.parents().data(), tr.data(), ro.data(), sc.data(), nullptr, model.data(), n);
    for (size_t j = 0; j < n; ++j) pos[j] = glm::vec3(model[j][3]);
    return pos;
}

}  // namespace aloha::test
