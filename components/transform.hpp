// Plain data: where a character is and how it moves. No behaviour.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace aloha {

/// World placement of a character's root. Y is up, metres.
struct Transform {
    glm::vec3 position{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    float scale = 1.0f;
};

/// World-space linear velocity of the root (m/s).
struct Velocity {
    glm::vec3 linear{0.0f};
};

/// Bounding capsule/cylinder of a character around its root: used for frustum tests and
/// projected height. `height` is the standing height (m), `radius` the horizontal radius (m).
struct Bounds {
    float height = 1.8f;
    float radius = 0.4f;
};

/// Importance set by the scene (0 = background, 1 = hero).
struct Importance {
    float value = 0.5f;
};

}  // namespace aloha
