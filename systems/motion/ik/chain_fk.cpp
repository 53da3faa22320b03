#include "systems/motion/ik/chain_fk.hpp"

#include "engine/anim/rest_pose.hpp"

#include <algorithm>
#include <cmath>

namespace aloha::ik {

glm::quat matrix_rotation(const glm::mat4& m) {
    const glm::mat3 r(glm::normalize(glm::vec3(m[0])), glm::normalize(glm::vec3(m[1])),
                      glm::normalize(glm::vec3(m[2])));
    return glm::normalize(glm::quat_cast(r));
}

glm::mat4 parent_model(const Skeleton& skeleton, std::span<const glm::mat4> model, int joint) {
    const int p = skeleton.parents()[static_cast<size_t>(joint)];
    return p < 0 ? glm::mat4(1.0f) : model[static_cast<size_t>(p)];
}

void update_chain_model(const Skeleton& skeleton, std::span<const int> chain, const PoseView& pose, size_t first) {
    glm::mat4 m = parent_model(skeleton, pose.model, chain[first]);
    for (size_t k = first; k < chain.size(); ++k) {
        const auto j = static_cast<size_t>(chain[k]);
        m = m * trs_matrix(pose.translations[j], pose.rotations[j], pose.scales[j]);
        pose.model[j] = m;
    }
}

glm::quat shortest_arc(const glm::vec3& from, const glm::vec3& to) {
    const float lf = glm::length(from);
    const float lt = glm::length(to);
    if (lf < 1e-9f || lt < 1e-9f) return {1.0f, 0.0f, 0.0f, 0.0f};
    return rotation_between(from / lf, to / lt);
}

glm::vec3 rotation_vector(const glm::quat& q_in) {
    const glm::quat q = q_in.w < 0.0f ? -q_in : q_in;
    const glm::vec3 v(q.x, q.y, q.z);
    const float s = glm::length(v);
    if (s < 1e-12f) return glm::vec3(0.0f);
    const float angle = 2.0f * std::atan2(s, q.w);
    return v * (angle / s);
}

glm::quat quat_from_rotation_vector(const glm::vec3& v) {
    const float angle = glm::length(v);
    if (angle < 1e-6f) return glm::normalize(glm::quat(1.0f, 0.5f * v.x, 0.5f * v.y, 0.5f * v.z));
    return glm::angleAxis(angle, v / angle);
}

float rotation_angle_between(const glm::quat& a, const glm::quat& b) {
    const glm::quat d = glm::inverse(a) * b;
    const float s = glm::length(glm::vec3(d.x, d.y, d.z));
    return 2.0f * std::atan2(s, std::abs(d.w));
}

}  // namespace aloha::ik
