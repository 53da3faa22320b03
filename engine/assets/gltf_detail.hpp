// Internal helpers of the glTF loader (not part of the public API): validated accessor reads,
// node hierarchy checks and transform folding, mesh and clip conversion.
#pragma once

#include "engine/assets/gltf_loader.hpp"
#include "engine/core/result.hpp"

#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include <optional>
#include <string>
#include <string_view>
#include <utility>
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

/// What tinygltf refuses in compressed files, rewritten so it loads them: it takes a buffer without uri for
/// the GLB's BIN chunk (or, in a .gltf, for a missing file), so EXT_meshopt_compression's fallback
/// buffers (no uri, no data, "fallback": true) become one zero byte as a data URI; and it wants a
/// bufferView on every indices accessor, so a KHR_draco_mesh_compression primitive's indices accessor
/// without one gets the extension's (compressed) view. Both are replaced by decoded data in
/// prepare_buffers() before anything is read. Returns the file (GLB when `glb`) rewritten, or nullopt
/// when nothing needs it or it cannot be parsed (tinygltf then reports it).
std::optional<std::vector<unsigned char>> rewritten_for_tinygltf(const unsigned char* bytes, size_t size, bool glb);

/// The compression extensions' names.
inline constexpr std::string_view kMeshoptExtension = "EXT_meshopt_compression";
inline constexpr std::string_view kDracoExtension = "KHR_draco_mesh_compression";
/// The WebP texture extension's name (a texture's image source in WebP, gltf_material.cpp).
inline constexpr std::string_view kWebpExtension = "EXT_texture_webp";

