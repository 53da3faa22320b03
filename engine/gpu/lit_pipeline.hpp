// The lit-mesh and line pipelines (shaders/lit_mesh.*, shaders/line.*): vertex pulling from storage buffers,
// per-instance model matrix + colour, per-draw material (base colour factor; optional base colour, normal,
// occlusion, emissive and metallic-roughness textures at per-vertex UVs; optional per-vertex colours), a key light
// plus hemispherical ambient, diffuse or glTF metallic-roughness (shaders/pbr.glsl), depth test, push-constant camera.
#pragma once

#include "engine/core/result.hpp"

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <vector>

namespace aloha::gpu {

class Buffer;
class Context;

/// What the w component of LitPush::offsets selects.
enum LitMode : uint32_t {
    kLitMesh = 0,          ///< vertex-pulled mesh, albedo = instance colour * base colour
    kLitBoxes = 1,         ///< arithmetic unit boxes (proxies), flat normals
    kLitTexturedMesh = 2,  ///< mesh whose albedo is also multiplied by texture(set 1) at the vertex UVs
    kLitNormals = 4,       ///< per-pixel pipelines write 0.5 + 0.5 * the world normal instead of the lit colour
    /// The per-pixel pipelines turn the normal by the material's normal map (set 1 binding 2) at the vertex UVs,
    /// in a tangent frame from screen-space derivatives of the world position and UVs (with kLitTexturedMesh).
    kLitNormalMap = 8,
    /// The per-pixel pipelines scale the ambient light by the red channel of set 1 binding 3 (occlusion map).
    kLitOcclusion = 16,
    /// Every mesh pipeline adds set 1 binding 4 (emissive colour) to the lit colour, read at the vertex UVs (at
    /// (0, 0) without kLitTexturedMesh: a one-texel emissive texture).
    kLitEmissive = 32,
    /// Every mesh pipeline multiplies the albedo by the vertex's colour (set 1 binding 6, vec4 per vertex, shared
    /// by every character of the topology like the UVs), interpolated across the triangle.
    kLitVertexColour = 64,
    /// Every mesh pipeline lights with glTF's metallic-roughness model (shaders/pbr.glsl: a diffuse lobe of the
    /// non-metal share and a GGX specular lobe, under the key light and the hemisphere), metalness and roughness
    /// from set 1 binding 5 (blue, green) at the vertex UVs (at (0, 0) without kLitTexturedMesh: one texel). The
    /// per-pixel pipelines evaluate it per pixel; the vertex-lit ones at the vertices.
    kLitMetallicRoughness = 128,
};
/// The LitMode bits that only pipelines built with the code for them draw (LitPipelines::for_mode): lavapipe runs both
/// sides of a branch on a push constant (every masked texture read included) and sets up an interpolated colour for
/// every triangle, so code a material does not use is left out of the shaders it is drawn with (on crowd_10k's
/// close frames that code cost 2-4 ms a frame though no material used it: docs/PERFORMANCE.md).
inline constexpr uint32_t kLitMaterialMaps =
    kLitNormalMap | kLitOcclusion | kLitEmissive | kLitVertexColour | kLitMetallicRoughness;
/// The shader builds a material's LitMode bits call for: Plain (no kLitMaterialMaps bit: the project's own
/// materials), MetallicRoughness (that bit alone: most glTF materials), Maps (any other bit: every feature's code).
enum class LitVariant : uint32_t { Plain = 0, MetallicRoughness = 1, Maps = 2 };
/// The variant LitMode bits `mode` are drawn with.
[[nodiscard]] constexpr LitVariant lit_variant(uint32_t mode) {
    const uint32_t maps = mode & kLitMaterialMaps;
    return maps == 0 ? LitVariant::Plain : maps == kLitMetallicRoughness ? LitVariant::MetallicRoughness : LitVariant::Maps;
}

/// Bits 8..13 of LitPush::offsets.w for the dithered pipelines (LitPipelines::dithered): a mesh faded to
/// `share` in [0, 1] of its pixels keeps those whose 4x4 Bayer value b has (b + 0.5) / 16 < share, exactly
/// the pixels an impostor faded at -share does not keep (shaders/impostor.frag), so the two cover each pixel
/// once. The same float comparison as that shader, so the split is exact for every share. A negative share
/// keeps the complement of -share's pixels (kLitDitherComplement set): the other mesh of a mesh <-> mesh
/// cross-fade, as the impostor's negative fade.
[[nodiscard]] uint32_t lit_dither_bits(float share);
/// Bit of LitPush::offsets.w that turns the dithered pipelines' kept pixels into their complement.
inline constexpr uint32_t kLitDitherComplement = 1u << 13;
/// Bit of LitPush::offsets.w for an unlit material (glTF KHR_materials_unlit): every mesh pipeline writes the
/// albedo without the key light and hemisphere.
inline constexpr uint32_t kLitUnlit = 1u << 15;
/// Bit of LitPush::offsets.w that turns on the dithered pipelines' alpha test (lit_alpha_bits).
inline constexpr uint32_t kLitAlphaTest = 1u << 14;
/// Offsets.w bits of an alpha test at `cutoff` in [0, 1] for the dithered pipelines: kLitAlphaTest and the
/// cutoff in bits 16..31 (cutoff x 65535 rounded); fragments whose albedo alpha is below it are discarded.
/// A negative cutoff (no alpha test) gives 0.
[[nodiscard]] uint32_t lit_alpha_bits(float cutoff);

/// Textures a material set binds (set 1 bindings 1..5, in this order: MaterialTexture).
inline constexpr uint32_t kMaterialTextures = 5;
/// A material texture's place among a material set's textures (its binding is 1 + this).
enum MaterialTexture : uint32_t {
    kBaseColourTexture = 0,
    kNormalTexture = 1,
    kOcclusionTexture = 2,
    kEmissiveTexture = 3,
    kMetallicRoughnessTexture = 4,
};
/// A texture as a material set binds it (in SHADER_READ_ONLY_OPTIMAL layout).
struct MaterialImage {
    VkImageView view = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
};
/// The textures of a material set, in binding order (see kMaterialTextures).
using MaterialImages = std::array<MaterialImage, kMaterialTextures>;

/// Push constants shared by both pipelines (128 bytes, std430 layout of shaders/lit_mesh.vert).
struct LitPush {
    glm::mat4 view_proj{1.0f};  ///< Vulkan clip space from world (see vulkan_clip_from_gl())
    glm::vec4 light{0.0f, 0.0f, 1.0f, 0.2f}; ///< xyz: unit direction towards the light, w: ambient in [0,1]
    glm::vec4 camera{0.0f};     ///< w 1: xyz the camera's position in world space (normals are turned to face it);
                                ///< w 0 (an eye at infinity): xyz the unit direction towards it. The shaders take
                                ///< camera.xyz - world * camera.w as the way to the eye.
    glm::uvec4 offsets{0u};     ///< mesh: x vertex_base, y vertex_stride (0 = shared), z instance_base, w LitMode bits;
                                ///< lines: x first line vertex
    glm::vec4 base_colour{1.0f}; ///< the draw's material colour (display space), multiplies the albedo
};
static_assert(sizeof(LitPush) == 128, "LitPush must match the shader push-constant block");

/// The frame's lighting (set 0 binding 4, 48 bytes std430): ambient light is mix(ground, sky,
/// 0.5 + 0.5 n.y) (a hemisphere), the key light's colour multiplies its diffuse term.
struct LitLighting {
    glm::vec4 sky{1.0f};        ///< rgb: ambient colour from straight above
    glm::vec4 ground{1.0f};     ///< rgb: ambient colour from straight below
    glm::vec4 key{1.0f};        ///< rgb: key light colour
};
static_assert(sizeof(LitLighting) == 48, "LitLighting must match the shader's std430 struct");

/// One instance in binding 2: model matrix and RGBA colour (80 bytes, std430).
struct LitInstance {
    glm::mat4 model{1.0f};      ///< world from model
    glm::vec4 colour{1.0f};     ///< albedo RGB, alpha written as is
};
static_assert(sizeof(LitInstance) == 80, "LitInstance must match the shader's std430 struct");

/// One line vertex in binding 3 (32 bytes, std430).
struct LineVertex {
    glm::vec4 position{0.0f, 0.0f, 0.0f, 1.0f}; ///< world position (w ignored)
    glm::vec4 colour{1.0f};                     ///< RGBA written unlit
};
static_assert(sizeof(LineVertex) == 32, "LineVertex must match the shader's std430 struct");

/// The colour the lit shader writes for albedo `colour` and world normal `n` (already facing the camera):
/// colour.rgb * (ambient * mix(ground, sky, 0.5 + 0.5 n.y) + (1 - ambient) * key * max(dot(n, L), 0)),
/// clamped to [0, 1]. Used by tests to predict pixels.
[[nodiscard]] glm::vec3 lit_colour(glm::vec3 colour, glm::vec3 n, glm::vec4 light, const LitLighting& lighting = {});

/// Matrix taking OpenGL clip space (glm::perspective: y up, z in [-w, w]) to Vulkan clip space
/// (y down, z in [0, w]). Multiply it on the left of a glm projection.
[[nodiscard]] glm::mat4 vulkan_clip_from_gl();

/// Descriptor set layouts (set 0: bindings 0 positions float[], 1 normals float[], 2 LitInstance[],
/// 3 LineVertex[], 4 LitLighting (vertex and fragment stages), all storage buffers; set 1, the material: 0 UVs vec2[] (storage buffer),
/// 1 base colour texture (combined image sampler)), the pipeline layout (sets 0, 1 + LitPush), the three
/// pipelines and descriptor pools.
class LitPipelines {
public:
    /// Builds the pipelines for render passes compatible with `render_pass` (colour + D32 depth, see
    /// create_render_pass); the pool holds `max_sets` descriptor sets. `constant_fragments`: the mesh and
    /// vertex-lit pipelines use shaders/lit_constant.frag (unlit albedo, for profiling the fragment cost).
    [[nodiscard]] static Result<LitPipelines> create(const Context& ctx, VkRenderPass render_pass,
                                                     uint32_t max_sets = 4, bool constant_fragments = false);
    LitPipelines() = default;
    ~LitPipelines() { destroy(); }
    LitPipelines(LitPipelines&& other) noexcept;
    LitPipelines& operator=(LitPipelines&& other) noexcept;
    LitPipelines(const LitPipelines&) = delete;
    LitPipelines& operator=(const LitPipelines&) = delete;

