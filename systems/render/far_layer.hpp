// The far layer: impostors far enough behind everything else that they can be drawn into a target of half
// the frame's resolution (gpu::LayerTarget) and composited behind what is drawn at full resolution
// (gpu::LitPipelines::composite). On lavapipe a small quad's cost is per 4x4 block it touches, mostly along
// its edges, so it grows with the target's side: at half resolution the far crowd costs about half
// (docs/PERFORMANCE.md, "The far layer").
#pragma once

#include "systems/render/impostor_types.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// The far layer's limit on a software rasteriser, where it halves the cost of small impostors
/// (docs/PERFORMANCE.md, "The far layer").
inline constexpr float kDefaultFarLayerBelowPx = 70.0f;

/// The far layer a CrowdRenderer draws when RendererOptions::far_layer_below_px is unset: kDefaultFarLayerBelowPx on a software rasteriser (a CPU
/// device, where a small quad's cost grows with the target's resolution), 0 on a GPU (where it buys nothing and
/// costs the far crowd half its resolution).
[[nodiscard]] inline float far_layer_default(bool cpu_device) { return cpu_device ? kDefaultFarLayerBelowPx : 0.0f; }

/// One run of impostor records of one atlas, in draw order: [first, split) are drawn at full resolution,
/// [split, end) into the far layer.
struct ImpostorRun {
    uint32_t first = 0;
    uint32_t split = 0;
    uint32_t end = 0;
    uint32_t atlas = 0;
};

/// What plan_far_layer decided for one frame.
struct FarLayerPlan {
    std::vector<ImpostorRun> runs;             ///< every run of the frame's impostor records, in order
    uint32_t far_count = 0;                    ///< records in the far layer (0: no far pass, no composite)
    glm::vec4 ndc_rect{-1.0f, -1.0f, 1.0f, 1.0f};  ///< screen rectangle (Vulkan NDC x0, y0, x1, y1) holding every
                                               ///< far record's quad and the filter's reach: the composite's quad
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
    float viewport_width = 1.0f;                   ///< full-resolution pixels (the rectangle's padding)
    float viewport_height = 1.0f;
};

/// Moves each run's far records (quad under below_px tall, i.e. depth > focal_px * layout.height / below_px, and
/// not cross-fading: its dither pairs pixel for pixel with a mesh's at full resolution) behind its others in
/// `order`, keeping both parts nearest first, and sets the runs' splits. The rectangle bounds each far record's
/// bounding sphere on screen, padded by two layer texels (the filter's reach); the whole screen when one lies
/// at or behind the eye's plane.
void plan_far_layer(const FarLayerInput& in, FarLayerPlan& out);

}  // namespace aloha
