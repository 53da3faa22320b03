#include "systems/geometry/muscle/muscle_retarget.hpp"

#include "engine/anim/rest_pose.hpp"

namespace aloha {

namespace {

// Anchor `a` (on canonical joint c) moved onto the target; returns the canonical joint or -1.
int retarget_anchor(MuscleAnchor& a, const Skeleton& target, const HumanoidMap& map, const CanonicalFit& fit,
                    const std::vector<glm::mat4>& rest) {
    const int c = canonical_index(a.joint);
    if (c < 0) return -1;
    const auto u = static_cast<size_t>(c);
    const int j = map.fold(c);
    glm::vec3 point = fit.position[u] + fit.alignment[u] * a.offset;
    if (fit.bone_child[u] >= 0) point += a.along * (fit.position[static_cast<size_t>(fit.bone_child[u])] - fit.position[u]);
    a.joint = target.names()[static_cast<size_t>(j)];
    a.along = 0.0f;
    a.offset = glm::vec3(glm::inverse(rest[static_cast<size_t>(j)]) * glm::vec4(point, 1.0f));
    return c;
}

}  // namespace

std::vector<MuscleDef> retarget_muscle_defs(std::span<const MuscleDef> defs, const Skeleton& target, const HumanoidMap& map,
                                            const CanonicalFit& fit) {
    const std::vector<glm::mat4> rest = skeleton_rest_model(target);
    std::vector<MuscleDef> out(defs.begin(), defs.end());
    for (MuscleDef& d : out) {
        const int c = retarget_anchor(d.origin, target, map, fit, rest);
        (void)retarget_anchor(d.insertion, target, map, fit, rest);
        if (c >= 0 && d.depth_axis != glm::vec3(0.0f)) {
            const glm::mat3 frame(rest[static_cast<size_t>(map.fold(c))]);
            d.depth_axis = glm::normalize(glm::inverse(frame) * (fit.alignment[static_cast<size_t>(c)] * d.depth_axis));
        }
    }
    return out;
}

}  // namespace aloha
