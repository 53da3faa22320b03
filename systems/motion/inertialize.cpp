#include "systems/motion/inertialize.hpp"

#include "systems/motion/clip.hpp"
#include "systems/motion/throttle_keys.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

float inertial_weight(float elapsed, float total) {
    // 1 - smootherstep(t) = smootherstep(1 - t); each half uses the form whose polynomial is small
    // there, so the curve keeps full float precision (and stays monotone) at both ends.
    const float t = std::clamp(elapsed / total, 0.0f, 1.0f);
    const auto smootherstep = [](float x) { return x * x * x * (x * (x * 6.0f - 15.0f) + 10.0f); };
    return t < 0.5f ? 1.0f - smootherstep(t) : smootherstep(1.0f - t);
}

uint32_t InertialOffsets::acquire() {
    ++used_;
    if (!free_.empty()) {
        const uint32_t s = free_.back();
        free_.pop_back();
        return s;
    }
    const auto s = static_cast<uint32_t>(offsets_.size() / joints_);
    offsets_.resize(offsets_.size() + joints_);
    return s;
}

void InertialOffsets::release(uint32_t slot) {
    free_.push_back(slot);
    --used_;
}

void InertialOffsets::hold(uint32_t slot, const int16_t* parents, std::span<const glm::mat4> shown) {
    Offset* out = offsets_.data() + static_cast<size_t>(slot) * joints_;
    for (size_t j = 0; j < joints_; ++j) {
        const glm::mat4 local = parents[j] < 0 ? shown[j] : glm::inverse(shown[static_cast<size_t>(parents[j])]) * shown[j];
        const ModelKey k = decompose_model(local);
        out[j] = Offset{k.rotation, k.position, k.scale};
    }
}

void InertialOffsets::relate(uint32_t slot, const ConstPoseView& target) {
    Offset* out = offsets_.data() + static_cast<size_t>(slot) * joints_;
    for (size_t j = 0; j < joints_; ++j) {
        glm::quat q = glm::normalize(out[j].rotation * glm::inverse(target.rotations[j]));
        if (q.w < 0.0f) q = -q;
        out[j].rotation = q;
        out[j].translation -= target.translations[j];
        out[j].scale -= target.scales[j];
    }
}

void InertialOffsets::keep_root_travel(uint32_t slot) {
    if (joints_ == 0) return;
    Offset& root = offsets_[static_cast<size_t>(slot) * joints_];
    root.translation.x = root.translation.z = 0.0f;
    glm::quat q = without_turn_about_vertical(root.rotation);
    if (q.w < 0.0f) q = -q;
    root.rotation = q;
}

void InertialOffsets::apply(uint32_t slot, float weight, const PoseView& pose) const {
    if (weight <= 0.0f) return;
    const Offset* in = offsets_.data() + static_cast<size_t>(slot) * joints_;
    const glm::quat identity(1.0f, 0.0f, 0.0f, 0.0f);
    for (size_t j = 0; j < joints_; ++j) {
        pose.rotations[j] = glm::normalize(glm::slerp(identity, in[j].rotation, weight) * pose.rotations[j]);
        pose.translations[j] += weight * in[j].translation;
        pose.scales[j] += weight * in[j].scale;
    }
}

}  // namespace aloha
