#include "systems/motion/crowd_motion_meter.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace aloha {

namespace {

float horizontal(const glm::vec3& a, const glm::vec3& b) { return std::hypot(a.x - b.x, a.z - b.z); }

uint16_t key_of(uint8_t level, uint8_t interval) { return static_cast<uint16_t>(level << 8 | interval); }

float p95(std::vector<float> v) {
    if (v.empty()) return 0.0f;
    const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::ceil(0.95 * static_cast<double>(v.size()))) - 1);
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

}  // namespace

CrowdMotionMeter::CrowdMotionMeter(uint32_t characters) : tracks_(characters) {}

void CrowdMotionMeter::add(uint32_t c, std::span<const glm::vec3> joints, std::span<const glm::vec3> soles,
                           const glm::vec3& root, float dt, uint8_t level, uint8_t interval, MotionFrameKind kind) {
    assert(c < tracks_.size());
    Track& t = tracks_[c];
    const bool first = t.dts.empty();
    if (first) t.feet = soles.size();
    assert(soles.size() == t.feet && "CrowdMotionMeter: the same feet every frame");
    const uint16_t key = key_of(level, interval);
    t.soles.insert(t.soles.end(), soles.begin(), soles.end());
    t.dts.push_back(first ? 0.0f : dt);
    t.bucket.push_back(key);
    t.walked.push_back(first ? 0.0f : horizontal(root, t.last_root));
    t.last_root = root;
    if (!first && t.last_joints.size() == joints.size()) {
        float largest = 0.0f;
        for (size_t j = 0; j < joints.size(); ++j) largest = std::max(largest, glm::length(joints[j] - t.last_joints[j]));
        PopTally& p = pops_[key];
        if (kind == MotionFrameKind::Switch) {
            ++p.switches;
            p.worst_switch = std::max(p.worst_switch, largest);
        } else if (kind == MotionFrameKind::Transition) {
            ++p.transitions;
            p.worst_transition = std::max(p.worst_transition, largest);
        } else {
            p.ordinary.push_back(largest);
        }
    }
    t.last_joints.assign(joints.begin(), joints.end());
}

std::vector<MotionBucketFigures> CrowdMotionMeter::collect(const ContactThresholds& th, bool merged) const {
    std::map<uint16_t, MotionBucketFigures> out;
    auto bucket = [&](uint16_t key) -> MotionBucketFigures& {
        const uint16_t k = merged ? 0 : key;
        auto [it, fresh] = out.try_emplace(k);
        if (fresh) it->second.level = static_cast<uint8_t>(k >> 8), it->second.interval = static_cast<uint8_t>(k & 0xFF);
        return it->second;
    };
    for (const Track& t : tracks_) {
        const size_t frames = t.dts.size();
        for (size_t i = 0; i < frames; ++i) {
            MotionBucketFigures& b = bucket(t.bucket[i]);
            ++b.frames;
            b.walked_m += t.walked[i];
        }
        const std::vector<float> travel = contact_travel(t.soles, t.feet, t.dts, th);
        for (size_t i = 1; i < frames; ++i) bucket(t.bucket[i]).skate_m += travel[i];
    }
    std::map<uint16_t, std::vector<float>> ordinary;
    for (const auto& [key, p] : pops_) {
        MotionBucketFigures& b = bucket(key);
        b.switch_frames += p.switches;
        b.transition_frames += p.transitions;
        b.worst_switch_m = std::max(b.worst_switch_m, p.worst_switch);
        b.worst_transition_m = std::max(b.worst_transition_m, p.worst_transition);
        auto& o = ordinary[merged ? 0 : key];
        o.insert(o.end(), p.ordinary.begin(), p.ordinary.end());
    }
    for (auto& [key, o] : ordinary) {
        MotionBucketFigures& b = out[key];
        b.ordinary_p95_m = p95(o);
        b.ordinary_max_m = o.empty() ? 0.0f : *std::max_element(o.begin(), o.end());
    }
    std::vector<MotionBucketFigures> v;
    for (auto& [key, b] : out) v.push_back(b);
    return v;
}

std::vector<MotionBucketFigures> CrowdMotionMeter::buckets(const ContactThresholds& t) const { return collect(t, false); }

MotionBucketFigures CrowdMotionMeter::overall(const ContactThresholds& t) const {
    auto v = collect(t, true);
    return v.empty() ? MotionBucketFigures{} : v.front();
}

}  // namespace aloha
