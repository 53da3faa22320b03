// A clip's root motion track and the ground motions it gives (see root_motion.hpp).
#include "systems/motion/root_motion.hpp"

#include "systems/motion/clip.hpp"
#include "systems/motion/sampling.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

namespace aloha {

namespace {

constexpr float kTwoPi = 6.28318530717958647692f;

// R(turn) about +Y applied to (x, z): glm::angleAxis(turn, +Y) * (x, 0, z).
glm::vec2 turned(const glm::vec2& xz, float turn) {
    const float c = std::cos(turn), s = std::sin(turn);
    return {xz.x * c + xz.y * s, -xz.x * s + xz.y * c};
}

// The turn about +Y of rotation `d` (the twist of its swing-twist split about +Y: d = swing * twist, the swing
// about a horizontal axis), in (-2 pi, 2 pi]; `fallback` when d is a half turn about a horizontal axis.
float turn_about_vertical(const glm::quat& d, float fallback) {
    if (!(std::hypot(d.y, d.w) > 1e-6f)) return fallback;
    return 2.0f * std::atan2(d.y, d.w);
}

}  // namespace

glm::vec3 GroundMotion::apply(const glm::vec3& p) const {
    const glm::vec2 q = turned({p.x, p.z}, turn) + offset;
    return {q.x, p.y, q.y};
}

glm::quat GroundMotion::rotation() const { return glm::angleAxis(turn, glm::vec3(0.0f, 1.0f, 0.0f)); }

GroundMotion GroundMotion::inverse() const { return {-turned(offset, -turn), -turn}; }

GroundMotion GroundMotion::after(const GroundMotion& first) const {
    return {turned(first.offset, turn) + offset, turn + first.turn};
}

GroundMotion GroundMotion::power(long long n) const {
    GroundMotion base = n < 0 ? inverse() : *this;
    unsigned long long k = n < 0 ? 0ull - static_cast<unsigned long long>(n) : static_cast<unsigned long long>(n);
    GroundMotion out;
    while (k != 0) {
        if (k & 1ull) out = base.after(out);
        base = base.after(base);
        k >>= 1;
    }
    return out;
}

RootMotionTrack RootMotionTrack::build(std::span<const float> times, std::span<const glm::vec3> root_translations,
                                       std::span<const glm::quat> root_rotations, int joint, float inverse_spacing) {
    assert(times.size() == root_translations.size() && times.size() == root_rotations.size());
    RootMotionTrack track;
    track.joint_ = joint;
    if (times.empty()) return track;
    track.inverse_spacing_ = times.size() >= 2 ? inverse_spacing : 0.0f;
    track.times_.assign(times.begin(), times.end());
    track.keys_.resize(times.size());
    const glm::quat start_inverse = glm::inverse(root_rotations[0]);
    const glm::vec2 start(root_translations[0].x, root_translations[0].z);
    float heading = 0.0f;
    for (size_t k = 0; k < times.size(); ++k) {
        const float raw = turn_about_vertical(root_rotations[k] * start_inverse, heading);
        // Unwrapped: the key's heading is the previous one plus the shortest turn to it.
        heading += std::remainder(raw - heading, kTwoPi);
        const glm::vec2 at(root_translations[k].x, root_translations[k].z);
        track.keys_[k] = glm::vec3(at, k == 0 ? 0.0f : heading);
        track.excursion_ = std::max(track.excursion_, glm::length(at - start));
    }
    track.moves_ = times.size() >= 2 && (track.excursion_ >= kRootMotionMinTravel || std::abs(track.net_turn()) >= kRootMotionMinTurn);
    return track;
}

float RootMotionTrack::net_travel() const {
    return keys_.empty() ? 0.0f : glm::length(glm::vec2(keys_.back()) - glm::vec2(keys_.front()));
}

GroundMotion RootMotionTrack::at(float t) const {
    if (!moves_) return {};
    // The key segment holding t (clamped), then (x, z, heading) interpolated linearly.
    glm::vec3 key;
    if (!(t > times_.front())) {
        key = keys_.front();
    } else if (!(t < times_.back())) {
        key = keys_.back();
    } else if (inverse_spacing_ > 0.0f) {  // evenly spaced: the key by a multiply
        const float at_key = t * inverse_spacing_;
        const size_t i = std::min(static_cast<size_t>(at_key), keys_.size() - 2);
        const float a = std::clamp(at_key - static_cast<float>(i), 0.0f, 1.0f);
        key = keys_[i] * (1.0f - a) + keys_[i + 1] * a;
    } else {
        const size_t i = static_cast<size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()) - 1;
        const float a = (t - times_[i]) / (times_[i + 1] - times_[i]);
        key = keys_[i] * (1.0f - a) + keys_[i + 1] * a;
    }
    const glm::vec2 h0(keys_.front().x, keys_.front().y);
    return {glm::vec2(key.x, key.y) - turned(h0, key.z), key.z};
}