    /// Triangle-list pipeline: lit, depth test and write, no culling (two-sided lighting).
    [[nodiscard]] VkPipeline mesh() const { return mesh_; }
    /// The mesh pipeline with back faces culled, for closed meshes wound counter-clockwise seen from
    /// outside in a right-handed world (proxy boxes, closed skins); about halves the rasteriser's work.
    [[nodiscard]] VkPipeline mesh_culled() const { return culled_; }
    /// The mesh pipeline lit per vertex (Gouraud: lit_mesh.vert built with VERTEX_LIT, lit_vertex.frag), no
    /// culling; same push constants and modes (kLitMesh, kLitTexturedMesh).
    [[nodiscard]] VkPipeline vertex_lit() const { return vertex_lit_; }
    /// vertex_lit() with back faces culled.
    [[nodiscard]] VkPipeline vertex_lit_culled() const { return vertex_lit_culled_; }
    /// The mesh (vertex_lit: the vertex-lit; culled: back faces culled) pipeline with a screen-door fade:
    /// the fragment shaders built with DITHER keep only the pixels lit_dither_bits() in offsets.w names. Only
    /// fading characters are drawn with it (the others' pipelines have no discard, so early depth stays on).
    [[nodiscard]] VkPipeline dithered(bool vertex_lit, bool culled) const { return dithered_[(vertex_lit ? 2 : 0) + (culled ? 1 : 0)]; }
    /// Builds, once per variant, the twins of the mesh, vertex-lit and dithered pipelines for lit_variant(`mode`)
    /// (shaders built with MATERIAL_PBR or MATERIAL_MAPS); nothing for Plain. Call it when a material with those
    /// bits is registered, not in a frame; a no-op once built, and with create()'s constant fragments (profiling draws
    /// every material with the plain pipelines).
    [[nodiscard]] Status ensure_variant(uint32_t mode);
    /// The pipeline to draw LitMode bits `mode` with where `pipeline` (one of mesh(), mesh_culled(), vertex_lit(),
    /// vertex_lit_culled(), dithered()) is the choice for a plain material: `pipeline` itself for LitVariant::Plain,
    /// else its twin of lit_variant(`mode`) (ensure_variant(`mode`) must have run); `pipeline` with constant fragments.
    [[nodiscard]] VkPipeline for_mode(VkPipeline pipeline, uint32_t mode) const;
    /// Impostor pipeline (shaders/impostor.*): non-indexed, 6 vertices per instance (one camera-facing quad),
    /// set 0 binding 2 read as 64-byte impostor records, set 1 binding 1 the atlas; depth test and write.
    [[nodiscard]] VkPipeline impostor() const { return impostor_; }
    /// The same, each quad blending its two nearest views, walk phases and bands (shaders/impostor.* compiled with
    /// BLEND: up to four atlas reads a fragment, the blend fading in with the quad's size from push offsets.w >> 8 px).
    [[nodiscard]] VkPipeline impostor_blend() const { return impostor_blend_; }
    /// The same neighbours, one of them a pixel by a dither of their weights (shaders/impostor.frag compiled with BLEND
    /// and PICK: one atlas read a fragment).
    [[nodiscard]] VkPipeline impostor_pick() const { return impostor_pick_; }
    /// Composite pipeline (shaders/composite.*, layout composite_layout()): 6 vertices, one quad over the NDC
    /// rectangle in LitPush::base_colour; where the layer in set 0 (composite_set; filtered at gl_FragCoord *
    /// camera.xy) covers at least half a pixel it writes the layer's colour and depth (the nearest of the four
    /// depth texels around), depth-tested LESS_OR_EQUAL against what is drawn at full resolution.
    [[nodiscard]] VkPipeline composite() const { return composite_; }
    /// The composite pipeline's layout: set 0 the layer (composite_set), the LitPush push constants.
    [[nodiscard]] VkPipelineLayout composite_layout() const { return composite_layout_; }
    /// Points a composite set (`reuse`, or a new one from a pool of kCompositeSets) at a layer's colour (in
    /// SHADER_READ_ONLY_OPTIMAL) and depth (in DEPTH_STENCIL_READ_ONLY_OPTIMAL) with their samplers. The set must
    /// not be in use by a pending command buffer.
    [[nodiscard]] Result<VkDescriptorSet> composite_set(VkImageView colour, VkSampler colour_sampler, VkImageView depth,
                                                        VkSampler depth_sampler, VkDescriptorSet reuse = VK_NULL_HANDLE);
    /// Composite sets the pool holds (one per frame in flight is what a renderer needs).
    static constexpr uint32_t kCompositeSets = 8;
    /// Line-list pipeline: unlit vertex colour, depth test LESS_OR_EQUAL.
    [[nodiscard]] VkPipeline lines() const { return lines_; }
    /// Layout for vkCmdPushConstants (stages vertex + fragment, LitPush) and vkCmdBindDescriptorSets.
    [[nodiscard]] VkPipelineLayout layout() const { return layout_; }
    /// Allocates one descriptor set from the pool (at most max_sets in total).
    [[nodiscard]] Result<VkDescriptorSet> allocate_set() const;
    /// Points `set` at the five buffers (whole ranges); each must be a non-empty storage buffer.
    /// The set must not be in use by a pending command buffer.
    void write_set(VkDescriptorSet set, const Buffer& positions, const Buffer& normals, const Buffer& instances,
                   const Buffer& lines, const Buffer& lighting) const;
    /// Allocates a material set (set 1) pointing at `uvs` (a non-empty storage buffer of vec2), the material's
    /// textures (`images`, in binding order) and `colours` (binding 5, a non-empty storage buffer of vec4 per
    /// vertex). Sets live as long as the pipelines.
    [[nodiscard]] Result<VkDescriptorSet> material_set(const Buffer& uvs, const Buffer& colours, const MaterialImages& images);
    /// material_set with one texture, `view` / `sampler`, at every texture binding and `uvs` also bound as the
    /// colours (impostor atlases, tests: drawn without kLitVertexColour).
    [[nodiscard]] Result<VkDescriptorSet> material_set(const Buffer& uvs, VkImageView view, VkSampler sampler);
    /// Releases everything now (also done by the destructor).
    void destroy();

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout material_layout_ = VK_NULL_HANDLE;
    std::vector<VkDescriptorPool> material_pools_;  ///< 256 sets each, a new one when full
    VkPipeline mesh_ = VK_NULL_HANDLE;
    VkPipeline culled_ = VK_NULL_HANDLE;
    VkPipeline lines_ = VK_NULL_HANDLE;
    VkPipeline vertex_lit_ = VK_NULL_HANDLE;
    VkPipeline vertex_lit_culled_ = VK_NULL_HANDLE;
    VkPipeline impostor_ = VK_NULL_HANDLE;
    VkPipeline impostor_blend_ = VK_NULL_HANDLE;
    VkPipeline impostor_pick_ = VK_NULL_HANDLE;
    VkPipeline composite_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout composite_set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout composite_layout_ = VK_NULL_HANDLE;
    VkDescriptorPool composite_pool_ = VK_NULL_HANDLE;
    VkPipeline dithered_[4] = {VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE};  ///< mesh, culled, vertex-lit, its culled
    /// Twins of mesh_, culled_, vertex_lit_, vertex_lit_culled_, dithered_[0..3], in that order, per LitVariant
    /// after Plain (VK_NULL_HANDLE until ensure_variant).
    std::array<std::array<VkPipeline, 8>, 2> twins_{};
    VkRenderPass render_pass_ = VK_NULL_HANDLE;  ///< what the pipelines are compatible with (for the twins)
    bool constant_fragments_ = false;            ///< create()'s profiling option: no twins
};

}  // namespace aloha::gpu
