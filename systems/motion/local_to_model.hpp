// Local-to-model conversion: turns a local pose (SoA translation/rotation/scale) into model-space
// matrices, parents before children, like ozz-animation's LocalToModelJob.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Builds the affine matrix translate(t) * mat4(q) * scale(s). Requires q normalised.
[[nodiscard]] glm::mat4 compose_trs(const glm::vec3& t, const glm::quat& q, const glm::vec3& s);

/// Computes model[j] = model[parent[j]] * TRS(j) (root joints use `root`, identity by default).
struct LocalToModelJob {
    std::span<const int16_t> parents;        ///< skeleton parents (parents precede children, -1 root)
    std::span<const glm::vec3> translations; ///< local translations, parents.size() elements
    std::span<const glm::quat> rotations;    ///< local rotations (normalised), parents.size() elements
    std::span<const glm::vec3> scales;       ///< local scales, parents.size() elements
    const glm::mat4* root = nullptr;         ///< optional matrix applied above the roots (e.g. world placement)
    std::span<glm::mat4> model;              ///< output, parents.size() elements

    /// True when the job can run; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Converts. Requires Validate().
    void Run() const;
};

/// The kernel behind LocalToModelJob on raw pointers (for batched loops); `count` joints. Uses the AVX2
/// form when the CPU has it and `allow_avx2` (same bits either way).
void local_to_model(const int16_t* parents, const glm::vec3* translations, const glm::quat* rotations,
                    const glm::vec3* scales, const glm::mat4* root, glm::mat4* model, size_t count,
                    bool allow_avx2 = true);

/// One character's pose for local_to_model_many: local pose in, model matrices out.
struct PosePointers {
    const glm::vec3* translations = nullptr;  ///< local translations, joint count elements
    const glm::quat* rotations = nullptr;     ///< local rotations (normalised), joint count elements
    const glm::vec3* scales = nullptr;        ///< local scales, joint count elements
    glm::mat4* model = nullptr;               ///< output, joint count elements
};

/// local_to_model (identity root) for `pose_count` poses of one skeleton of `count` joints. The AVX2
/// form runs poses in pairs, joint by joint, so their parent chains overlap; same bits as one
/// local_to_model call per pose.
void local_to_model_many(const int16_t* parents, const PosePointers* poses, size_t pose_count, size_t count,
                         bool allow_avx2 = true);

namespace l2m_simd {
/// The AVX2 form of local_to_model for `pose_count` poses (local_to_model_avx2.cpp), roots under `top`;
/// requires AVX2 (clip_simd::avx2_available()).
void local_to_model_avx2(const int16_t* parents, const PosePointers* poses, size_t pose_count, const glm::mat4& top,
                         size_t count);
}  // namespace l2m_simd

}  // namespace aloha
