#include "systems/motion/blend.hpp"

#include <cmath>

namespace aloha {

namespace {
void blend_kernel(const glm::vec3* at, const glm::quat* ar, const glm::vec3* as, const glm::vec3* bt,
                  const glm::quat* br, const glm::vec3* bs, float w, glm::vec3* ot, glm::quat* orr, glm::vec3* os,
                  size_t n) {
    if (w <= 0.0f) {
        for (size_t j = 0; j < n; ++j) { ot[j] = at[j]; orr[j] = ar[j]; os[j] = as[j]; }
        return;
    }
    if (w >= 1.0f) {
        for (size_t j = 0; j < n; ++j) { ot[j] = bt[j]; orr[j] = br[j]; os[j] = bs[j]; }
        return;
    }
    const float wa = 1.0f - w;
    for (size_t j = 0; j < n; ++j) {
        ot[j] = at[j] * wa + bt[j] * w;
        os[j] = as[j] * wa + bs[j] * w;
        const glm::quat& p = ar[j];
        const glm::quat& q = br[j];
        const float wb = (p.x * q.x + p.y * q.y + p.z * q.z + p.w * q.w) < 0.0f ? -w : w;  // hemisphere fix
        const float x = p.x * wa + q.x * wb, y = p.y * wa + q.y * wb, z = p.z * wa + q.z * wb, ww = p.w * wa + q.w * wb;
        const float inv = 1.0f / std::sqrt(x * x + y * y + z * z + ww * ww);
        orr[j].x = x * inv;
        orr[j].y = y * inv;
        orr[j].z = z * inv;
        orr[j].w = ww * inv;
    }
}
}  // namespace

bool BlendJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](const std::string& m) { ok = false; if (errors) errors->push_back("BlendJob: " + m); };
    const size_t n = translations.size();
    if (n == 0) fail("output translations span is empty");
    if (a_translations.size() < n || a_rotations.size() < n || a_scales.size() < n) fail("pose a has fewer joints than the output");
    if (b_translations.size() < n || b_rotations.size() < n || b_scales.size() < n) fail("pose b has fewer joints than the output");
    if (rotations.size() < n || scales.size() < n) fail("output rotations/scales are shorter than translations");
    if (!(weight >= 0.0f && weight <= 1.0f)) fail("weight " + std::to_string(weight) + " is outside [0,1]");
    return ok;
}

void BlendJob::Run() const {
    blend_kernel(a_translations.data(), a_rotations.data(), a_scales.data(), b_translations.data(), b_rotations.data(),
                 b_scales.data(), weight, translations.data(), rotations.data(), scales.data(), translations.size());
}

void blend_into(const PoseView& a, const ConstPoseView& b, float weight) {
    blend_kernel(a.translations.data(), a.rotations.data(), a.scales.data(), b.translations.data(), b.rotations.data(),
                 b.scales.data(), weight, a.translations.data(), a.rotations.data(), a.scales.data(),
                 a.translations.size());
}

}  // namespace aloha
