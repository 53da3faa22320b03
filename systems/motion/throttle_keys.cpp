#include "systems/motion/throttle_keys.hpp"

#include <algorithm>

namespace aloha {

ModelKey decompose_model(const glm::mat4& m) {
    const glm::vec3 s(glm::length(glm::vec3(m[0])), glm::length(glm::vec3(m[1])), glm::length(glm::vec3(m[2])));
    const glm::mat3 r{glm::vec3(m[0]) / s.x, glm::vec3(m[1]) / s.y, glm::vec3(m[2]) / s.z};
    return ModelKey{glm::normalize(glm::quat_cast(r)), glm::vec3(m[3]), s};
}

uint32_t ThrottleKeys::acquire() {
    ++used_;
    if (!free_.empty()) {
        const uint32_t s = free_.back();
        free_.pop_back();
        return s;
    }
    const uint32_t s = static_cast<uint32_t>(keys_.size() / (2 * joints_));
    keys_.resize(keys_.size() + 2 * joints_);
    return s;
}

void ThrottleKeys::release(uint32_t slot) {
    free_.push_back(slot);
    --used_;
}

void ThrottleKeys::capture(uint32_t slot, bool ahead, std::span<const glm::mat4> model) {
    ModelKey* out = keys_.data() + (2 * static_cast<size_t>(slot) + (ahead ? 1 : 0)) * joints_;
    for (size_t j = 0; j < joints_; ++j) out[j] = decompose_model(model[j]);
}

void ThrottleKeys::interpolate(uint32_t slot, float w, std::span<glm::mat4> model) const {
    const ModelKey* a = keys_.data() + 2 * static_cast<size_t>(slot) * joints_;
    const ModelKey* b = a + joints_;
    w = std::clamp(w, 0.0f, 1.0f);
    for (size_t j = 0; j < joints_; ++j) {
        const glm::quat qb = glm::dot(a[j].rotation, b[j].rotation) < 0.0f ? -b[j].rotation : b[j].rotation;
        const glm::quat q = glm::normalize(a[j].rotation * (1.0f - w) + qb * w);
        const glm::vec3 s = glm::mix(a[j].scale, b[j].scale, w);
        glm::mat4 m = glm::mat4_cast(q);
        m[0] *= s.x;
        m[1] *= s.y;
        m[2] *= s.z;
        m[3] = glm::vec4(glm::mix(a[j].position, b[j].position, w), 1.0f);
        model[j] = m;
    }
}

}  // namespace aloha
