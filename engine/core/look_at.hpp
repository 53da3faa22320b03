// A camera's view matrix with world +Y up that stays defined for every direction, straight up and straight down
// included (glm::lookAt with +Y up divides by zero there and gives NaN: a top-down camera saw nothing).
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace aloha {

/// How close to vertical (|forward.y| of the unit view direction) a view must be for look_at_y_up() to stop using
/// +Y as its up hint: 1 - 1e-6, about 0.08 degrees off vertical, where the cross product with +Y still has a length
/// of 1.4e-3 and glm::lookAt's normalisation is exact to float precision.
inline constexpr float kVerticalViewCos = 1.0f - 1.0e-6f;

/// The up hint look_at_y_up() uses for the unit view direction `forward`: +Y, except looking (nearly) straight down,
/// where it is -Z (the limit of a camera tilted down from facing -Z: screen up is world -Z, screen right world +X),
/// or straight up, where it is +Z (the limit of tilting up from facing -Z).
[[nodiscard]] inline glm::vec3 view_up_hint(glm::vec3 forward) {
    if (forward.y <= -kVerticalViewCos) return {0.0f, 0.0f, -1.0f};
    if (forward.y >= kVerticalViewCos) return {0.0f, 0.0f, 1.0f};
    return {0.0f, 1.0f, 0.0f};
}

/// World -> camera (the camera looks down its -Z), as glm::lookAt(eye, target, +Y) wherever that is defined; looking
/// straight up or down, the up hint of view_up_hint(); `target` at `eye` (or not finite relative to it) looks along
/// -Z. Always returns a finite rotation-translation for finite `eye`.
[[nodiscard]] inline glm::mat4 look_at_y_up(glm::vec3 eye, glm::vec3 target) {
    glm::vec3 d = target - eye;
    const float len = glm::length(d);
    if (!(len > 1e-12f) || !std::isfinite(len)) d = {0.0f, 0.0f, -1.0f};
    else d /= len;
    return glm::lookAt(eye, eye + d, view_up_hint(d));
}

}  // namespace aloha
