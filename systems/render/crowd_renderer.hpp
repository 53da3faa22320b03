// CrowdRenderer: draws a crowd frame (deformable meshes, instanced rigid proxies, lines) into a target.
// Inputs arrive per frame through spans (no ECS dependency); uploads go into persistently mapped,
// per-frame-in-flight buffers that grow only when exceeded.
#pragma once

#include "engine/assets/surface_material.hpp"
#include "engine/core/result.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/layer_target.hpp"
#include "engine/gpu/lit_pipeline.hpp"
#include "engine/gpu/offscreen_target.hpp"
#include "engine/gpu/texture.hpp"
#include "systems/render/far_layer.hpp"
#include "systems/render/impostor_types.hpp"

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace aloha {

namespace gpu {
class Context;
}

/// Camera matrices in OpenGL convention (glm::lookAt / glm::perspective); the renderer converts to Vulkan.
struct RenderCamera {
    glm::mat4 view{1.0f};  ///< view from world
    glm::mat4 proj{1.0f};  ///< OpenGL clip from view (y up, z in [-w, w])
    /// The way to the eye (two-sided normals, specular) is the view's +Z everywhere instead of towards the eye's
    /// position: for an orthographic view of things far off its axis (the impostor bake's cells, metres across).
    bool eye_at_infinity = false;
};

/// One character's deformed surface: vertices in model space over a registered topology.
struct DeformableMesh {
    uint32_t topology = 0;                   ///< id from CrowdRenderer::register_topology
    std::span<const glm::vec3> positions;    ///< exactly the topology's vertex_count entries
    std::span<const glm::vec3> normals;      ///< same count as positions (need not be unit length)
    glm::mat4 model{1.0f};                   ///< world from model
    glm::vec4 colour{1.0f};                  ///< albedo (e.g. a debug palette colour)
    float dither = 1.0f;                     ///< share of its pixels drawn: 1 all (the usual pipelines); in [0, 1) a
                                             ///< screen-door fade (gpu::lit_dither_bits), the complement of an
                                             ///< impostor with forward_phase.w = -dither (a cross-fade between them);
                                             ///< in [-1, 0) the complement of a mesh dithered at -dither (mesh <-> mesh)
};

/// One rigid proxy: the unit box [-0.5, 0.5]^3 transformed by `model` (see bone_box_matrix).
struct ProxyInstance {
    glm::mat4 model{1.0f};   ///< world from unit box
    glm::vec4 colour{1.0f};  ///< albedo
};

/// Proxies [first, first + count) of a frame drawn with a screen-door fade: `share` of their pixels, as
/// DeformableMesh::dither (one fading character's boxes, cross-faded with its impostor).
struct ProxyFade {
    uint32_t first = 0;   ///< first proxy of the run
    uint32_t count = 0;   ///< proxies in the run
    float share = 1.0f;   ///< in [0, 1]
};

/// What shaders/impostor.vert reads of an atlas (set 1 binding 0, vec4 each): first (cell width, cell height in
/// texels, mip levels, 0), then (the elevated bands' cell height in model units or 0 with one band, the depth ratio,
/// 0, 0), then per cell (row r of all bands' rows, band e's rows from e * rows; column d at 2 + r * directions + d)
/// the bounds of its colour
/// texels with alpha > 0 as fractions of the cell (x0, y0, x1, y1; x from the left, y from the bottom; all 0 for an
/// empty cell), so the quad covers only the silhouette. Precondition: `image` is whole cells of `layout`.
[[nodiscard]] std::vector<glm::vec4> impostor_cell_table(const TextureImage& image, const ImpostorAtlasLayout& layout);

/// One overlay line segment (bones, springs), drawn unlit and depth-tested.
struct LineSegment {
    glm::vec3 a{0.0f};       ///< start, world space
    glm::vec3 b{0.0f};       ///< end, world space
    glm::vec4 colour{1.0f};  ///< RGBA
};

/// Everything one frame draws. Spans must stay valid until render() returns (data is copied).
struct FrameInput {
    RenderCamera camera;                         ///< view and projection
    std::span<const DeformableMesh> meshes;      ///< batch (a): one draw per topology
    std::span<const ProxyInstance> proxies;      ///< batch (b): one instanced draw
    std::span<const LineSegment> lines;          ///< batch (c): one line-list draw
    std::span<const ImpostorInstance> impostors; ///< batch (d): one instanced quad draw per run of equal atlas
    bool write_normals = false;                  ///< meshes write 0.5 + 0.5 * world normal, not lit colour
                                                 ///< (impostor bakes; per-pixel-lit topologies only)
    glm::vec4 clear_colour{0.12f, 0.12f, 0.14f, 1.0f}; ///< background
    glm::vec3 light_direction{0.3f, 0.8f, 0.5f}; ///< towards the key light, world space (normalised here)
    float ambient = 0.3f;                        ///< 0..1 share of the hemisphere light; 1 with white sky and
                                                 ///< ground writes the albedo unlit
    glm::vec3 sky_colour{1.0f};                  ///< ambient light from straight above (hemisphere)
    glm::vec3 ground_colour{1.0f};               ///< ambient light from straight below
    glm::vec3 key_colour{1.0f};                  ///< key light colour
    bool materials = true;                       ///< draw topologies' materials (base colour, texture); false:
                                                 ///< the instance colour alone (debug colourings)
    std::span<const ProxyFade> proxy_fades;      ///< runs of `proxies` drawn dithered (ascending, disjoint; last, so
                                                 ///< positional initialisers of the fields above still hold): one draw
                                                 ///< each, the other proxies one draw per gap between runs
};

/// Light that reads as a character: a warm key light from the upper front right and a hemisphere from
/// a pale sky to a dark warm ground (ambient 0.45). Sets only the lighting fields of `frame`.
void set_character_lighting(FrameInput& frame);

/// The materials of a topology: per-vertex texture coordinates and material, and which registered
/// material each local material index is. Triangles take the material of their first vertex.
struct TopologySurface {
    std::span<const glm::vec2> uvs;               ///< one per vertex, or empty (no texture is sampled)
    std::span<const uint16_t> vertex_material;    ///< one per vertex (indices into `materials`), or empty
    std::span<const uint32_t> materials;          ///< ids from CrowdRenderer::register_material
    /// LINEAR RGBA per vertex multiplying the materials (glTF COLOR_0; drawn encoded as pow(rgb, 1/2.2), as base
    /// colour factors are), or empty (white). Requires materials.
    std::span<const glm::vec4> colours;
};

/// Where the renderer waits/signals for swapchain use; all optional.
struct FrameSync {
    VkSemaphore wait = VK_NULL_HANDLE;    ///< waited at colour-attachment output (image acquired)
    VkSemaphore signal = VK_NULL_HANDLE;  ///< signalled when the frame's commands finish (ready to present)
};

/// Whether material textures blend two mip levels when RendererOptions::blend_texture_mips is unset: not on a
/// software rasteriser (a CPU device), where the second level's fetches cost ~1 ms of crowd_10k's whole-frame p95
/// and the picture moves by 0.02 dB of --fidelity PSNR (docs/PERFORMANCE.md, fifteenth session, "Material textures
/// from the nearest mip level on tier low"); on a GPU, where blending costs nothing, yes.
[[nodiscard]] inline bool blend_texture_mips_default(bool cpu_device) { return !cpu_device; }

/// How impostors show their neighbouring views, walk phases and bands when RendererOptions::impostor_views is unset:
/// on a software rasteriser the nearest (the blending pipeline reads and shades every cell for every fragment, ~1.8
/// ms of crowd_1k's frame on lavapipe, while its default far layer leaves almost every impostor within the blend's
/// fade-in; Pick costs what the nearest does but its dither is noisy at crowd sizes: docs/PERFORMANCE.md,
/// "Twenty-seventh session"); on a GPU, where it costs nothing and every impostor is at full resolution, their
/// weighted mean (Blend: 17% less change from frame to frame on crowd_1k than the nearest).
[[nodiscard]] inline ImpostorViews impostor_views_default(bool cpu_device) {
    return cpu_device ? ImpostorViews::Nearest : ImpostorViews::Blend;
}

/// Construction options.
struct RendererOptions {
    VkFormat colour_format = VK_FORMAT_R8G8B8A8_UNORM; ///< format of the targets drawn into
    uint32_t frames_in_flight = 2;                     ///< 1..4 sets of per-frame buffers
    uint32_t initial_vertices = 1u << 16;              ///< initial per-frame vertex capacity
    uint32_t initial_instances = 1u << 12;             ///< initial per-frame instance capacity
    uint32_t initial_line_segments = 1u << 12;         ///< initial per-frame line capacity
    bool pass_timestamps = false;                      ///< a GPU timestamp after every pass (see GpuPassTime);
                                                       ///< on lavapipe each one flushes the binned scene, which
                                                       ///< costs a little (docs/PERFORMANCE.md gives the figure)
    bool constant_fragments = false;                   ///< meshes and proxies drawn with a constant-colour fragment
                                                       ///< shader (unlit albedo): profiling the fragment cost only
                                                       ///< (validation then warns of unread vertex outputs)
    std::optional<float> far_layer_below_px;           ///< impostors under this many pixels tall (at scale 1, on a
                                                       ///< 720-line target: scaled with its height, far_layer_limit) are
                                                       ///< drawn at half resolution and composited with their depth
                                                       ///< (systems/render/far_layer.hpp); 0: every impostor at full
                                                       ///< resolution; unset: far_layer_default(the context's device)
    std::optional<bool> blend_texture_mips;            ///< material textures read from the two nearest mip levels blended
                                                       ///< (trilinear) or from the nearest one (bilinear within it);
                                                       ///< unset: blend_texture_mips_default(the context's device)
    std::optional<float> far_layer_meshes_below_px;    ///< meshes under this many pixels tall, not cross-fading, likewise;
                                                       ///< 0: every mesh at full resolution; unset:
                                                       ///< far_layer_meshes_default(the context's device)
    float distant_layer_below_px = 0.0f;               ///< far impostors under this many pixels tall (at 720 lines, as
                                                       ///< above) are drawn at a quarter of the resolution instead of half
                                                       ///< (systems/render/far_layer.hpp); 0 (the default): none. On
                                                       ///< lavapipe 70 saves ~3.5 ms a frame on crowd_10k's close pass, but
                                                       ///< walkers of 30-70 px turn to blobs (docs/PERFORMANCE.md)
    float far_layer_alpha_test = kDefaultFarLayerAlphaTest;  ///< coverage from which an impostor's texel shows in the far
                                                       ///< and distant layers, (0, 1] (full resolution: 0.5)
    std::optional<ImpostorViews> impostor_views;       ///< how impostors at full resolution show their two nearest
                                                       ///< views, walk phases and bands: blended or picked per pixel,
                                                       ///< fading in from the far layer's limit to twice it
                                                       ///< (impostor_blend_from), or the nearest (the far layers always
                                                       ///< do); unset: impostor_views_default(the context's device)
    uint32_t max_texture_side = 2048;                  ///< material textures wider or taller are halved (2 x 2 means)
                                                       ///< until both sides fit, at registration: a crowd's character
                                                       ///< seldom covers more than 2048 pixels, and an 8192^2 texture
                                                       ///< takes 341 MiB with its mips; 0: no limit
};

/// GPU time of one pass of a completed frame (RendererOptions::pass_timestamps). Passes, in recording order:
/// "far meshes" and "far layer" (the small meshes, then the far impostors, at half resolution, before the frame's
/// render pass), "distant layer" (the farthest impostors at a quarter of the resolution), one per mesh pass label
/// (register_topology's `pass`: all topologies with that label, drawn together), "proxies", "impostors",
/// "lines", "composite" (the far and distant layers written in with their depth) and "resolve" (end of the render pass: tiles written out,
/// layout transition).
struct GpuPassTime {
    std::string name;        ///< pass label
    double begin_ms = 0.0;   ///< start, ms after the frame's first timestamp
    double ms = 0.0;         ///< duration (timestamp after the pass minus the one before)
    uint32_t draws = 0;      ///< draw calls recorded in the pass
    uint64_t instances = 0;  ///< characters (meshes) or boxes (proxies) or segments (lines) drawn
    uint64_t triangles = 0;  ///< triangles submitted (before culling and clipping)
};

/// Draws crowd frames on a gpu::Context. Not thread-safe; destroy before the Context.
class CrowdRenderer {
public:
    /// Builds pipelines, per-frame command buffers, fences, timestamp queries and buffers.
    [[nodiscard]] static Result<std::unique_ptr<CrowdRenderer>> create(gpu::Context& ctx,
                                                                       const RendererOptions& options = {});
    /// Waits for in-flight frames, then releases everything.
    ~CrowdRenderer();
    CrowdRenderer(const CrowdRenderer&) = delete;
    CrowdRenderer& operator=(const CrowdRenderer&) = delete;

    /// Registers a shared triangle index list (size a non-zero multiple of 3) once; vertex_count 0 means
    /// max index + 1. `cull_back_faces`: the mesh is closed and wound counter-clockwise seen from outside,
    /// so back faces are skipped (about half the raster work). Returns the id for DeformableMesh::topology.
    /// `surface` (optional) gives its materials: the index list is then reordered by material, one draw
    /// per material. `pass` labels the GPU pass it is drawn in (e.g. its LOD level's name): topologies are
    /// drawn grouped by label, in the order labels were first registered. `vertex_lighting`: the light is
    /// computed per vertex and interpolated (Gouraud) instead of per pixel, for characters small on screen:
    /// on lavapipe the fragment work per triangle is then a multiply (docs/PERFORMANCE.md).
    [[nodiscard]] Result<uint32_t> register_topology(std::span<const uint32_t> indices, uint32_t vertex_count = 0,
                                                     bool cull_back_faces = false, const TopologySurface& surface = {},
                                                     std::string_view pass = "meshes", bool vertex_lighting = false);
    /// Names mesh pass labels (register_topology's `pass`) in the order their topologies are to be drawn, before
    /// those topologies are registered; labels already named keep their place. Declaring the levels' names richest
    /// first draws the nearest characters first (richer levels go to nearer characters), so a software rasteriser
    /// skips the shading of what they hide, whichever level happened to be registered first.
    void declare_passes(std::span<const std::string> labels);
    /// Uploads a texture (RGBA8, rows top to bottom, colours as stored: sRGB-encoded) once, halved first while a
    /// side exceeds RendererOptions::max_texture_side; returns its id. Errors: empty or inconsistent image, Vulkan
    /// failures.
    [[nodiscard]] Result<uint32_t> register_texture(const TextureImage& image);
    /// The size texture `id` was uploaded at (after any halving). Requires a registered id.
    [[nodiscard]] glm::uvec2 texture_size(uint32_t id) const { return texture_sizes_.at(id); }
    /// Registers a material: `material.base_colour` is a LINEAR factor (glTF) and is drawn encoded as
    /// pow(rgb, 1/2.2), the display space the renderer shades in, so that factor x texel matches the
    /// sRGB encoding of their linear product. Its textures (texture, normal_texture, occlusion_texture,
    /// emissive_texture, metallic_roughness_texture; -1 = none) index `texture_ids`, ids from register_texture.
    /// Normal and occlusion maps are drawn by the levels lit per pixel; every level adds the emissive colour and
    /// lights `metallic_roughness` materials with that model (from the map, else from a one-texel texture of the
    /// factors made here, once per pair). Textures are read at the topology's UVs (a one-texel emissive texture
    /// also without UVs; without UVs metallic-roughness comes from the factors). Errors: an index outside
    /// `texture_ids`, an id not registered, factors out of range.
    [[nodiscard]] Result<uint32_t> register_material(const SurfaceMaterial& material, std::span<const uint32_t> texture_ids = {});
    /// Uploads an impostor atlas (image laid out as `layout` says, mipmapped) once; returns its id for
    /// ImpostorInstance::atlas. Errors: empty or inconsistent image or layout, Vulkan failures.
    [[nodiscard]] Result<uint32_t> register_impostor_atlas(const TextureImage& image, const ImpostorAtlasLayout& layout);
    /// Draws one triangle of every registered topology (each material, whole and dithered) and one quad of every
    /// impostor atlas into a small target of the frame's formats, and waits: a software rasteriser (lavapipe)
    /// compiles each pipeline's shader variant for the textures and target it meets at its first draw (~10 ms
    /// each), which would otherwise land in the frame where a level is first drawn or cross-faded. Call after
    /// registering; what is registered later is compiled when first drawn. Errors: Vulkan failures.
    [[nodiscard]] Status warm_up();
    /// Number of topologies registered so far.
    [[nodiscard]] size_t topology_count() const { return topologies_.size(); }
    /// Vertex count of a registered topology (0 when unknown).
    [[nodiscard]] uint32_t topology_vertex_count(uint32_t topology) const;

    /// Lists every problem in `frame` (unknown topology, wrong vertex/normal counts, dithers outside [0, 1],
    /// proxy fade runs out of order or range); true when none.
    bool Validate(const FrameInput& frame, std::vector<std::string>* errors = nullptr) const;
    /// Uploads `frame` and submits its draws into `target` (formats must match the options). Waits only
    /// for the frame that last used this frame slot. Errors: invalid input, Vulkan failures.
    [[nodiscard]] Status render(const FrameInput& frame, const gpu::TargetView& target, const FrameSync& sync = {});
    /// Same, into an offscreen target (read it back with target.read_back()).
    [[nodiscard]] Status render(const FrameInput& frame, gpu::OffscreenTarget& target);
    /// Waits for every submitted frame and collects its GPU time.
    [[nodiscard]] Status finish();

    /// GPU time of the most recently completed frame in ms (timestamp queries); -1 when unavailable.
    [[nodiscard]] double last_gpu_ms() const { return last_gpu_ms_; }
    /// The options this renderer runs with: those it was created with, every unset one resolved for the device
    /// (far_layer_default, far_layer_meshes_default, blend_texture_mips_default, impostor_views_default), and
    /// frames_in_flight as clamped. What a profile report records, so that runs on different devices compare.
    [[nodiscard]] RendererOptions resolved_options() const;
    /// Per-pass GPU times of the most recently completed frame; empty without pass_timestamps.
    [[nodiscard]] std::span<const GpuPassTime> last_gpu_passes() const { return last_passes_; }
    /// CPU time of the last frame's upload (copies into mapped buffers) in ms.
    [[nodiscard]] double last_upload_ms() const { return last_upload_ms_; }
    /// Bytes copied into GPU-visible buffers by the last frame.
    [[nodiscard]] uint64_t last_upload_bytes() const { return last_upload_bytes_; }
    /// Draw calls recorded by the last frame.
    [[nodiscard]] uint32_t last_draw_count() const { return last_draw_count_; }
    /// Times a per-frame buffer had to be reallocated because a frame exceeded its capacity.
    [[nodiscard]] uint32_t growth_events() const { return growth_events_; }
    /// The context it draws on (impostor bakes make renderers of their own on it).
    [[nodiscard]] gpu::Context& context() const { return ctx_; }
    /// Frames submitted so far.
    [[nodiscard]] uint64_t frame_count() const { return frame_index_; }

private:
    struct Range {  // triangles of one material in a topology's index list
        uint32_t first_index = 0;
        uint32_t index_count = 0;
        uint32_t material = 0;
        uint32_t mode = 0;                     // its LitPush::offsets.w bits: material_mode, kLitVertexColour
        VkDescriptorSet set = VK_NULL_HANDLE;  // the topology's UVs and colours + the material's textures
    };
    struct Topology {
        gpu::Buffer indices;
        uint32_t index_count = 0;
        uint32_t vertex_count = 0;
        bool cull_back_faces = false;
        gpu::Buffer uvs;              // empty without UVs
        gpu::Buffer colours;          // display-encoded vertex colours, empty without
        std::vector<Range> ranges;    // empty without materials
        uint32_t pass = 0;            // index into pass_names_
        bool vertex_lighting = false;  // lit per vertex (LitPipelines::vertex_lit), else per pixel
    };
    struct PassRecord {  // what a slot's command buffer drew in one timed pass
        uint32_t name = 0;            // index into pass_names_
        uint32_t draws = 0;
        uint64_t instances = 0, triangles = 0;
    };
    struct Material {
        glm::vec4 colour{1.0f};       // display-space base colour
        int textures[gpu::kMaterialTextures] = {-1, -1, -1, -1, -1};  // registered ids in gpu::MaterialTexture order, -1 = none
        bool texel_emissive = false;  // its emissive texture is one texel: drawn without UVs too
        int metallic_roughness_factors = -1;  // one texel of its metallic and roughness factors: drawn without a map or UVs
        uint32_t mode_bits = 0;       // its LitPush::offsets.w bits: gpu::lit_alpha_bits of its cutoff, gpu::kLitUnlit
    };
    struct Atlas {  // its layout is atlas_layouts_[id]
        gpu::Buffer cells;                     // impostor_cell_table: the texel grid, then each cell's bounds
        VkDescriptorSet set = VK_NULL_HANDLE;  // cells + the atlas texture
    };
    struct Slot {
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
        VkQueryPool queries = VK_NULL_HANDLE;
        uint32_t query_capacity = 0;
        std::vector<PassRecord> passes;  // timed passes recorded (query k + 1 ends pass k)
        VkDescriptorSet set = VK_NULL_HANDLE;
        gpu::Buffer positions, normals, instances, lines, lighting;
        gpu::Buffer proxy_indices;  // fill_box_batch_indices for proxy_capacity boxes (rewritten on growth)
        gpu::LayerTarget far_layer;  // half the target's size, made at the first frame with a far layer
        VkDescriptorSet far_set = VK_NULL_HANDLE;  // LitPipelines::composite_set sampling far_layer
        gpu::LayerTarget distant_layer;  // a quarter of the target's size, made at the first frame with a distant layer
        VkDescriptorSet distant_set = VK_NULL_HANDLE;  // LitPipelines::composite_set sampling distant_layer
        uint32_t proxy_capacity = 0;
        bool pending = false;
        bool set_dirty = true;
        uint64_t frame = 0;
    };

    explicit CrowdRenderer(gpu::Context& ctx) : ctx_(ctx) {}
    Status init(const RendererOptions& options);
    Status ensure(gpu::Buffer& buffer, uint64_t bytes, bool& grew);
    Status ensure_proxy_indices(Slot& slot, uint32_t boxes);
    Status retire(Slot& slot);
    uint64_t upload(const FrameInput& frame, Slot& slot, VkExtent2D extent);
    void plan_far_layer_for(const FrameInput& frame, VkExtent2D extent);
    // Makes `layer` 1 / `divisor` of `extent` (rounded up) with its composite set, unless it has that size.
    Status ensure_layer(gpu::LayerTarget& layer, VkDescriptorSet& set, VkExtent2D extent, uint32_t divisor);
    // Begins `layer`'s render pass (cleared to transparent) with a viewport 1 / divisor of `extent` and the frame's
    // descriptor sets bound; returns the viewport's height.
    float begin_layer_pass(VkCommandBuffer cmd, const Slot& slot, const gpu::LayerTarget& layer, uint32_t divisor, VkExtent2D extent);
    // Records the far layer's pass (far meshes, then far impostors) and the distant layer's, each where it has records.
    uint32_t record_far_layer(const FrameInput& frame, VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push, VkExtent2D extent);
    uint32_t record_distant_layer(VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push, VkExtent2D extent);
    // The pipeline of a topology's meshes that are not fading.
    [[nodiscard]] VkPipeline whole_pipeline(const Topology& topo) const;
    // Draws instances [first, first + count) of mesh group g (topology g / 2) with `pipeline` and the `dither` mode
    // bits, one draw per material; binds `pipeline` unless `bound` is it (and records it there). Returns the draws.
    uint32_t draw_mesh_group(VkCommandBuffer cmd, const FrameInput& frame, uint32_t g, uint32_t first, uint32_t count,
                             VkPipeline pipeline, uint32_t dither, gpu::LitPush& push, VkPipeline& bound);
    uint32_t record_composite(VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push);
    Status record(const FrameInput& frame, const gpu::TargetView& target, Slot& slot);
    Status init_materials();
    // The LitPush::offsets.w bits of drawing `m` on a topology with UVs (`uvs`) or without: its mode_bits and
    // one texture bit per texture it can sample there (Range::mode, set at registration).
    [[nodiscard]] static uint32_t material_mode(const Material& m, bool uvs);
    Status ensure_queries(Slot& slot, uint32_t count);
    uint32_t pass_id(std::string_view name);
    void end_pass(VkCommandBuffer cmd, Slot& slot, PassRecord pass);
    // Draws each run's impostor records of `part` (run_part) into a viewport `viewport_height` pixels high.
    uint32_t record_impostors(VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push, float viewport_height, ImpostorPart part);
    uint32_t record_proxies(const FrameInput& frame, VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push);
    [[nodiscard]] static uint32_t impostor_base(const FrameInput& frame);

    gpu::Context& ctx_;
    RendererOptions options_;
    gpu::LitPipelines pipes_;
    VkRenderPass compat_pass_ = VK_NULL_HANDLE;
    std::vector<Topology> topologies_;
    std::vector<gpu::Texture> textures_;
    std::vector<Material> materials_;
    std::vector<Atlas> atlases_;
    gpu::Texture white_;                              // 1x1 white: untextured draws
    std::vector<bool> texel_textures_;                // per registered texture: 1 x 1 texel
    std::map<std::pair<uint8_t, uint8_t>, uint32_t> factor_textures_;  // (metalness, roughness) bytes -> one-texel texture
    std::vector<glm::uvec2> texture_sizes_;           // per registered texture: its size as uploaded
    uint32_t max_texture_side_ = 0;                   // RendererOptions::max_texture_side
    gpu::Buffer no_colours_;                          // one white vec4: material sets of topologies without vertex colours
    gpu::Buffer no_uvs_;                              // one zero vec2: draws without UVs
    VkDescriptorSet plain_set_ = VK_NULL_HANDLE;      // no_uvs_ + white_
    std::vector<Slot> slots_;
    gpu::LayerTarget warm_target_;                    // warm_up()'s 8 x 8 target, made at its first call
    // Per-frame scratch, reused (capacity only grows): meshes ordered by topology, group offsets. Groups are
    // keyed 2 * topology + 1 for the dithered (fading) meshes of a topology, 2 * topology for the others.
    std::vector<uint32_t> order_;
    std::vector<uint32_t> group_start_;
    std::vector<uint32_t> group_count_;
    std::vector<uint32_t> group_vertex_base_;
    std::vector<uint32_t> group_cursor_;
    std::vector<float> depth_;                        // per mesh: distance ahead of the camera (draw order)
    std::vector<uint32_t> impostor_order_;            // impostors nearest first within each atlas's run
    std::vector<float> impostor_depth_;               // per impostor: distance ahead of the camera
    std::vector<ImpostorAtlasLayout> atlas_layouts_;  // by atlas id (drawing and the far layer's planning)
    float far_layer_below_px_ = 0.0f;                 // options_.far_layer_below_px resolved for the device
    bool blend_texture_mips_ = true;                  // options_.blend_texture_mips resolved for the device
    float far_layer_meshes_below_px_ = 0.0f;          // options_.far_layer_meshes_below_px resolved for the device
    ImpostorViews impostor_views_ = ImpostorViews::Nearest;  // options_.impostor_views resolved for the device
    std::vector<FarMeshGroup> far_mesh_groups_;       // per topology t: its whole group 2t's records in order_
    std::vector<FarMeshBound> far_mesh_bounds_;       // per mesh: measured where it may be under the mesh limit
    FarLayerPlan far_plan_;                           // this frame's impostor runs and far layer
    uint32_t impostor_base_ = 0;                      // this frame's first impostor record in the instance buffer
    std::vector<std::string> pass_names_;             // mesh pass labels, then fixed ones, by first use
    std::vector<uint32_t> draw_order_;                // topologies by pass (stable): the recording order
    std::vector<GpuPassTime> last_passes_;
    uint64_t frame_index_ = 0;
    double last_gpu_ms_ = -1.0;
    double last_upload_ms_ = 0.0;
    uint64_t last_upload_bytes_ = 0;
    uint32_t last_draw_count_ = 0;
    uint32_t growth_events_ = 0;
    uint64_t last_completed_frame_ = 0;
};

}  // namespace aloha
