// Closing a loop's seam with Hermite offsets at both ends (loop_seam.hpp).
#include "systems/motion/library/loop_seam.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace aloha {

namespace {

// The offset at key time t, from the seam's halved value difference `half` and halved velocity difference
// `half_rate`: over the last `w` seconds it grows from zero (with zero slope) to +half with slope +half_rate at the
// end; over the first `w` it starts at -half with slope -half_rate and fades to zero (with zero slope).
glm::vec3 offset_at(float t, float duration, float w, const glm::vec3& half, const glm::vec3& half_rate) {
    glm::vec3 o(0.0f);
    if (t >= duration - w) {
        const float s = std::clamp((t - (duration - w)) / w, 0.0f, 1.0f);
        o += (3.0f * s * s - 2.0f * s * s * s) * half + (s * s * s - s * s) * w * half_rate;  // h01, h11
    }
    if (t <= w) {
        const float s = std::clamp(t / w, 0.0f, 1.0f);
        o -= (2.0f * s * s * s - 3.0f * s * s + 1.0f) * half + (s * s * s - 2.0f * s * s + s) * w * half_rate;  // h00, h10
    }
    return o;
}

// Whether a track's keys run from the loop's start to its end with a step inside at each.
template <class T>
bool spans_loop(const RawTrack<T>& track, float duration) {
    constexpr float kEps = 1e-4f;
    const std::vector<float>& t = track.times;
    const size_t n = t.size();
    if (n < 3 || track.values.size() != n || std::abs(t.front()) >= kEps || std::abs(t.back() - duration) >= kEps) return false;
    for (size_t i = 1; i < n; ++i)
        if (!(t[i] > t[i - 1])) return false;
    return true;
}

// The share of a seam's velocity jump `jump` beyond `inside`, the largest jump between steps inside the loop: 0
// when the seam jolts no more than the motion does anyway.
float excess_share(const glm::vec3& jump, float inside) {
    const float j = glm::length(jump);
    return j > inside && j > 0.0f ? 1.0f - inside / j : 0.0f;
}

// A track's step from key a to key b as a vector: the values' difference, or the rotation vector between them.
struct VectorValues {
    const std::vector<glm::vec3>& v;
    glm::vec3 step(size_t a, size_t b) const { return v[b] - v[a]; }
};
struct RotationValues {
    const std::vector<glm::quat>& q;
    glm::vec3 step(size_t a, size_t b) const { return rotation_vector(q[b] * glm::inverse(q[a])); }
};

// First-difference velocities at the loop's two ends, and the largest jump between consecutive steps inside it.
template <class Values>
void own_rates(const Values& values, const std::vector<float>& t, glm::vec3& start, glm::vec3& end, float& inside) {
    const size_t n = t.size();
    const auto rate = [&](size_t a) { return values.step(a, a + 1) / (t[a + 1] - t[a]); };
    start = rate(0);
    end = rate(n - 2);
    inside = 0.0f;
    for (size_t i = 1; i + 1 < n; ++i) inside = std::max(inside, glm::length(rate(i) - rate(i - 1)));
}

// A track's velocities at the loop's two ends as the source take has them (SeamRates).
struct EndRates {
    glm::vec3 start, end;
};

// Closes a translation or scale track; `keep_travel` leaves the horizontal first-to-last difference (the root's walk);
// velocities are matched only with `match_rate`, to `rates` when given.
float close_vector_track(RawTrack<glm::vec3>& track, float duration, float w, bool keep_travel, bool match_rate, const std::optional<EndRates>& rates) {
    if (!spans_loop(track, duration)) return 0.0f;
    std::vector<glm::vec3>& v = track.values;
    glm::vec3 diff = v.front() - v.back();
    if (keep_travel) diff.x = diff.z = 0.0f;
    glm::vec3 half_rate(0.0f);
    if (match_rate && rates) {
        half_rate = 0.5f * (rates->start - rates->end);
    } else if (match_rate) {
        glm::vec3 start, end;
        float inside = 0.0f;
        own_rates(VectorValues{v}, track.times, start, end, inside);
        half_rate = 0.5f * excess_share(start - end, inside) * (start - end);
    }
    const glm::vec3 half = 0.5f * diff;
    float largest = 0.0f;
    for (size_t i = 0; i < v.size(); ++i) {
        const glm::vec3 o = offset_at(track.times[i], duration, w, half, half_rate);
        v[i] += o;
        largest = std::max(largest, glm::length(o));
    }
    return largest;
}

float close_rotation_track(RawTrack<glm::quat>& track, float duration, float w, const std::optional<EndRates>& rates) {
    if (!spans_loop(track, duration)) return 0.0f;
    std::vector<glm::quat>& q = track.values;
    // Rotations as left (parent-space) differences: the first key is exp(diff) times the last.
    const glm::vec3 half = 0.5f * rotation_vector(q.front() * glm::inverse(q.back()));
    glm::vec3 start, end;
    float share = 1.0f;
    if (rates) {
        start = rates->start, end = rates->end;
    } else {
        float inside = 0.0f;
        own_rates(RotationValues{q}, track.times, start, end, inside);
        share = excess_share(start - end, inside);
    }
    // Each end's angular velocity turns with the offset put on that end (left multiplication), so the velocities are
    // matched as they will be after it: equal to second order in the seam's difference.
    const glm::vec3 half_rate = 0.5f * share * (from_rotation_vector(-half) * start - from_rotation_vector(half) * end);
    float largest = 0.0f;
    for (size_t i = 0; i < q.size(); ++i) {
        const glm::vec3 o = offset_at(track.times[i], duration, w, half, half_rate);
        if (o == glm::vec3(0.0f)) continue;
        q[i] = glm::normalize(from_rotation_vector(o) * q[i]);
        largest = std::max(largest, glm::length(o));
    }
    return largest;
}

// Joint j's velocities at both ends from a start and an end list, or none when either lacks it.
std::optional<EndRates> end_rates(const std::vector<glm::vec3>& start, const std::vector<glm::vec3>& end, size_t j) {
    if (j >= start.size() || j >= end.size()) return std::nullopt;
    return EndRates{start[j], end[j]};
}

}  // namespace

