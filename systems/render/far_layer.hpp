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

/// RendererOptions::far_layer_below_px by default: on the software rasteriser the far layer halves the cost of
/// small impostors (docs/PERFORMANCE.md, "The far layer").
inline constexpr float kDefaultFarLayerBelowPx = 70.0f;

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

/// A frame's impostors and the limits of its far layer.
struct FarLayerInput {
    std::span<const ImpostorInstance> records;     ///< in draw order: runs of equal atlas, each nearest first
    std::span<const uint32_t> order;               ///< record k's index into `depth`
    std::span<const float> depth;                  ///< distance ahead of the camera (view-space -z) by that index
    std::span<const ImpostorAtlasLayout> layouts;  ///< by atlas id (every record's atlas must be listed)
    glm::mat4 clip_from_world{1.0f};               ///< Vulkan clip space from world
    float focal_px = 0.0f;                         ///< pixels per unit of height at distance 1 (viewport height / 2
                                                   ///< * the projection's y scale); <= 0 (orthographic): no far layer
    float below_px = 0.0f;                         ///< a record goes to the far layer only where its quad at scale 1
                                                   ///< is under this many pixels tall; <= 0: no far layer
    float beyond_depth = 0.0f;                     ///< and only beyond this distance (every mesh and proxy drawn at full
                                                   ///< resolution lies nearer, with its reach), so all it holds is behind
    float viewport_width = 1.0f;                   ///< full-resolution pixels (the rectangle's padding)
    float viewport_height = 1.0f;
};

/// True when the sphere (world centre, radius) lies wholly outside one of the view volume's side or near planes
/// of `clip_from_world` (Vulkan clip space: -w <= x, y <= w, 0 <= z): nothing of it can be on screen.
[[nodiscard]] bool sphere_outside_view(const glm::mat4& clip_from_world, const glm::vec3& centre, float radius);

/// Splits each run at its first record beyond both limits (depth > beyond_depth and quad height under
/// below_px, i.e. depth > focal_px * layout.height / below_px): the runs are nearest first, so the far
/// records are each run's tail. The rectangle bounds each far record's bounding sphere on screen, padded
/// by two layer texels (the bilinear filter's reach); the whole screen when one lies at or behind the eye.
/// Requires records sorted as described.
void plan_far_layer(const FarLayerInput& in, FarLayerPlan& out);

}  // namespace aloha
