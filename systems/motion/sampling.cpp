#include "systems/motion/sampling.hpp"

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

void sample_blocks(const AnimationClip& clip, int k, float alpha, glm::vec3* translations, glm::quat* rotations,
                   glm::vec3* scales) {
    const size_t n = static_cast<size_t>(clip.joint_count());
    const float* __restrict a = clip.block(k);
    const float* __restrict b = clip.key_count() > 1 ? clip.block(k + 1) : a;
    const float wa = 1.0f - alpha;
    const float wb = alpha;
    // Translations and scales: packed xyz, one flat loop each (a*wa + b*wb is exact at alpha 0 and 1).
    float* __restrict ot = &translations[0].x;
    for (size_t i = 0; i < 3 * n; ++i) ot[i] = a[i] * wa + b[i] * wb;
    float* __restrict os = &scales[0].x;
    const float* __restrict as = a + 7 * n;
    const float* __restrict bs = b + 7 * n;
    for (size_t i = 0; i < 3 * n; ++i) os[i] = as[i] * wa + bs[i] * wb;
    // Rotations: four planes, lerp then normalise (nlerp; keys are hemisphere-aligned at build time).
    const float* __restrict ax = a + 3 * n;
    const float* __restrict bx = b + 3 * n;
    for (size_t j = 0; j < n; ++j) {
        const float x = ax[j] * wa + bx[j] * wb;
        const float y = ax[n + j] * wa + bx[n + j] * wb;
        const float z = ax[2 * n + j] * wa + bx[2 * n + j] * wb;
        const float w = ax[3 * n + j] * wa + bx[3 * n + j] * wb;
        const float inv = 1.0f / std::sqrt(x * x + y * y + z * z + w * w);
        rotations[j].x = x * inv;
        rotations[j].y = y * inv;
        rotations[j].z = z * inv;
        rotations[j].w = w * inv;
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
