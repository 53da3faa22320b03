// glTF 2.0 character loader (tinygltf): skeleton and inverse bind matrices from skin 0, the meshes
// skinned by it, and all animation clips.
//
// Conventions:
// - Raw joint i is skin.joints[i]; its parent is the nearest ancestor node that is also a joint.
//   Transforms of non-joint nodes between a joint and its joint parent (or above a root joint,
//   e.g. CesiumMan's Z_UP and Armature `matrix` nodes) are folded into that joint's rest transform
//   and into its animation keys, so model space equals the glTF scene's world space (Y up).
//   Folding keys is exact when the folded transform has uniform scale (otherwise a note is added).
//   Animations of non-joint nodes are ignored.
// - inverse_bind_matrices[i] belongs to raw joint i (identity when the skin has none). Skinning:
//   v_model = sum_k w_k * model[runtime joint] * inverse_bind_matrices[raw joint] * v. The mesh
//   node's own transform is ignored, as the glTF spec requires for skinned meshes.
// - GltfSkinnedMesh::joints holds RUNTIME joint indices (of build_skeleton(skeleton));
//   weights are normalised to sum 1; one GltfSkinnedMesh per triangle primitive; a missing NORMAL
//   is computed (area-weighted); missing indices become 0..n-1.
// - Clips: tracks indexed by RUNTIME joint. Key times are shifted so the earliest key of the clip
//   is at 0; start_offset keeps that original time; duration = last key - first key (CesiumMan:
//   2.0 - 0.041667 = 1.958333 s). Unnamed clips are called "clip<index>". LINEAR keys are kept;
//   STEP keys are expanded to hold each value until 1e-4 s (at most a quarter of the gap) before
//   the next key so linear sampling reproduces the steps; CUBICSPLINE keeps only the value of each
//   (in-tangent, value, out-tangent) triple, i.e. it is resampled as linear. `weights` (morph)
//   channels are skipped with a note.
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/raw_skeleton.hpp"
#include "engine/core/result.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace aloha {

/// One skinned triangle mesh in bind space (the space inverse bind matrices map from).
struct GltfSkinnedMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;   ///< unit length, one per position
    std::vector<glm::u16vec4> joints; ///< runtime skeleton joint indices, one per position
    std::vector<glm::vec4> weights;   ///< non-negative, sum 1, one per position
    std::vector<uint32_t> indices;    ///< triangle list, each < positions.size()
};

/// A character read from a glTF file.
struct GltfCharacter {
    RawSkeleton skeleton;                           ///< joints in skin order (raw order)
    std::vector<glm::mat4> inverse_bind_matrices;   ///< per raw joint
    std::vector<GltfSkinnedMesh> meshes;            ///< primitives of meshes on nodes using skin 0
    std::vector<RawAnimation> clips;                ///< tracks in runtime joint order
    std::vector<std::string> clip_names;            ///< clips[i].name, "" in the file -> "clip<i>"
    std::vector<std::string> notes;                 ///< things read but deliberately ignored
};

/// Largest vertex / index / key count accepted per accessor (guards allocations).
inline constexpr size_t kMaxGltfAccessorCount = size_t{1} << 26;

/// Loads a .glb or .gltf file (decided by content: GLB files start with "glTF"). Errors name the
/// file and the glTF object ("accessors[12]", "skins[0]", "nodes[4]") and say what is wrong.
Result<GltfCharacter> load_gltf_character(const std::string& path);

/// Parses glTF JSON text whose buffers are embedded (data: URIs) or relative to `base_dir`.
/// `source_name` names the input in errors.
Result<GltfCharacter> parse_gltf_character(std::string_view json_text, const std::string& source_name,
                                           const std::string& base_dir = "");

}  // namespace aloha