/// The little-endian 32-bit value at `p` (GLB header and chunk fields).
inline uint32_t glb_u32(const unsigned char* p) {
    return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

/// A JSON value (an extension's member) as a non-negative integer, or -1 when it is not one (a fraction, a
/// negative number, a string, more than 9e15).
int64_t non_negative_integer(const tinygltf::Value& v);

/// Extensions a file may list in extensionsRequired and still be read.
std::vector<std::string> supported_required_extensions();

/// Runs before anything is read: fails (naming the extension and what to do) when the file requires an
/// extension outside supported_required_extensions(), and decodes every EXT_meshopt_compression buffer
/// view into a buffer of its own (the view then points at it, uncompressed), then every Draco primitive
/// (decode_draco_primitives). Errors name the view. `notes` gets one line per extension it decoded or
/// read (meshopt views, Draco primitives, KHR_mesh_quantization), for the character's notes.
Status prepare_buffers(tinygltf::Model* model, const std::string& file, std::vector<std::string>* notes);

/// Decodes every mesh primitive carrying KHR_draco_mesh_compression: each attribute the extension
/// names, and the indices, become plain data in a buffer of their own that the primitive's existing
/// accessors then point at (bufferView set, byteOffset 0), converted to each accessor's componentType,
/// type and normalized flag; the extension is then removed from the primitive. Errors name the
/// primitive ("meshes[0].primitives[1].extensions.KHR_draco_mesh_compression") and what is wrong.
/// `decoded` counts the primitives decoded.
Status decode_draco_primitives(tinygltf::Model* model, const std::string& file, size_t* decoded);

/// glTF's name of component type `c` ("UNSIGNED_SHORT"), or "unknown component type <c>".
std::string component_name(int c);

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

/// Per raw joint: its node and the folded non-joint ancestor transform applied to its keys.
struct JointBinding {
    int node = -1;
    glm::mat4 fold{1.0f};
    bool folded = false;
    std::vector<int> chain;  ///< the folded non-joint ancestor nodes, top-most first (fold = their product)
};

/// The character's joints gathered from every skin (see gltf_loader.hpp for the order).
struct SkinSet {
    std::vector<int> joint_of_node;                   ///< raw joint of each node, -1 for non-joints
    std::vector<JointBinding> bindings;               ///< per raw joint
    std::vector<std::vector<int>> raw_of_skin_joint;  ///< per skin: raw joint of skins[k].joints[i]
    std::vector<std::vector<glm::mat4>> skin_ibm;     ///< per skin: inverse bind of skins[k].joints[i] as in the file
};

/// A file without skins whose nodes carry meshes, or that has animations (an animation file: a Blender
/// armature exported without its mesh), gets one skin over every node of its displayed scene (parents
/// first), bound at the rest pose (inverse bind matrices: the nodes' inverted rest world matrices, in a
/// buffer of their own), so each mesh is a rigid part of its node and node animations are clips; one note.
/// Files with skins, or with neither meshes nor animations, are left as they are. Errors: a scene node out
/// of range, a singular rest transform, more than 32767 nodes.
Status add_node_skin(tinygltf::Model* model, const std::vector<int>& parents, const std::string& file, std::vector<std::string>* notes);

/// Reads every skin: fills out->skeleton (rest transforms with folded ancestors, unique names),
/// out->inverse_bind_matrices (per raw joint: skin 0's, then later skins' new joints brought into
/// skin 0's bind space through a shared joint) and notes.
Result<SkinSet> read_skins(const tinygltf::Model& model, const std::vector<int>& parents, const std::string& file,
                           GltfCharacter* out);

/// Reads the humanoid the file declares (VRM 1.0's VRMC_vrm or VRM 0.x's VRM extension:
/// humanoid.humanBones) into out->humanoid, canonical joint -> joint name, with notes for bones that
/// are not canonical joints (fingers, eyes, jaw) or not skin joints. No extension: nothing. Errors
/// (naming the JSON path under extensions.): a malformed humanBones, a node index out of range (-1: the
/// bone is ignored with a note), a bone declared twice, one node for two bones. Requires read_skins'
/// `skins` and out->skeleton.
Status read_declared_humanoid(const tinygltf::Model& model, const SkinSet& skins, const std::string& file, GltfCharacter* out);

/// How a material's base colour texture reads a primitive's texture coordinates: the TEXCOORD set
/// (-1: untextured) and the KHR_texture_transform matrix applied to them (identity without one).
struct MaterialUv {
    int texcoord = -1;
    glm::mat3 transform{1.0f};
};

/// Counters of things read but changed or left out while converting primitives, turned into one
/// note each by add_mesh_notes().
struct MeshNotes {
    size_t unnormalised_vertices = 0, unnormalised_primitives = 0;
    size_t flat_normal_primitives = 0;
    size_t morph_primitives = 0, morph_applied_primitives = 0;
    size_t eight_influence_primitives = 0;
    size_t skipped_primitives = 0;        ///< points and lines
    size_t bind_mismatch_vertices = 0;    ///< second-skin vertices whose joints disagree on the bind pose
    size_t untextured_primitives = 0;     ///< textured material but no such TEXCOORD set
    size_t coloured_primitives = 0;       ///< with COLOR_0
    std::vector<std::string> unattached;  ///< mesh nodes with no skin and no joint above them
};

/// How a primitive is tied to the skeleton: through a skin (skin-local joint index -> runtime joint)
/// or rigidly (weight 1) to one runtime joint.
struct PrimitiveBinding {
    const std::vector<int>* runtime_of_skin_joint = nullptr;  ///< skinned when set
    uint16_t rigid_joint = 0;                                 ///< runtime joint of a rigid part
    const std::vector<double>* morph_weights = nullptr;       ///< default morph weights (node's or mesh's)
};

/// Converts every primitive of mesh `mesh_index` used by node `node_index`; appends one
/// GltfSkinnedMesh per triangle primitive to `out`. Textured materials need their TEXCOORD set.
Status read_mesh(const tinygltf::Model& model, int node_index, int mesh_index, const PrimitiveBinding& binding,
                 const std::vector<SurfaceMaterial>& materials, const std::vector<MaterialUv>& material_uv,
                 const std::string& file, MeshNotes* notes, std::vector<GltfSkinnedMesh>* out);

/// Attaches every mesh node: skinned ones through their skin (second skins' bind differences
/// resolved per vertex), rigid ones to the nearest joint at or above them. `runtime_of_raw` maps raw
/// to runtime joints. Appends to out->meshes and notes.
Status attach_meshes(const tinygltf::Model& model, const std::vector<int>& parents, const SkinSet& skins,
                     const std::vector<int>& runtime_of_raw, const std::vector<MaterialUv>& material_uv,
                     const std::string& file, GltfCharacter* out);

/// Reads materials (base colour factor, base colour texture) and decodes the images they use into
/// out->materials / out->textures; `uv` gets each material's TEXCOORD set (-1 = no texture) and texture
/// transform (KHR_texture_transform: offset, rotation, scale, texCoord; checked finite).
/// Images that failed to decode (see ImageDecodeLog) leave their materials untextured with a note.
Status read_materials(const tinygltf::Model& model, const std::string& file, GltfCharacter* out,
                      std::vector<MaterialUv>* uv);

/// tinygltf image callback state: images that could not be decoded (index -> reason).
struct ImageDecodeLog {
    std::vector<std::pair<int, std::string>> failures;
};

/// tinygltf image loader: decodes PNG/JPEG with stb_image into RGBA8, refusing images larger than
/// 8192 x 8192; a failure is logged in the ImageDecodeLog passed as `user` and the load goes on.
/// An image stored in a bufferView is left for decode_buffer_view_images: tinygltf hands the callback
/// the view's bytes without checking that they lie inside the buffer.
bool decode_image(tinygltf::Image* image, int index, std::string* err, std::string* warn, int req_width,
                  int req_height, const unsigned char* bytes, int size, void* user);

/// Decodes every image stored in a bufferView (after tinygltf's load, which left them): a view whose
/// bytes do not lie inside its buffer is logged in `log` as a failure, like an image that does not decode.
void decode_buffer_view_images(tinygltf::Model* model, ImageDecodeLog* log);

/// Converts animation `index` into a clip with tracks in RAW joint order; notes skipped channels
/// (`weights` channels are only counted in `morph_channels`, for one note per file).
Result<RawAnimation> read_clip(const tinygltf::Model& model, int index, const std::vector<JointBinding>& joints,
                               const std::string& file, std::vector<std::string>* notes, size_t* morph_channels);

}  // namespace aloha::gltf_detail
