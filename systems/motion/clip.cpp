#include "systems/motion/clip.hpp"

#include "systems/motion/clip_quant.hpp"
#include "systems/motion/sampling.hpp"

#include <algorithm>
#include <cassert>
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

size_t AnimationClip::byte_size() const {
    return times_.size() * sizeof(float) + qkeys_.size() * sizeof(uint16_t) + fkeys_.size() * sizeof(float) +
           (base_.size() + step_.size()) * sizeof(float) + (const_t_.size() + const_s_.size()) * sizeof(glm::vec3) +
           const_r_.size() * sizeof(glm::quat);
}

/// Turns dense float key values into an AnimationClip's key blocks (friend of AnimationClip).
struct ClipEncoder {
    /// Every joint's value at every key of the union timeline, index k * joints + j.
    struct Keys {
        size_t joints = 0;
        size_t count = 0;
        std::vector<glm::vec3> t;
        std::vector<glm::quat> r;
        std::vector<glm::vec3> s;
    };

    // Component c of a value (x, y, z[, w]).
    static float comp(const glm::vec3& v, size_t c) { return v[static_cast<glm::length_t>(c)]; }
    static float comp(const glm::quat& q, size_t c) { return c == 0 ? q.x : c == 1 ? q.y : c == 2 ? q.z : q.w; }

    // The joints [first, last] whose value changes over the keys, as a section (count 0 if none).
    template <class T>
    static ClipSection animated(const std::vector<T>& v, const Keys& keys) {
        int first = -1, last = -1;
        for (size_t j = 0; j < keys.joints; ++j)
            for (size_t k = 1; k < keys.count; ++k)
                if (v[k * keys.joints + j] != v[j]) {
                    if (first < 0) first = static_cast<int>(j);
                    last = static_cast<int>(j);
                    break;
                }
        ClipSection sec;
        if (first >= 0) { sec.first = first; sec.count = last - first + 1; }
        return sec;
    }

    // Element e of a block for joint j, component c: packed (3 per joint) or planar (`planes` planes).
    static size_t element(const ClipSection& sec, size_t j, size_t c, size_t dims) {
        const size_t local = j - static_cast<size_t>(sec.first);
        return sec.offset + (dims == 3 ? 3 * local + c : c * static_cast<size_t>(sec.count) + local);
    }

    // Stores section `sec` of values `v` (dims components) into every block; returns the largest
    // channel bound per joint component in `bounds` (joint-major, dims per joint).
    template <class T>
    static void store(AnimationClip& clip, const Keys& keys, const std::vector<T>& v, const ClipSection& sec,
                      size_t dims, std::vector<float>* bounds) {
        const bool quant = clip.encoding_ == ClipEncoding::Quantized16;
        for (size_t jj = 0; jj < static_cast<size_t>(sec.count); ++jj) {
            const size_t j = static_cast<size_t>(sec.first) + jj;
            for (size_t c = 0; c < dims; ++c) {
                float lo = comp(v[j], c), hi = lo;
                for (size_t k = 1; k < keys.count; ++k) {
                    lo = std::min(lo, comp(v[k * keys.joints + j], c));
                    hi = std::max(hi, comp(v[k * keys.joints + j], c));
                }
                const size_t e = element(sec, j, c, dims);
                const QuantChannel q = quant ? fit_channel(lo, hi) : QuantChannel{};
                if (quant) {
                    clip.base_[e] = q.base;
                    clip.step_[e] = q.step;
                }
                float bound = channel_error_bound(lo, hi, q.step);
                if (quant && q.step == 0.0f && hi > lo) bound += hi - lo;  // underflowed step: codes all 0
                (*bounds)[j * dims + c] = bound;
                for (size_t k = 0; k < keys.count; ++k) {
                    const float x = comp(v[k * keys.joints + j], c);
                    if (quant) clip.qkeys_[k * clip.block_ + e] = quantize(x, q);
                    else clip.fkeys_[k * clip.block_ + e] = x;
                }
            }
        }
    }

    // Fills `clip` (timeline, joint count and encoding already set) from `keys`.
    static void encode(AnimationClip& clip, const Keys& keys) {
        const size_t n = keys.joints;
        ClipSection& st = clip.sections_[AnimationClip::kTranslations];
        ClipSection& sr = clip.sections_[AnimationClip::kRotations];
        ClipSection& ss = clip.sections_[AnimationClip::kScales];
        st = animated(keys.t, keys);
        sr = animated(keys.r, keys);
        ss = animated(keys.s, keys);
        sr.offset = 3 * static_cast<size_t>(st.count);
        ss.offset = sr.offset + 4 * static_cast<size_t>(sr.count);
        clip.block_ = ss.offset + 3 * static_cast<size_t>(ss.count);
        // Joints outside a section hold their (constant) first-key value, rotations as sampling returns them.
        if (static_cast<size_t>(st.count) < n) clip.const_t_.assign(keys.t.begin(), keys.t.begin() + static_cast<long>(n));
        if (static_cast<size_t>(ss.count) < n) clip.const_s_.assign(keys.s.begin(), keys.s.begin() + static_cast<long>(n));
        if (static_cast<size_t>(sr.count) < n) {
            clip.const_r_.resize(n);
            for (size_t j = 0; j < n; ++j) clip.const_r_[j] = normalize_like_sampling(keys.r[j]);
        }
        const size_t total = keys.count * clip.block_;
        if (clip.encoding_ == ClipEncoding::Quantized16) {
            clip.qkeys_.assign(total, 0);
            clip.base_.assign(clip.block_, 0.0f);
            clip.step_.assign(clip.block_, 0.0f);
        } else {
            clip.fkeys_.assign(total, 0.0f);
        }
        std::vector<float> bt(3 * n, 0.0f), br(4 * n, 0.0f), bs(3 * n, 0.0f);
        store(clip, keys, keys.t, st, 3, &bt);
        store(clip, keys, keys.r, sr, 4, &br);
        store(clip, keys, keys.s, ss, 3, &bs);
        clip.bound_ = ClipErrorBound{};
        for (float b : bt) clip.bound_.translation = std::max(clip.bound_.translation, b);
        for (float b : bs) clip.bound_.scale = std::max(clip.bound_.scale, b);
        for (size_t j = static_cast<size_t>(sr.first); j < static_cast<size_t>(sr.first + sr.count); ++j)
            clip.bound_.rotation = std::max(clip.bound_.rotation, rotation_error_bound(&br[4 * j]));
    }
};

