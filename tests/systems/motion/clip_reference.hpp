// Double-precision reference sampling of a RawAnimation (the float source of a clip) for the clip
// tests: lerp of translation / scale keys, nlerp of hemisphere-aligned rotation keys, rest values
// for missing tracks, clamped outside a track's key range, and forward kinematics in double.
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/skeleton.hpp"
#include "systems/motion/clip.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace aloha::test {

/// Segment i and fraction a (double) of time t on `times` (clamped to the ends).
inline void ref_locate(const std::vector<float>& times, double t, size_t* i, double* a) {
    if (times.size() < 2 || t <= times.front()) { *i = 0; *a = 0.0; return; }
    if (t >= times.back()) { *i = times.size() - 2; *a = 1.0; return; }
    size_t k = 0;
    while (k + 2 < times.size() && static_cast<double>(times[k + 1]) <= t) ++k;
    *i = k;
    *a = (t - static_cast<double>(times[k])) / (static_cast<double>(times[k + 1]) - static_cast<double>(times[k]));
}

/// The source value of a vector track at time t (rest when the track is empty).
inline glm::dvec3 ref_vec(const RawTrack<glm::vec3>& track, double t, const glm::vec3& rest) {
    if (track.values.empty()) return glm::dvec3(rest);
    if (track.values.size() == 1) return glm::dvec3(track.values[0]);
    size_t i = 0;
    double a = 0.0;
    ref_locate(track.times, t, &i, &a);
    return glm::dvec3(track.values[i]) * (1.0 - a) + glm::dvec3(track.values[i + 1]) * a;
}

/// The source rotation at time t: keys normalised (in float, as build_clip does) and hemisphere-aligned,
/// chord in double, normalised in double. Rest rotation when the track is empty.
inline glm::dquat ref_rot(const RawTrack<glm::quat>& track, double t, const glm::quat& rest) {
    if (track.values.empty()) return glm::normalize(glm::dquat(rest));
    std::vector<glm::quat> k(track.values.size());
    for (size_t i = 0; i < k.size(); ++i) {
        k[i] = glm::normalize(track.values[i]);
        if (i > 0 && glm::dot(k[i], k[i - 1]) < 0.0f) k[i] = -k[i];
    }
    if (k.size() == 1) return glm::normalize(glm::dquat(k[0]));
    size_t i = 0;
    double a = 0.0;
    ref_locate(track.times, t, &i, &a);
    const glm::dquat p(k[i]), q(k[i + 1]);
    return glm::normalize(glm::dquat(p.w * (1 - a) + q.w * a, p.x * (1 - a) + q.x * a, p.y * (1 - a) + q.y * a,
                                     p.z * (1 - a) + q.z * a));
}

/// Rotation angle (radians) between a sampled rotation and a reference, robust near 0: the 4D chord
/// d between the unit quaternions (sign chosen) is 2 sin(phi / 2) for 4D angle phi, rotation angle 2 phi.
inline double rotation_angle(const glm::quat& sampled, const glm::dquat& ref) {
    const glm::dquat s = glm::normalize(glm::dquat(sampled));
    const glm::dquat r = glm::dot(s, ref) < 0.0 ? -ref : ref;
    const double d = std::sqrt((s.x - r.x) * (s.x - r.x) + (s.y - r.y) * (s.y - r.y) + (s.z - r.z) * (s.z - r.z) +
                               (s.w - r.w) * (s.w - r.w));
    return 4.0 * std::asin(std::min(1.0, d / 2.0));
}

/// Source local pose of every joint at time t (double).
struct RefPose {
    std::vector<glm::dvec3> t, s;
    std::vector<glm::dquat> r;
};

/// Evaluates `raw` for `skeleton` at time t.
inline RefPose ref_pose(const RawAnimation& raw, const Skeleton& sk, double t) {
    const size_t n = static_cast<size_t>(sk.joint_count());
    RefPose p;
    p.t.resize(n);
    p.r.resize(n);
    p.s.resize(n);
    for (size_t j = 0; j < n; ++j) {
        const bool has = j < raw.tracks.size();
        p.t[j] = has ? ref_vec(raw.tracks[j].translations, t, sk.rest_translations()[j]) : glm::dvec3(sk.rest_translations()[j]);
        p.s[j] = has ? ref_vec(raw.tracks[j].scales, t, sk.rest_scales()[j]) : glm::dvec3(sk.rest_scales()[j]);
        p.r[j] = has ? ref_rot(raw.tracks[j].rotations, t, sk.rest_rotations()[j]) : glm::normalize(glm::dquat(sk.rest_rotations()[j]));
    }
    return p;
}

/// Model matrices of a reference pose in double (parents before children, roots at the origin).
inline std::vector<glm::dmat4> ref_model(const RefPose& p, const Skeleton& sk) {
    std::vector<glm::dmat4> m(p.t.size());
    for (size_t j = 0; j < m.size(); ++j) {
        const glm::dmat4 local = glm::translate(glm::dmat4(1.0), p.t[j]) * glm::mat4_cast(p.r[j]) *
                                 glm::scale(glm::dmat4(1.0), p.s[j]);
        const int parent = sk.parents()[j];
        m[j] = parent < 0 ? local : m[static_cast<size_t>(parent)] * local;
    }
    return m;
}

/// The time the clip's segment k at fraction alpha stands for (double), so references are taken at
/// the (k, alpha) that sampling used, leaving find_key's float time-to-fraction rounding out.
inline double segment_time(const AnimationClip& clip, int k, float alpha) {
    const auto times = clip.times();
    if (clip.key_count() < 2) return 0.0;
    return static_cast<double>(times[static_cast<size_t>(k)]) +
           static_cast<double>(alpha) *
               (static_cast<double>(times[static_cast<size_t>(k) + 1]) - static_cast<double>(times[static_cast<size_t>(k)]));
}

}  // namespace aloha::test
