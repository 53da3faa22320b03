// The far layer: impostors and meshes small on screen, drawn into a target of half the frame's resolution
// (gpu::LayerTarget) and composited with their depth into what is drawn at full resolution
// (gpu::LitPipelines::composite). On lavapipe a small quad's or triangle's cost is per 4x4 block it touches,
// mostly along its edges, so it grows with the target's side: at half resolution the far crowd costs about half
// (docs/PERFORMANCE.md, "The far layer").
#pragma once

#include "systems/render/impostor_types.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace aloha {

/// The far layer's limit on a software rasteriser, where it halves the cost of small impostors
/// (docs/PERFORMANCE.md, "The far layer").
inline constexpr float kDefaultFarLayerBelowPx = 70.0f;

/// The far layer's limit for meshes on a software rasteriser: characters under 70 px tall, the size under which
/// impostors go there too (on tier low the meshes that small are the periphery's and fast movers'), where a triangle
/// covers a pixel or two and its cost is the blocks it touches. 120 px was the default until measurements showed no
/// gain beyond the machine's noise while walkers of 70-120 px visibly lost their detail at half resolution
/// (docs/PERFORMANCE.md, "Small meshes in the far layer" and "Lighter skinned meshes on tier low").
inline constexpr float kDefaultFarLayerMeshesBelowPx = 70.0f;

/// The far layer a CrowdRenderer draws when RendererOptions::far_layer_below_px is unset: kDefaultFarLayerBelowPx on a software rasteriser (a CPU
/// device, where a small quad's cost grows with the target's resolution), 0 on a GPU (where it buys nothing and
/// costs the far crowd half its resolution).
[[nodiscard]] inline float far_layer_default(bool cpu_device) { return cpu_device ? kDefaultFarLayerBelowPx : 0.0f; }

/// The same for meshes (RendererOptions::far_layer_meshes_below_px unset): kDefaultFarLayerMeshesBelowPx on a
/// software rasteriser, 0 on a GPU.
[[nodiscard]] inline float far_layer_meshes_default(bool cpu_device) { return cpu_device ? kDefaultFarLayerMeshesBelowPx : 0.0f; }

/// The far and distant layers' alpha test (RendererOptions::far_layer_alpha_test): a layer texel shows an impostor's
/// atlas where the coverage of the mip level one coarser than at full resolution reaches 0.42, not one half. At half
/// resolution a limb under a layer texel wide averages below one half and vanished: crowd_10k's far crowd drew 0.75x the
/// reference's character pixels against 0.90x with every impostor at full resolution; at 0.42 it draws 0.94x at the
/// same PSNR (25.08 against 25.09 dB; 0.35 drew 1.15x, fatter, at 24.85 dB). Chosen by those measurements
/// (docs/PERFORMANCE.md, "Twenty-sixth session"), not derived: no one threshold keeps every width's pixel count.
inline constexpr float kDefaultFarLayerAlphaTest = 0.42f;

/// How many times coarser than the frame the far layer is (each side), and the distant layer.
inline constexpr uint32_t kFarLayerDivisor = 2;
inline constexpr uint32_t kDistantLayerDivisor = 4;

/// The viewport height the far layer's limits are given at: a limit of L px applies as L * height / 720 on a target
/// `height` pixels high, so the same share of the screen goes to the layer at any resolution (at 480 x 270 a 120 px
/// limit would take every character of a crowd and soften it; scaled, it takes those under 45 px).
inline constexpr float kFarLayerReferenceHeight = 720.0f;

/// A far-layer limit `px` (given at kFarLayerReferenceHeight) on a viewport `viewport_height` pixels high.
[[nodiscard]] inline float far_layer_limit(float px, float viewport_height) { return px * viewport_height / kFarLayerReferenceHeight; }

/// One group of meshes drawn together (one topology, none cross-fading): records [first, first + count) of
/// FarLayerInput::mesh_order.
struct FarMeshGroup {
    uint32_t first = 0;
    uint32_t count = 0;
};

/// A mesh's extent for the far layer: its bounding sphere (world) and its height (world units, top to bottom).
struct FarMeshBound {
    glm::vec4 sphere{0.0f};  ///< xyz centre, w radius
    float height = 0.0f;     ///< world units
};

/// One run of impostor records of one atlas, in draw order: [first, split) are drawn at full resolution,
/// [split, distant) into the far layer (half resolution), [distant, end) into the distant layer (a quarter).
struct ImpostorRun {
    uint32_t first = 0;
    uint32_t split = 0;
    uint32_t end = 0;
    uint32_t atlas = 0;
    uint32_t distant = 0;
};

