// A pose: local joint transforms (structure of arrays) and model-space matrices for one character.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <span>

namespace aloha {

/// Non-owning view of one character's local pose (SoA) and its model-space matrices.
/// All spans have the skeleton's joint count.
struct PoseView {
    std::span<glm::vec3> translations;
    std::span<glm::quat> rotations;
    std::span<glm::vec3> scales;
    std::span<glm::mat4> model;  ///< model-space (character space) matrix of each joint
};

/// The local matrix T * R * S of a joint (translation `t`, unit rotation `r`, scale `s`).
[[nodiscard]] inline glm::mat4 trs_matrix(const glm::vec3& t, const glm::quat& r, const glm::vec3& s) {
    glm::mat4 m = glm::mat4_cast(r);
    m[0] *= s.x;
    m[1] *= s.y;
    m[2] *= s.z;
    m[3] = glm::vec4(t, 1.0f);
    return m;
}

/// Read-only counterpart of PoseView.
struct ConstPoseView {
    std::span<const glm::vec3> translations;
    std::span<const glm::quat> rotations;
    std::span<const glm::vec3> scales;
    std::span<const glm::mat4> model;
};

}  // namespace aloha
