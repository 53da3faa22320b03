// Internal helpers of the glTF loader (not part of the public API): validated accessor reads,
// node hierarchy checks and transform folding, mesh and clip conversion.
#pragma once

#include "engine/assets/gltf_loader.hpp"
#include "engine/core/result.hpp"

#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace aloha::gltf_detail {

/// Reads accessor `index` as floats (count * components values). Requires type `type`
/// (TINYGLTF_TYPE_*) and a component type from `allowed`; integer components are normalised
/// to [0,1] / [-1,1] when the accessor says `normalized` or `force_normalize` is set.
/// `usage` says who uses it ("meshes[0].primitives[0].attributes.POSITION") for the error.
Result<std::vector<float>> read_floats(const tinygltf::Model& model, int index, int type,
                                       const std::vector<int>& allowed, const std::string& file,
                                       const std::string& usage, bool force_normalize = false);

/// Reads accessor `index` as unsigned integers (indices, joints); same checks as read_floats().
Result<std::vector<uint32_t>> read_uints(const tinygltf::Model& model, int index, int type,
                                         const std::vector<int>& allowed, const std::string& file,
                                         const std::string& usage);

/// Translation, rotation, scale of a transform.
struct Trs {
    glm::vec3 t{0.0f};
    glm::quat r{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 s{1.0f};
};

/// Parent node of every node (-1 for roots). Errors: child index out of range, a node listed as
/// child twice or by two parents, cycles.
Result<std::vector<int>> node_parents(const tinygltf::Model& model, const std::string& file);

/// Local matrix of node `index` from `matrix` or TRS. Errors: wrong array sizes, NaN/Inf.
Result<glm::mat4> node_local_matrix(const tinygltf::Model& model, int index, const std::string& file);

/// Splits an affine matrix without shear into TRS. Errors (naming `where`): singular, shear.
Result<Trs> decompose(const glm::mat4& m, const std::string& file, const std::string& where);

/// Converts the primitives of skinned mesh `mesh_index`; `runtime_of_raw` maps skin joint
/// indices to runtime joint indices.
Status read_skinned_mesh(const tinygltf::Model& model, int mesh_index, const std::vector<int>& runtime_of_raw,
                         const std::string& file, std::vector<GltfSkinnedMesh>* out);

/// Per raw joint: its node and the folded non-joint ancestor transform applied to its keys.
struct JointBinding {
    int node = -1;
    glm::mat4 fold{1.0f};
    bool folded = false;
};

/// Converts animation `index` into a clip with tracks in RAW joint order; notes skipped channels.
Result<RawAnimation> read_clip(const tinygltf::Model& model, int index, const std::vector<JointBinding>& joints,
                               const std::string& file, std::vector<std::string>* notes);

}  // namespace aloha::gltf_detail