/// The layers a frame's impostor records are drawn in: full resolution, the far layer, the distant layer.
enum class ImpostorPart : uint8_t { Near, Far, Distant };

/// The records [begin, end) of `run` drawn in `part`.
[[nodiscard]] inline std::pair<uint32_t, uint32_t> run_part(const ImpostorRun& run, ImpostorPart part) {
    switch (part) {
        case ImpostorPart::Near: return {run.first, run.split};
        case ImpostorPart::Far: return {run.split, run.distant};
        case ImpostorPart::Distant: return {run.distant, run.end};
    }
    return {run.first, run.first};
}

/// What plan_far_layer decided for one frame.
struct FarLayerPlan {
    std::vector<ImpostorRun> runs;             ///< every run of the frame's impostor records, in order
    std::vector<uint32_t> mesh_splits;         ///< per FarLayerInput::mesh_groups entry: its records [first, split)
                                               ///< are drawn at full resolution, [split, first + count) in the layer
    uint32_t far_count = 0;                    ///< records and meshes in the far layer (0: no far pass)
    uint32_t distant_count = 0;                ///< records in the distant layer (0: no distant pass; neither: no composite)
    uint32_t far_meshes = 0;                   ///< of which meshes
    glm::vec4 ndc_rect{-1.0f, -1.0f, 1.0f, 1.0f};  ///< screen rectangle (Vulkan NDC x0, y0, x1, y1) holding every
                                               ///< far record's quad and the filter's reach: the composite's quad
    glm::vec4 distant_ndc_rect{-1.0f, -1.0f, 1.0f, 1.0f};  ///< the same for the distant layer's records
};

/// A frame's impostors and the limit of its far layer.
struct FarLayerInput {
    std::span<const ImpostorInstance> records;     ///< as the frame gives them: runs of equal atlas
    std::span<uint32_t> order;                     ///< the draw order (sort_impostors_nearest_first): order[k] is the
                                                   ///< record drawn k-th, each run sorted nearest first; partitioned here
    std::span<const float> depth;                  ///< each record's distance ahead of the camera (view-space -z)
    std::span<const ImpostorAtlasLayout> layouts;  ///< by atlas id (every record's atlas must be listed)
    glm::mat4 clip_from_world{1.0f};               ///< Vulkan clip space from world
    float focal_px = 0.0f;                         ///< pixels per unit of height at distance 1 (viewport height / 2
                                                   ///< * the projection's y scale); <= 0 (orthographic): no far layer
    float below_px = 0.0f;                         ///< a record goes to the far layer where its quad at scale 1 is under
                                                   ///< this many pixels tall; <= 0: no far layer
    float distant_below_px = 0.0f;                 ///< a far record goes on to the distant layer where its quad is under
                                                   ///< this many pixels tall; <= 0 (or no far layer): no distant layer
    float viewport_width = 1.0f;                   ///< full-resolution pixels (the rectangle's padding)
    float viewport_height = 1.0f;
    std::span<uint32_t> mesh_order;                ///< mesh draw order: each group's records nearest first; partitioned here
    std::span<const FarMeshGroup> mesh_groups;     ///< the groups that may go to the layer (not cross-fading)
    std::span<const FarMeshBound> mesh_bounds;     ///< by mesh id (the values of mesh_order); read only when
                                                   ///< meshes_below_px > 0
    std::span<const float> mesh_depth;             ///< by mesh id: distance ahead of the camera (view-space -z)
    float meshes_below_px = 0.0f;                  ///< a mesh goes to the far layer where it is under this many pixels
                                                   ///< tall (height * focal_px / depth); <= 0: no mesh in the layer
};

/// Moves each run's far records (quad under below_px tall, i.e. depth > focal_px * layout.height / below_px, and
/// not cross-fading: its dither pairs pixel for pixel with a mesh's at full resolution) behind its others in
/// `order`, keeping both parts nearest first, and sets the runs' splits; the far part's records under
/// distant_below_px tall (its farthest, a suffix of it) go to the distant layer. Each layer's rectangle bounds its
/// records' bounding spheres on screen, padded by two of its texels (the filter's reach); the whole screen when
/// one lies at or behind the eye's plane. Likewise each mesh group: its meshes under meshes_below_px
/// go behind its others, both parts nearest first, and their spheres join the rectangle.
void plan_far_layer(const FarLayerInput& in, FarLayerPlan& out);

}  // namespace aloha
