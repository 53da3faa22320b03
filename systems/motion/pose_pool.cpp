#include "systems/motion/pose_pool.hpp"

#include "systems/motion/local_to_model.hpp"

#include <algorithm>

namespace aloha {

PosePool::PosePool(int joint_count, size_t slot_count, const Skeleton* rest)
    : joints_(joint_count), slots_(slot_count) {
    const size_t total = static_cast<size_t>(joint_count) * slot_count;
    t_.assign(total, glm::vec3(0.0f));
    r_.assign(total, glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
    s_.assign(total, glm::vec3(1.0f));
    m_.assign(total, glm::mat4(1.0f));
    if (rest)
        for (size_t s = 0; s < slot_count; ++s) set_rest(s, *rest);
}

PoseView PosePool::view(size_t s) {
    const size_t n = static_cast<size_t>(joints_);
    const size_t o = s * n;
    return PoseView{std::span<glm::vec3>(t_).subspan(o, n), std::span<glm::quat>(r_).subspan(o, n),
                    std::span<glm::vec3>(s_).subspan(o, n), std::span<glm::mat4>(m_).subspan(o, n)};
}

ConstPoseView PosePool::view(size_t s) const {
    const size_t n = static_cast<size_t>(joints_);
    const size_t o = s * n;
    return ConstPoseView{std::span<const glm::vec3>(t_).subspan(o, n), std::span<const glm::quat>(r_).subspan(o, n),
                         std::span<const glm::vec3>(s_).subspan(o, n), std::span<const glm::mat4>(m_).subspan(o, n)};
}

void PosePool::set_rest(size_t s, const Skeleton& skeleton) {
    PoseView v = view(s);
    const auto rt = skeleton.rest_translations();
    const auto rr = skeleton.rest_rotations();
    const auto rs = skeleton.rest_scales();
    for (size_t j = 0; j < v.translations.size(); ++j) {
        v.translations[j] = rt[j];
        v.rotations[j] = rr[j];
        v.scales[j] = rs[j];
    }
    local_to_model(skeleton.parents().data(), v.translations.data(), v.rotations.data(), v.scales.data(), nullptr,
                   v.model.data(), v.translations.size());
}

void PosePool::set_stance(size_t s, const AnimationClip& clip, const Skeleton& skeleton) {
    PoseView v = view(s);
    int k = 0;
    float alpha = 0.0f;
    find_key(clip, 0.0f, nullptr, &k, &alpha);
    sample_blocks(clip, k, alpha, v.translations.data(), v.rotations.data(), v.scales.data());
    const glm::vec3 rest_root = skeleton.rest_translations()[0];
    v.translations[0].x = rest_root.x, v.translations[0].z = rest_root.z;
    local_to_model(skeleton.parents().data(), v.translations.data(), v.rotations.data(), v.scales.data(), nullptr,
                   v.model.data(), v.translations.size());
}

bool AnimateBatchJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](const std::string& m) { ok = false; if (errors) errors->push_back("AnimateBatchJob: " + m); };
    if (!clip) fail("clip is null");
    if (!skeleton) fail("skeleton is null");
    if (!pool) fail("pool is null");
    if (!ok) return false;
    if (clip->joint_count() != skeleton->joint_count()) fail("clip was built for a skeleton of another joint count");
    if (pool->joint_count() != skeleton->joint_count()) fail("pose pool joint count differs from the skeleton's");
    if (slots.size() != times.size()) fail("slots and times differ in length");
    if (caches.size() != times.size()) fail("caches and times differ in length");
    for (uint32_t s : slots)
        if (s >= pool->slot_count()) {
            fail("slot " + std::to_string(s) + " is outside the pool (" + std::to_string(pool->slot_count()) + " slots)");
            break;
        }
    return ok;
}

void AnimateBatchJob::Run() const {
    const AnimationClip& c = *clip;
    const int16_t* parents = skeleton->parents().data();
    const size_t n = static_cast<size_t>(skeleton->joint_count());
    // Characters in groups: sample each, then convert the group together (local_to_model_many overlaps
    // their parent chains); the group's local poses are still in cache when converted.
    constexpr size_t kGroup = 4;
    PosePointers group[kGroup];
    for (size_t first = 0; first < times.size(); first += kGroup) {
        const size_t count = std::min(kGroup, times.size() - first);
        for (size_t g = 0; g < count; ++g) {
            const size_t i = first + g;
            const float t = wrap_clip_time(times[i], c.duration(), loop);
            int k = 0;
            float alpha = 0.0f;
            find_key(c, t, &caches[i], &k, &alpha);
            PoseView v = pool->view(slots[i]);
            sample_blocks(c, k, alpha, v.translations.data(), v.rotations.data(), v.scales.data());
            group[g] = PosePointers{v.translations.data(), v.rotations.data(), v.scales.data(), v.model.data()};
        }
        local_to_model_many(parents, group, count, n);
    }
}

}  // namespace aloha
