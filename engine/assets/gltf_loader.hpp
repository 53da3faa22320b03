// glTF 2.0 character loader (tinygltf): the skeleton formed by the joints of every skin, inverse
// bind matrices, every mesh attached to it (skinned, or rigid under a joint node), materials with
// their base colour textures, and all animation clips.
//
// Conventions (each checked against the glTF 2.0 specification):
// - A file without skins whose nodes carry meshes is read as if it had one skin over every node of
//   its displayed scene, bound at the rest pose (a rigid robot: each mesh a rigid part of its node).
// - Joints are the union of all skins' joints: skins[0].joints in order, then the joints of
//   skins[1] not already listed, and so on (several skins may share joints). Raw joint i's parent is
//   the nearest ancestor node that is also a joint. Transforms of non-joint nodes between a joint
//   and its joint parent (or above a root joint: a scale-100 armature, CesiumMan's Z_UP and
//   Armature `matrix` nodes) are folded into that joint's rest transform and into its animation
//   keys, so model space equals the glTF scene's world space (Y up). Folding keys is exact when the
//   folded transform has uniform scale (otherwise a note is added). An animated node among those
//   (an armature object moved instead of its root bone) is folded key by key: the joints below it get
//   keys at the union of its and their key times, each the product of the sampled transforms (one
//   note per clip). Animations of other non-joint nodes are ignored (one note per channel).
// - inverse_bind_matrices[i] belongs to raw joint i (identity when its skin has none). Skinning:
//   v_model = sum_k w_k * model[runtime joint] * inverse_bind_matrices[raw joint] * v. The mesh
//   node's own transform is ignored, as the spec requires for skinned meshes. Meshes are returned in
//   the skeleton's rest space: when skin 0's root joint binds elsewhere (X = its rest model matrix
//   times its inverse bind matrix is not the identity: a mesh under a Z-up node, gltfpack's
//   quantised integer positions, a centimetre mesh), vertices become X v and inverse bind matrices
//   ibm X^-1, skinning unchanged, with a note. Skin 0's matrices are
//   kept; a later skin whose matrices of shared joints differ by an offset B (its mesh bound in
//   another space) has its new joints' matrices and its vertices brought into skin 0's space by B,
//   which is exact when the vertex's joints agree on B (otherwise the largest weight's joint wins,
//   with a note).
// - A node with a mesh and no skin under a joint node (or that is one) is a rigid part: its
//   vertices are bound with weight 1 to the nearest joint at or above it, carrying the transforms
//   of the nodes between (mirroring flips the triangles' winding, as the spec's determinant rule
//   says). Meshes with no skin and no joint above them are left out with a note.
// - GltfSkinnedMesh::joints holds RUNTIME joint indices (of build_skeleton(skeleton)); one
//   GltfSkinnedMesh per primitive and per node using the mesh. TRIANGLES, TRIANGLE_STRIP and
//   TRIANGLE_FAN primitives are read (strips and fans become lists); points and lines are left out
//   with a note. Weights (JOINTS_0/WEIGHTS_0 and, when present, JOINTS_1/WEIGHTS_1, of which the
//   4 largest are kept) are normalised to sum 1; sums off 1 by more than the quantisation allows
//   get one note. A missing NORMAL is computed flat (each triangle gets its own corners carrying
//   its face normal, as the spec requires; one note). Missing indices become 0..n-1. Morph
//   targets: the shape at the default weights (node.weights, else mesh.weights, else 0: the base
//   shape) is kept, one note; `weights` animation channels are skipped with one note per file.
// - Materials: baseColorFactor, alpha mode, KHR_materials_unlit, metallic and roughness factors, and the base
//   colour, normal, occlusion, emissive and metallic-roughness textures (their factors baked in; the same
//   texCoord set and KHR_texture_transform as the material's first texture, applied to the texture
//   coordinates; sampler wrap modes); images are decoded (PNG, JPEG via stb_image, WebP via libwebp) into
//   RGBA8; an image that cannot be decoded leaves its materials without it, with a note. Every lit material is
//   metallic-roughness (SurfaceMaterial::metallic_roughness).
// - Clips: tracks indexed by RUNTIME joint. Key times are shifted so the earliest key of the clip
//   is at 0; start_offset keeps that original time; duration = last key - first key (CesiumMan:
//   2.0 - 0.041667 = 1.958333 s). Unnamed clips are called "clip<index>". LINEAR keys are kept;
//   STEP keys are expanded to hold each value until 1e-4 s (at most a quarter of the gap) before
//   the next key so linear sampling reproduces the steps; CUBICSPLINE keeps only the value of each
//   (in-tangent, value, out-tangent) triple, i.e. it is resampled as linear.
// - Data: sparse accessors (also over an accessor without bufferView: zeros), KHR_mesh_quantization's
//   integer vertex types and EXT_meshopt_compression's compressed buffer views are read; a file that
//   requires any other extension is refused, naming it (gltf_buffers.cpp).
// - Humanoid: a VRM file's humanoid bones (VRMC_vrm 1.0 or VRM 0.x: humanoid.humanBones, bone name
//   -> node) become `humanoid` (canonical joint -> joint name, engine/anim/humanoid_map.hpp), so a
//   VRM character maps whatever its nodes are called; bones that are no canonical joint (fingers,
//   eyes) or no skin joint are noted; a malformed declaration is an error naming its JSON path.
// - Names: unnamed joints are called "node<index>"; a joint name used twice gets "_node<index>"
//   appended (with a note); any other characters (dots, colons, spaces) are kept as they are.
#pragma once

#include "engine/anim/humanoid_map.hpp"
#include "engine/anim/raw_animation.hpp"
#include "engine/anim/raw_skeleton.hpp"
#include "engine/assets/surface_material.hpp"
#include "engine/core/result.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace aloha {

/// One skinned triangle mesh (a primitive) in bind space (the space inverse bind matrices map from),
/// which the loader makes the skeleton's rest space (see the conventions above).
struct GltfSkinnedMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;   ///< unit length, one per position
    std::vector<glm::u16vec4> joints; ///< runtime skeleton joint indices, one per position
    std::vector<glm::vec4> weights;   ///< non-negative, sum 1, one per position
    std::vector<glm::vec2> uvs;       ///< the material texture's coordinates, one per position (empty: none)
    std::vector<glm::vec4> colours;   ///< COLOR_0: LINEAR RGBA in [0, 1] multiplying the base colour, one per position (empty: none)
    std::vector<uint32_t> indices;    ///< triangle list, each < positions.size()
    int material = -1;                ///< index into GltfCharacter::materials, -1 = the default (white)
    std::string source;               ///< "nodes[3] meshes[1].primitives[0]", for notes and tests
};

/// A character read from a glTF file.
struct GltfCharacter {
    RawSkeleton skeleton;                           ///< joints in skin order (raw order)
    std::vector<glm::mat4> inverse_bind_matrices;   ///< per raw joint
    std::vector<GltfSkinnedMesh> meshes;            ///< primitives of skinned and rigid meshes
    std::vector<SurfaceMaterial> materials;         ///< referenced by GltfSkinnedMesh::material
    std::vector<TextureImage> textures;             ///< referenced by SurfaceMaterial::texture
    std::vector<RawAnimation> clips;                ///< tracks in runtime joint order
    std::vector<std::string> clip_names;            ///< clips[i].name, "" in the file -> "clip<i>"
    DeclaredHumanoid humanoid;                      ///< the file's own humanoid bones (VRM), empty without
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
