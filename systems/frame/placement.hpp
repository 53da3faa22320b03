// A character's placement as a matrix: what every draw item, overlay and world-space export uses.
#pragma once

#include "components/transform.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace aloha {

/// World matrix of a character's root placement: translation * rotation * uniform Transform::scale.
inline glm::mat4 world_matrix(const Transform& t) {
    return glm::scale(glm::translate(glm::mat4(1.0f), t.position) * glm::mat4_cast(t.rotation), glm::vec3(t.scale));
}

/// World matrix of the renderer's unit box [-0.5, 0.5]^3 (ProxyInstance::model) for a proxy box `box` (the
/// geometric controller's, mapping [-1, 1]^3, character space) of a character placed at `world`.
inline glm::mat4 proxy_box_matrix(const glm::mat4& world, const glm::mat4& box) {
    return world * box * glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
}

}  // namespace aloha
