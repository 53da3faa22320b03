#include "systems/motion/local_to_model.hpp"

#include "systems/motion/clip_quant.hpp"

namespace aloha {

glm::mat4 compose_trs(const glm::vec3& t, const glm::quat& q, const glm::vec3& s) {
    const float xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
    const float xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
    const float wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
    glm::mat4 m;
    m[0] = glm::vec4((1.0f - 2.0f * (yy + zz)) * s.x, 2.0f * (xy + wz) * s.x, 2.0f * (xz - wy) * s.x, 0.0f);
    m[1] = glm::vec4(2.0f * (xy - wz) * s.y, (1.0f - 2.0f * (xx + zz)) * s.y, 2.0f * (yz + wx) * s.y, 0.0f);
    m[2] = glm::vec4(2.0f * (xz + wy) * s.z, 2.0f * (yz - wx) * s.z, (1.0f - 2.0f * (xx + yy)) * s.z, 0.0f);
    m[3] = glm::vec4(t, 1.0f);
    return m;
}

void local_to_model(const int16_t* parents, const glm::vec3* translations, const glm::quat* rotations,
                    const glm::vec3* scales, const glm::mat4* root, glm::mat4* model, size_t count,
                    bool allow_avx2) {
    static const glm::mat4 kIdentity(1.0f);
    const glm::mat4& top = root ? *root : kIdentity;
    if (allow_avx2 && clip_simd::avx2_available()) {
        const PosePointers pose{translations, rotations, scales, model};
        l2m_simd::local_to_model_avx2(parents, &pose, 1, top, count);
        return;
    }
    // Portable loop; the AVX2 form evaluates every expression below in the same order (same bits).
    for (size_t j = 0; j < count; ++j) {
        const glm::quat& q = rotations[j];
        const glm::vec3& s = scales[j];
        const glm::vec3& t = translations[j];
        const float xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
        const float xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
        const float wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
        // Local affine columns (rotation scaled per axis); the product below only needs 3x4 of it.
        const float l00 = (1.0f - 2.0f * (yy + zz)) * s.x, l01 = 2.0f * (xy + wz) * s.x, l02 = 2.0f * (xz - wy) * s.x;
        const float l10 = 2.0f * (xy - wz) * s.y, l11 = (1.0f - 2.0f * (xx + zz)) * s.y, l12 = 2.0f * (yz + wx) * s.y;
        const float l20 = 2.0f * (xz + wy) * s.z, l21 = 2.0f * (yz - wx) * s.z, l22 = (1.0f - 2.0f * (xx + yy)) * s.z;
        const int p = parents[j];
        const glm::mat4& P = p < 0 ? top : model[p];
        const glm::vec4 p0 = P[0], p1 = P[1], p2 = P[2], p3 = P[3];
        glm::mat4& M = model[j];
        M[0] = p0 * l00 + p1 * l01 + p2 * l02;
        M[1] = p0 * l10 + p1 * l11 + p2 * l12;
        M[2] = p0 * l20 + p1 * l21 + p2 * l22;
        M[3] = p0 * t.x + p1 * t.y + p2 * t.z + p3;
    }
}

void local_to_model_many(const int16_t* parents, const PosePointers* poses, size_t pose_count, size_t count,
                         bool allow_avx2) {
    if (allow_avx2 && clip_simd::avx2_available()) {
        l2m_simd::local_to_model_avx2(parents, poses, pose_count, glm::mat4(1.0f), count);
        return;
    }
    for (size_t c = 0; c < pose_count; ++c)
        local_to_model(parents, poses[c].translations, poses[c].rotations, poses[c].scales, nullptr, poses[c].model,
                       count, false);
}

bool LocalToModelJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](const std::string& m) { ok = false; if (errors) errors->push_back("LocalToModelJob: " + m); };
    const size_t n = parents.size();
    if (n == 0) fail("parents span is empty");
    if (translations.size() < n) fail("translations span is shorter than parents");
    if (rotations.size() < n) fail("rotations span is shorter than parents");
    if (scales.size() < n) fail("scales span is shorter than parents");
    if (model.size() < n) fail("model span is shorter than parents");
    for (size_t j = 0; j < n; ++j)
        if (parents[j] >= static_cast<int>(j)) {
            fail("joint " + std::to_string(j) + " has parent " + std::to_string(parents[j]) + " that does not precede it");
            break;
        }
    return ok;
}

void LocalToModelJob::Run() const {
    local_to_model(parents.data(), translations.data(), rotations.data(), scales.data(), root, model.data(),
                   parents.size());
}

}  // namespace aloha
