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

}  // namespace aloha
