#include "systems/motion/clip.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

namespace {

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite4(const glm::quat& q) { return finite3(glm::vec3(q.x, q.y, q.z)) && std::isfinite(q.w); }

template <class T>
Status check_track(const RawTrack<T>& track, const std::string& clip, const std::string& where) {
    if (track.times.size() != track.values.size())
        return make_error(clip, where + ": " + std::to_string(track.times.size()) + " key times but " +
                                    std::to_string(track.values.size()) + " values");
    for (size_t k = 0; k < track.times.size(); ++k) {
        const float t = track.times[k];
        const std::string key = where + " key " + std::to_string(k);
        if (!std::isfinite(t) || t < 0.0f) return make_error(clip, key + ": time is negative or not finite");
        if (k > 0 && !(t > track.times[k - 1])) return make_error(clip, key + ": key times are not strictly increasing");
        if constexpr (std::is_same_v<T, glm::quat>) {
            if (!finite4(track.values[k])) return make_error(clip, key + ": rotation has a NaN or infinite value");
            if (glm::dot(track.values[k], track.values[k]) < 1e-12f) return make_error(clip, key + ": rotation quaternion is zero");
        } else {
            if (!finite3(track.values[k])) return make_error(clip, key + ": value has a NaN or infinite value");
        }
    }
    return {};
}

// Index i of the segment [times[i], times[i+1]] holding t, and the fraction along it (clamped).
void locate(const std::vector<float>& times, float t, size_t* i, float* alpha) {
    if (times.size() < 2 || t <= times.front()) { *i = 0; *alpha = 0.0f; return; }
    if (t >= times.back()) { *i = times.size() - 2; *alpha = 1.0f; return; }
    const auto it = std::upper_bound(times.begin(), times.end(), t);
    *i = static_cast<size_t>(it - times.begin()) - 1;
    *alpha = (t - times[*i]) / (times[*i + 1] - times[*i]);
}

glm::vec3 eval_vec(const RawTrack<glm::vec3>& track, float t, const glm::vec3& rest) {
    if (track.values.empty()) return rest;
    if (track.values.size() == 1) return track.values[0];
    size_t i = 0;
    float a = 0.0f;
    locate(track.times, t, &i, &a);
    if (a == 0.0f) return track.values[i];
    if (a == 1.0f) return track.values[i + 1];
    return track.values[i] * (1.0f - a) + track.values[i + 1] * a;
}

// `aligned` holds the track's keys normalised and hemisphere-aligned; returns the chord value.
glm::quat eval_rot(const std::vector<float>& times, const std::vector<glm::quat>& aligned, float t) {
    if (aligned.size() == 1) return aligned[0];
    size_t i = 0;
    float a = 0.0f;
    locate(times, t, &i, &a);
    if (a == 0.0f) return aligned[i];
    if (a == 1.0f) return aligned[i + 1];
    const glm::quat& p = aligned[i];
    const glm::quat& q = aligned[i + 1];
    return glm::quat(p.w * (1.0f - a) + q.w * a, p.x * (1.0f - a) + q.x * a, p.y * (1.0f - a) + q.y * a,
                     p.z * (1.0f - a) + q.z * a);
}

}  // namespace

float AnimationClip::root_speed() const {
    if (duration_ <= 0.0f) return 0.0f;
    const glm::vec2 d(root_end_.x - root_start_.x, root_end_.z - root_start_.z);
    return glm::length(d) / duration_;
}