glm::vec3 rotation_vector(glm::quat q) {
    if (q.w < 0.0f) q = -q;
    const glm::vec3 v(q.x, q.y, q.z);
    const float s = glm::length(v);
    return s < 1e-8f ? 2.0f * v : v * (2.0f * std::atan2(s, q.w) / s);
}

glm::quat from_rotation_vector(const glm::vec3& r) {
    const float angle = glm::length(r);
    return angle < 1e-9f ? glm::quat(1, 0, 0, 0) : glm::angleAxis(angle, r / angle);
}

float seam_bend(float pose_error, float velocity_error, float window) {
    return 0.5f * pose_error + (4.0f / 27.0f) * 0.5f * velocity_error * window;
}

SeamClosing close_loop_seam(RawAnimation& loop, const SeamRates* rates, float window) {
    SeamClosing out;
    const float duration = loop.duration;
    if (!(duration > 0.0f) || !(window > 0.0f)) return out;
    const float w = std::min(window, 0.5f * duration);
    for (size_t j = 0; j < loop.tracks.size(); ++j) {
        RawJointTracks& tracks = loop.tracks[j];
        const std::optional<EndRates> turning = rates ? end_rates(rates->rotation_start, rates->rotation_end, j) : std::nullopt;
        const std::optional<EndRates> moving = rates ? end_rates(rates->translation_start, rates->translation_end, j) : std::nullopt;
        out.max_rotation = std::max(out.max_rotation, close_rotation_track(tracks.rotations, duration, w, turning));
        out.max_translation = std::max(out.max_translation, close_vector_track(tracks.translations, duration, w, j == 0, true, moving));
        close_vector_track(tracks.scales, duration, w, false, false, std::nullopt);
    }
    return out;
}

}  // namespace aloha
