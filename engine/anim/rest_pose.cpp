#include "engine/anim/rest_pose.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace aloha {

std::vector<glm::mat4> skeleton_rest_model(const Skeleton& skeleton) {
    const auto n = static_cast<size_t>(skeleton.joint_count());
    std::vector<glm::mat4> model(n);
    for (size_t j = 0; j < n; ++j) {
        const glm::mat4 local = glm::translate(glm::mat4(1.0f), skeleton.rest_translations()[j]) *
                                glm::mat4_cast(skeleton.rest_rotations()[j]) *
                                glm::scale(glm::mat4(1.0f), skeleton.rest_scales()[j]);
        const int p = skeleton.parents()[j];
        model[j] = p < 0 ? local : model[static_cast<size_t>(p)] * local;
    }
    return model;
}

glm::quat rotation_between(const glm::vec3& from, const glm::vec3& to) {
    const float d = glm::dot(from, to);
    if (d < -0.999999f) {
        glm::vec3 axis = glm::cross(glm::vec3(1, 0, 0), from);
        if (glm::dot(axis, axis) < 1e-8f) axis = glm::cross(glm::vec3(0, 1, 0), from);
        return glm::angleAxis(3.14159265f, glm::normalize(axis));
    }
    const glm::vec3 c = glm::cross(from, to);
    return glm::normalize(glm::quat(1.0f + d, c.x, c.y, c.z));
}

}  // namespace aloha
