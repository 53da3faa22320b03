#include "systems/motion/sampling.hpp"

#include "systems/motion/clip_quant.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

float wrap_clip_time(float time, float duration, bool loop) {
    if (!(duration > 0.0f)) return 0.0f;
    if (loop) {
        if (time >= 0.0f && time <= duration) return time;
        float t = std::fmod(time, duration);
        if (t < 0.0f) t += duration;
        return t;
    }
    return std::clamp(time, 0.0f, duration);
}

void find_key(const AnimationClip& clip, float time, SamplingCache* cache, int* k, float* alpha) {
    const int keys = clip.key_count();
    if (keys < 2) { *k = 0; *alpha = 0.0f; return; }
    if (clip.uniform()) {
        const float u = time * clip.inverse_key_spacing();
        int i = static_cast<int>(u);
        i = std::clamp(i, 0, keys - 2);
        *k = i;
        *alpha = std::clamp(u - static_cast<float>(i), 0.0f, 1.0f);
        if (cache) { cache->clip = &clip; cache->cursor = i; cache->last_time = time; }
        return;
    }
    const float* times = clip.times().data();
    int i = 0;
    if (cache && cache->clip != &clip) {  // first use with this clip: the cursor starts at key 0
        cache->clip = &clip;
        cache->cursor = 0;
    }
    if (cache && cache->cursor >= 0 && cache->cursor < keys - 1 && time >= times[cache->cursor]) {
        i = cache->cursor;
        // Steady playback advances a key or two per frame; after 8 steps fall back to a search
        // restricted to the keys ahead (still never from the start).
        int walked = 0;
        while (i < keys - 2 && time >= times[i + 1] && walked < 8) { ++i; ++walked; }
        if (i < keys - 2 && time >= times[i + 1]) {
            const float* it = std::upper_bound(times + i + 1, times + keys, time);
            i = std::min(static_cast<int>(it - times) - 1, keys - 2);
        }
        cache->steps += static_cast<uint32_t>(walked);
    } else {
        const float* it = std::upper_bound(times, times + keys, time);
        i = std::clamp(static_cast<int>(it - times) - 1, 0, keys - 2);
        if (cache) ++cache->restarts;
    }
    if (cache) { cache->cursor = i; cache->last_time = time; }
    *k = i;
    *alpha = std::clamp((time - times[i]) / (times[i + 1] - times[i]), 0.0f, 1.0f);
}

namespace {

// Copies the constant values of the joints outside `sec` (joints [0, n) less [first, first + count)).
template <class T>
void copy_outside(const std::vector<T>& constant, const ClipSection& sec, size_t n, T* out) {
    if (static_cast<size_t>(sec.count) == n) return;
    const size_t first = static_cast<size_t>(sec.first), end = first + static_cast<size_t>(sec.count);
    std::copy(constant.begin(), constant.begin() + static_cast<std::ptrdiff_t>(sec.count > 0 ? first : n), out);
    if (sec.count > 0) std::copy(constant.begin() + static_cast<std::ptrdiff_t>(end), constant.end(), out + end);
}

}  // namespace

void sample_blocks(const AnimationClip& clip, int k, float alpha, glm::vec3* translations, glm::quat* rotations,
                   glm::vec3* scales) {
    const size_t n = static_cast<size_t>(clip.joints_);
    const size_t ka = static_cast<size_t>(k) * clip.block_;
    // Block k + 1, or k itself for the last key (sampled at alpha 0: weight 0 on it, and no read past the keys).
    const size_t kb = k + 1 < clip.key_count() ? ka + clip.block_ : ka;
    const float wa = 1.0f - alpha;
    const float wb = alpha;
    const ClipSection& st = clip.sections_[AnimationClip::kTranslations];
    const ClipSection& sr = clip.sections_[AnimationClip::kRotations];
    const ClipSection& ss = clip.sections_[AnimationClip::kScales];
    copy_outside(clip.const_t_, st, n, translations);
    copy_outside(clip.const_r_, sr, n, rotations);
    copy_outside(clip.const_s_, ss, n, scales);
    // Stored joints: translations and scales packed xyz (one flat loop each, exact at alpha 0 and 1
    // for floats); rotations from four planes, lerp then normalise (nlerp; keys hemisphere-aligned).
    float* ot = &translations[st.first].x;
    float* os = &scales[ss.first].x;
    glm::quat* orr = rotations + sr.first;
    const size_t ct = 3 * static_cast<size_t>(st.count), cr = static_cast<size_t>(sr.count);
    const size_t cs = 3 * static_cast<size_t>(ss.count);
    if (clip.encoding_ == ClipEncoding::Quantized16) {
        const uint16_t* a = clip.qkeys_.data() + ka;
        const uint16_t* b = clip.qkeys_.data() + kb;
        const float* base = clip.base_.data();
        const float* step = clip.step_.data();
        decode_lerp(a + st.offset, b + st.offset, base + st.offset, step + st.offset, wa, wb, ot, ct);
        decode_nlerp(a + sr.offset, b + sr.offset, cr, base + sr.offset, step + sr.offset, wa, wb, orr, cr);
        decode_lerp(a + ss.offset, b + ss.offset, base + ss.offset, step + ss.offset, wa, wb, os, cs);
    } else {
        const float* a = clip.fkeys_.data() + ka;
        const float* b = clip.fkeys_.data() + kb;
        decode_lerp(a + st.offset, b + st.offset, wa, wb, ot, ct);
        decode_nlerp(a + sr.offset, b + sr.offset, cr, wa, wb, orr, cr);
        decode_lerp(a + ss.offset, b + ss.offset, wa, wb, os, cs);
    }
}

bool SampleJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](const std::string& m) { ok = false; if (errors) errors->push_back("SampleJob: " + m); };
    if (!clip) {
        fail("clip is null");
        return false;
    }
    const size_t n = static_cast<size_t>(clip->joint_count());
    if (clip->key_count() < 1) fail("clip has no keys");
    if (translations.size() < n) fail("translations span has " + std::to_string(translations.size()) + " elements, clip needs " + std::to_string(n));
    if (rotations.size() < n) fail("rotations span has " + std::to_string(rotations.size()) + " elements, clip needs " + std::to_string(n));
    if (scales.size() < n) fail("scales span has " + std::to_string(scales.size()) + " elements, clip needs " + std::to_string(n));
    if (!std::isfinite(time)) fail("time is not finite");
    return ok;
}

void SampleJob::Run() const {
    const float t = wrap_clip_time(time, clip->duration(), loop);
    int k = 0;
    float alpha = 0.0f;
    find_key(*clip, t, cache, &k, &alpha);
    sample_blocks(*clip, k, alpha, translations.data(), rotations.data(), scales.data());
}

}  // namespace aloha