GroundMotion RootMotionTrack::between(float t0, float t1, bool loop) const {
    if (!moves_) return {};
    const float d = duration();
    if (!loop || !(d > 0.0f)) return at(t0).inverse().after(at(t1));
    // F(n D + part) = F(D)^n F(part): only the repeats between the two times are composed, so a clock far into
    // its repeats loses no precision.
    auto split = [d](float t, double* repeats) {
        const double n = std::floor(static_cast<double>(t) / static_cast<double>(d));
        *repeats = n;
        return std::clamp(static_cast<float>(static_cast<double>(t) - n * static_cast<double>(d)), 0.0f, d);
    };
    double n0 = 0.0, n1 = 0.0;
    const float part0 = split(t0, &n0), part1 = split(t1, &n1);
    const auto repeats = static_cast<long long>(n1 - n0);
    if (repeats == 0) return at(part0).inverse().after(at(part1));  // most frames: no wrap between the two readings
    return at(part0).inverse().after(at(d).power(repeats).after(at(part1)));
}

RootMotionTrack measure_root_motion(const AnimationClip& clip, std::span<const int16_t> parents) {
    const auto n = static_cast<size_t>(clip.joint_count());
    assert(parents.size() == n && n > 0);
    // The candidates: joint 0, then down its largest subtree (descendant counts: parents precede children).
    std::vector<int> below(n, 1);
    for (size_t j = n; j-- > 1;)
        if (parents[j] >= 0) below[static_cast<size_t>(parents[j])] += below[j];
    std::vector<int> chain{0};
    while (static_cast<int>(chain.size()) <= kRootMotionSearchDepth) {
        int next = -1;
        for (size_t j = 1; j < n; ++j)
            if (parents[j] == chain.back() && (next < 0 || below[j] > below[static_cast<size_t>(next)])) next = static_cast<int>(j);
        if (next < 0) break;
        chain.push_back(next);
    }
    // Each candidate's model translation and rotation at every key (the last key as the segment before ends).
    const int last = clip.key_count() - 1;
    std::vector<glm::vec3> t(n), s(n);
    std::vector<glm::quat> r(n);
    std::vector<std::vector<glm::vec3>> at(chain.size(), std::vector<glm::vec3>(static_cast<size_t>(last) + 1));
    std::vector<std::vector<glm::quat>> turned_by(chain.size(), std::vector<glm::quat>(static_cast<size_t>(last) + 1));
    for (int k = 0; k <= last; ++k) {
        sample_blocks(clip, k < last ? k : std::max(last - 1, 0), k < last || last == 0 ? 0.0f : 1.0f, t.data(), r.data(), s.data());
        glm::mat4 model(1.0f);
        for (size_t c = 0; c < chain.size(); ++c) {
            const auto j = static_cast<size_t>(chain[c]);
            model = model * glm::translate(glm::mat4(1.0f), t[j]) * glm::mat4_cast(r[j]) * glm::scale(glm::mat4(1.0f), s[j]);
            at[c][static_cast<size_t>(k)] = glm::vec3(model[3]);
            glm::mat3 axes(model);
            for (int a = 0; a < 3; ++a) axes[a] = glm::normalize(axes[a]);  // scale off
            turned_by[c][static_cast<size_t>(k)] = glm::normalize(glm::quat_cast(axes));
        }
    }
    RootMotionTrack first;  // joint 0's, returned when no candidate moves (it does not either)
    for (size_t c = 0; c < chain.size(); ++c) {
        RootMotionTrack track = RootMotionTrack::build(clip.times(), at[c], turned_by[c], chain[c], clip.inverse_key_spacing());
        if (track.moves()) return track;
        if (c == 0) first = std::move(track);
    }
    return first;
}

void put_roots_in_place(const GroundMotion& in_place_from, std::span<const int16_t> parents, std::span<glm::vec3> translations,
                        std::span<glm::quat> rotations) {
    const glm::quat turn = in_place_from.rotation();
    for (size_t j = 0; j < parents.size() && j < translations.size() && j < rotations.size(); ++j) {
        if (parents[j] >= 0) continue;
        translations[j] = in_place_from.apply(translations[j]);
        rotations[j] = glm::normalize(turn * rotations[j]);
    }
}

}  // namespace aloha
