#include "systems/motion/motion_metrics.hpp"

#include "systems/motion/local_to_model.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace aloha {

namespace {

float horizontal_distance(const glm::vec3& a, const glm::vec3& b) { return std::hypot(a.x - b.x, a.z - b.z); }

}  // namespace

std::vector<glm::vec3> sole_offsets(const Skeleton& skeleton, std::span<const int> feet) {
    const auto n = static_cast<size_t>(skeleton.joint_count());
    std::vector<glm::mat4> model(n);
    local_to_model(skeleton.parents().data(), skeleton.rest_translations().data(), skeleton.rest_rotations().data(),
                   skeleton.rest_scales().data(), nullptr, model.data(), n);
    float ground = INFINITY;
    for (const glm::mat4& m : model) ground = std::min(ground, m[3].y);
    std::vector<glm::vec3> out;
    out.reserve(feet.size());
    for (const int j : feet) {
        assert(j >= 0 && static_cast<size_t>(j) < n);
        const glm::mat4& m = model[static_cast<size_t>(j)];
        out.emplace_back(glm::inverse(m) * glm::vec4(m[3].x, ground, m[3].z, 1.0f));
    }
    return out;
}

void FootSkateMeter::add(std::span<const glm::vec3> feet, const glm::vec3& root, float dt) {
    if (dts_.empty()) {
        feet_ = feet.size();
        last_root_ = root;
    }
    assert(feet.size() == feet_ && "FootSkateMeter: the same feet every frame");
    positions_.insert(positions_.end(), feet.begin(), feet.end());
    dts_.push_back(dts_.empty() ? 0.0f : dt);
    walked_ += horizontal_distance(root, last_root_);
    last_root_ = root;
}

std::vector<float> contact_travel(std::span<const glm::vec3> soles, size_t feet, std::span<const float> dts,
                                  const ContactThresholds& t) {
    const size_t frames = dts.size();
    assert(soles.size() == frames * feet);
    std::vector<float> travel(frames, 0.0f);
    for (size_t f = 0; f < feet; ++f) {
        float lowest = INFINITY;
        for (size_t i = 0; i < frames; ++i) lowest = std::min(lowest, soles[i * feet + f].y);
        // A step counts when the foot is low at both ends and moved slower than the contact speed.
        for (size_t i = 1; i < frames; ++i) {
            const glm::vec3& a = soles[(i - 1) * feet + f];
            const glm::vec3& b = soles[i * feet + f];
            if (a.y > lowest + t.height || b.y > lowest + t.height || !(dts[i] > 0.0f)) continue;
            const float d = horizontal_distance(a, b);
            if (d <= t.speed * dts[i]) travel[i] += d;
        }
    }
    return travel;
}

float FootSkateMeter::skate_m(const ContactThresholds& t) const {
    float total = 0.0f;
    for (const float d : contact_travel(positions_, feet_, dts_, t)) total += d;
    return total;
}

float FootSkateMeter::mm_per_metre(const ContactThresholds& t) const {
    return walked_ >= 0.01f ? 1000.0f * skate_m(t) / walked_ : 0.0f;
}

void PopMeter::add(std::span<const glm::vec3> joints, bool switch_frame) {
    if (last_.size() == joints.size()) {
        float largest = 0.0f;
        for (size_t j = 0; j < joints.size(); ++j) largest = std::max(largest, glm::length(joints[j] - last_[j]));
        if (switch_frame) {
            worst_switch_ = std::max(worst_switch_, largest);
            ++switches_;
        } else {
            ordinary_.push_back(largest);
        }
    }
    last_.assign(joints.begin(), joints.end());
}

float PopMeter::ordinary_max() const {
    return ordinary_.empty() ? 0.0f : *std::max_element(ordinary_.begin(), ordinary_.end());
}

float PopMeter::ordinary_p95() const {
    if (ordinary_.empty()) return 0.0f;
    std::vector<float> sorted = ordinary_;
    const size_t k = std::min(sorted.size() - 1, static_cast<size_t>(std::ceil(0.95 * static_cast<double>(sorted.size()))) - 1);
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(k), sorted.end());
    return sorted[k];
}

}  // namespace aloha