glm::quat without_turn_about_vertical(const glm::quat& q) {
    const float len = std::sqrt(q.w * q.w + q.y * q.y);
    if (len < 1e-9f) return q;  // a half turn about a horizontal axis: no turn about the vertical to take out
    const glm::quat twist(q.w / len, 0.0f, q.y / len, 0.0f);
    return q * glm::conjugate(twist);
}

namespace {

// Whether the pose at the last key time is the first's (AnimationClip::ends_meet); `keys` holds every joint's value
// at every key time.
bool ends_meet(const ClipEncoder::Keys& keys) {
    const size_t n = keys.joints, last = (keys.count - 1) * n;
    for (size_t j = 0; j < n; ++j) {
        glm::quat d = keys.r[last + j] * glm::inverse(keys.r[j]);
        if (j == 0) d = without_turn_about_vertical(d);  // the root's turn is travel (a clip played in place turns back)
        const float angle = 2.0f * std::atan2(glm::length(glm::vec3(d.x, d.y, d.z)), std::abs(d.w));
        glm::vec3 moved = keys.t[last + j] - keys.t[j];
        if (j == 0) moved.x = moved.z = 0.0f;  // the root's travel over the ground
        const glm::vec3 scaled = keys.s[last + j] - keys.s[j];
        if (angle > kEndsMeetAngle || glm::length(moved) > kEndsMeetDistance || glm::length(scaled) > kEndsMeetDistance) return false;
    }
    return true;
}

}  // namespace

Result<AnimationClip> build_clip(const RawAnimation& raw, const Skeleton& skeleton, ClipEncoding encoding) {
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
    clip.encoding_ = encoding;
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

    // Every joint's value at every key time, then encoded into key blocks.
    ClipEncoder::Keys keys;
    keys.joints = n;
    keys.count = times.size();
    keys.t.resize(n * times.size());
    keys.r.resize(n * times.size());
    keys.s.resize(n * times.size());
    const auto rest_t = skeleton.rest_translations();
    const auto rest_r = skeleton.rest_rotations();
    const auto rest_s = skeleton.rest_scales();
    for (size_t k = 0; k < times.size(); ++k) {
        const float t = times[k];
        for (size_t j = 0; j < n; ++j) {
            const bool has = j < raw.tracks.size();
            keys.t[k * n + j] = has ? eval_vec(raw.tracks[j].translations, t, rest_t[j]) : rest_t[j];
            keys.s[k * n + j] = has ? eval_vec(raw.tracks[j].scales, t, rest_s[j]) : rest_s[j];
            keys.r[k * n + j] = has && !aligned[j].empty() ? eval_rot(raw.tracks[j].rotations.times, aligned[j], t) : rest_r[j];
        }
    }
    clip.ends_meet_ = ends_meet(keys);
    clip.times_ = std::move(times);
    ClipEncoder::encode(clip, keys);
    // Root translation at both ends, as sampling returns it there.
    std::vector<glm::vec3> t(n), s(n);
    std::vector<glm::quat> r(n);
    sample_blocks(clip, 0, 0.0f, t.data(), r.data(), s.data());
    clip.root_start_ = t[0];
    const int last = clip.key_count() - 1;
    sample_blocks(clip, std::max(last - 1, 0), last > 0 ? 1.0f : 0.0f, t.data(), r.data(), s.data());
    clip.root_end_ = t[0];
    clip.root_motion_ = measure_root_motion(clip, skeleton.parents());
    return clip;
}

ClipId ClipLibrary::add(AnimationClip clip) {
    assert(clips_.size() < 65535);
    clips_.push_back(std::move(clip));
    looped_.emplace_back();
    return static_cast<ClipId>(clips_.size() - 1);
}

Result<ClipId> ClipLibrary::add(const RawAnimation& raw, const Skeleton& skeleton) {
    Result<AnimationClip> clip = build_clip(raw, skeleton);
    if (!clip) return clip.error();
    return add(std::move(clip).value());
}

void ClipLibrary::set_looped(ClipId id, AnimationClip looped) {
    assert(id < clips_.size());
    assert(looped.joint_count() == clips_[id].joint_count() && looped.duration() == clips_[id].duration());
    looped_[id] = std::move(looped);
}

const AnimationClip* ClipLibrary::find(ClipId id) const {
    return id < clips_.size() ? &clips_[id] : nullptr;
}

const AnimationClip* ClipLibrary::find_looped(ClipId id) const {
    if (id >= clips_.size()) return nullptr;
    return looped_[id] ? &*looped_[id] : &clips_[id];
}

int ClipLibrary::find(const std::string& name) const {
    for (size_t i = 0; i < clips_.size(); ++i)
        if (clips_[i].name() == name) return static_cast<int>(i);
    return -1;
}

size_t ClipLibrary::byte_size() const {
    size_t bytes = 0;
    for (const AnimationClip& c : clips_) bytes += c.byte_size();
    for (const std::optional<AnimationClip>& c : looped_)
        if (c) bytes += c->byte_size();
    return bytes;
}

}  // namespace aloha
