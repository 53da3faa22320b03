// Test helper: the walk request most motion tests use (straight along +Z, no cross-fade).
#pragma once

#include "components/motion.hpp"

namespace aloha::test {

/// A walk at `speed` m/s straight along `direction` (horizontal), started without a cross-fade.
inline MotionRequest straight_walk(float speed, glm::vec3 direction = glm::vec3(0.0f, 0.0f, 1.0f)) {
    MotionRequest walk;
    walk.kind = RequestKind::Walk;
    walk.speed = speed;
    walk.target = direction;
    walk.crossfade_s = 0.0f;
    return walk;
}

}  // namespace aloha::test