Result<AnimationClip> build_clip(const RawAnimation& raw, const Skeleton& skeleton) {
    const size_t n = static_cast<size_t>(skeleton.joint_count());
    const std::string& clip_name = raw.name.empty() ? std::string("<unnamed clip>") : raw.name;
    if (n == 0) return make_error(clip_name, "skeleton has no joints");
    if (raw.tracks.size() > n)
        return make_error(clip_name, "clip has " + std::to_string(raw.tracks.size()) + " joint tracks but the skeleton has " +
                                         std::to_string(n) + " joints");
    // Validate every track and gather the union of key times.
    std::vector<float> times;
    for (size_t j = 0; j < raw.tracks.size(); ++j) {
        const RawJointTracks& tr = raw.tracks[j];
        const std::string where = "joint " + std::to_string(j) + " '" + skeleton.names()[j] + "'";
        if (Status s = check_track(tr.translations, clip_name, where + " translation"); !s) return s.error();
        if (Status s = check_track(tr.rotations, clip_name, where + " rotation"); !s) return s.error();
        if (Status s = check_track(tr.scales, clip_name, where + " scale"); !s) return s.error();
        times.insert(times.end(), tr.translations.times.begin(), tr.translations.times.end());
        times.insert(times.end(), tr.rotations.times.begin(), tr.rotations.times.end());
        times.insert(times.end(), tr.scales.times.begin(), tr.scales.times.end());
    }
    times.push_back(0.0f);
    std::sort(times.begin(), times.end());
    // Merge times closer than 1e-6 s (well below any capture rate) so float noise adds no keys.
    std::vector<float> merged;
    for (float t : times)
        if (merged.empty() || t - merged.back() > 1e-6f) merged.push_back(t);
    times.swap(merged);

    AnimationClip clip;
    clip.name_ = raw.name;
    clip.joints_ = static_cast<int>(n);
    clip.duration_ = times.back();
    // Uniform when every key lies within 1e-4 of a spacing of k * spacing (float capture times such as
    // k/120 s carry relative errors ~1e-7 of the clip time, far below this).
    if (times.size() >= 2) {
        const double dt = static_cast<double>(times.back()) / static_cast<double>(times.size() - 1);
        bool uniform = dt > 0.0;
        for (size_t k = 0; k < times.size() && uniform; ++k)
            uniform = std::abs(static_cast<double>(times[k]) - dt * static_cast<double>(k)) <= 1e-4 * dt;
        if (uniform) {
            clip.uniform_ = true;
            clip.spacing_ = static_cast<float>(dt);
            clip.inv_spacing_ = static_cast<float>(1.0 / dt);
        }
    } else {
        clip.uniform_ = true;  // one key: every time maps to key 0
    }

    // Normalised, hemisphere-aligned rotation keys per joint.
    std::vector<std::vector<glm::quat>> aligned(raw.tracks.size());
    for (size_t j = 0; j < raw.tracks.size(); ++j) {
        const auto& values = raw.tracks[j].rotations.values;
        auto& out = aligned[j];
        out.resize(values.size());
        for (size_t k = 0; k < values.size(); ++k) {
            glm::quat q = glm::normalize(values[k]);
            if (k > 0 && glm::dot(q, out[k - 1]) < 0.0f) q = -q;
            out[k] = q;
        }
    }

    const size_t stride = clip.block_floats();
    clip.times_ = times;
    clip.keys_.assign(times.size() * stride, 0.0f);
    const auto rest_t = skeleton.rest_translations();
    const auto rest_r = skeleton.rest_rotations();
    const auto rest_s = skeleton.rest_scales();
    for (size_t k = 0; k < times.size(); ++k) {
        float* b = clip.keys_.data() + k * stride;
        float* bt = b;
        float* bqx = b + 3 * n;
        float* bqy = bqx + n;
        float* bqz = bqy + n;
        float* bqw = bqz + n;
        float* bs = b + 7 * n;
        const float t = times[k];
        for (size_t j = 0; j < n; ++j) {
            const bool has = j < raw.tracks.size();
            const glm::vec3 tv = has ? eval_vec(raw.tracks[j].translations, t, rest_t[j]) : rest_t[j];
            const glm::vec3 sv = has ? eval_vec(raw.tracks[j].scales, t, rest_s[j]) : rest_s[j];
            glm::quat q = rest_r[j];
            if (has && !aligned[j].empty()) q = eval_rot(raw.tracks[j].rotations.times, aligned[j], t);
            bt[3 * j + 0] = tv.x;
            bt[3 * j + 1] = tv.y;
            bt[3 * j + 2] = tv.z;
            bqx[j] = q.x;
            bqy[j] = q.y;
            bqz[j] = q.z;
            bqw[j] = q.w;
            bs[3 * j + 0] = sv.x;
            bs[3 * j + 1] = sv.y;
            bs[3 * j + 2] = sv.z;
        }
    }
    const float* first = clip.keys_.data();
    const float* last = clip.keys_.data() + (times.size() - 1) * stride;
    clip.root_start_ = glm::vec3(first[0], first[1], first[2]);
    clip.root_end_ = glm::vec3(last[0], last[1], last[2]);
    return clip;
}

ClipId ClipLibrary::add(AnimationClip clip) {
    clips_.push_back(std::move(clip));
    return static_cast<ClipId>(clips_.size() - 1);
}

Result<ClipId> ClipLibrary::add(const RawAnimation& raw, const Skeleton& skeleton) {
    Result<AnimationClip> clip = build_clip(raw, skeleton);
    if (!clip) return clip.error();
    return add(std::move(clip).value());
}

const AnimationClip* ClipLibrary::find(ClipId id) const {
    return id < clips_.size() ? &clips_[id] : nullptr;
}

int ClipLibrary::find(const std::string& name) const {
    for (size_t i = 0; i < clips_.size(); ++i)
        if (clips_[i].name() == name) return static_cast<int>(i);
    return -1;
}

}  // namespace aloha
