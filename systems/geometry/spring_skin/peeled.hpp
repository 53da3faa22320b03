// Peeled layers for the cheap geometric levels: linear-blend skinning of a mesh directly on the
// skeleton (no muscles, no springs) and one rigid proxy box per bone (the bottom level).
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Linear-blend skinning of one mesh (or several meshes sharing a skeleton palette, concatenated):
/// p' = sum_i w_i J[j_i] p, n' = normalize(sum_i w_i mat3(J[j_i]) n). Exact for rigid joint
/// matrices and uniform scale; the normal ignores non-uniform scale (no inverse transpose).
struct LinearBlendSkinJob {
    std::span<const glm::mat4> joint_matrices;   ///< skinning palette: model(joint) * inverse_bind(joint)
    std::span<const glm::vec3> bind_positions;   ///< mesh positions in bind pose
    std::span<const glm::vec3> bind_normals;     ///< mesh normals in bind pose (unit), same size
    std::span<const glm::u16vec4> joints;        ///< up to 4 palette indices per vertex
    std::span<const glm::vec4> weights;          ///< matching weights (sum 1; unused slots 0)
    std::span<glm::vec3> positions;              ///< output skinned positions, same size
    std::span<glm::vec3> normals;                ///< output skinned unit normals, same size

    /// Checks sizes and that every index with a non-zero weight is in the palette.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Skins every vertex. Requires Validate().
    void Run() const;
};

/// One box per joint of a skeleton pose, for the rigid-proxy level: the box of joint j spans the
/// bone from its parent to j (so it is centred between a joint and its child j), its local x axis
/// along the bone with half-extent = half the bone length, y/z half-extents = the radius, y taken
/// from the parent's model-space y axis made perpendicular to the bone. A root joint gets a cube of
/// half-extent = radius at its position. Output matrices map the cube [-1, 1]^3 onto the box.
struct RigidProxyJob {
    std::span<const glm::mat4> model;      ///< model-space joint matrices (rigid)
    std::span<const int16_t> parents;      ///< parent per joint (-1 = root), parents before children
    std::span<const float> radii;          ///< box radius per joint, or empty to use `radius`
    float radius = 0.04f;                  ///< box radius (m) when `radii` is empty (> 0)
    std::span<glm::mat4> boxes;            ///< output: unit-cube-to-box matrix per joint

    /// Checks sizes, parent order and radius.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Writes one box per joint. Requires Validate().
    void Run() const;
};

}  // namespace aloha
