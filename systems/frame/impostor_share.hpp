// Whether one character type's impostor pictures can stand for another's: body variants that differ in height
// only (a file's character scaled to each height: add_body_variants, host/scene/scene_loader.cpp) bake the same
// pictures at another size, so one atlas drawn larger or smaller serves them all (World::build_impostors). The
// test is on what the bake would draw, not a promise of the scene: the two bake inputs' surfaces, one scaled onto
// the other, must lie within a tolerance in the atlas's own pixels in every row and show about the same albedo,
// with the same materials, textures and views.
#pragma once

#include "systems/render/impostor_atlas.hpp"

#include <limits>

namespace aloha {

/// How `other`'s bake input compares with `owner`'s scaled (impostor_share_between).
struct ImpostorShare {
    bool comparable = false;  ///< same rows, views, materials, textures and culling; else nothing else is set
    float scale = 1.0f;       ///< `other` is about `owner` scaled by this about the origin (their heights' ratio)
    /// The largest distance, in `owner`'s bake pixels (impostor_texel_size) drawn at `other`'s size, from a vertex
    /// of either's row to the other's surface in the same row (rows are compared in parallel, each stopping at its
    /// first distance over the tolerance: then a lower bound); infinity when not comparable.
    float distance_px = std::numeric_limits<float>::infinity();
    /// The mean over the vertices compared of the albedo's difference (its largest channel, LINEAR, in 8-bit steps)
    /// between each vertex and the other's closest point: material base colour x base colour texture x vertex
    /// colour, as a bake draws them; 0 until every row was compared.
    float colour_steps = 0.0f;
    /// Whether the owner's atlas, drawn `scale` times as large, shows `other` within the tolerances.
    [[nodiscard]] bool shareable(float tolerance_px, float tolerance_steps) const {
        return comparable && distance_px <= tolerance_px && colour_steps <= tolerance_steps;
    }
};

/// The default distance tolerance of impostor_share_between, in atlas pixels. The default rules draw an impostor
/// only where its character is under 50 px tall on the screen (70 px on the software rasteriser: data/rules/
/// default.json) and a cell is 96 px tall for the figure's height and margins: one atlas pixel is at most 0.73
/// screen pixels there, so a shared picture's surface lies within a screen pixel of the type's own. Bodies
/// generated for two heights are not exact scales of each other (the body surface is polygonised on a grid of
/// fixed spacing in metres, then simplified): height variants of one character measured 0.7 to 2.1 atlas pixels
/// apart (docs/PERFORMANCE.md, "Shared impostor atlases"), so neighbouring heights share and distant ones do not.
inline constexpr float kImpostorShareTolerancePx = 1.0f;
/// The default albedo tolerance, in 8-bit steps on average. Materials and textures are equal already, so what it
/// catches is texture coordinates or vertex colours laid out otherwise; what it lets pass is a hem or a material
/// boundary moving by a triangle's width between two tessellations of the same body: height variants of one
/// generated body measured 2.7 to 4.1 steps, texture coordinates moved by one column of the generated body's
/// texture (a region's colour on another's surface) 114.6 (tests/systems/frame/impostor_share_test.cpp).
inline constexpr float kImpostorShareToleranceSteps = 8.0f;

/// The lowest and highest y of `in`'s vertices over every row (infinity and -infinity for none): the quantity whose
/// ratio is impostor_share_between's scale.
[[nodiscard]] glm::vec2 impostor_vertical_range(const ImpostorBakeInput& in);

/// Compares `other` with `owner` scaled by the ratio of their rows' vertical extents (about the origin, as an
/// ImpostorInstance's scale draws a quad). Comparable when both have the same number of rows, directions,
/// elevations, cell height in pixels, back-face culling, equal materials and textures, and per-vertex colours,
/// texture coordinates and materials either both or neither (and sizes that fit their vertices). Then, row by
/// row, each vertex of either is taken to the closest point of the other's surface in the same row (a
/// TriangleGrid each way): the largest distance, and the mean albedo difference there. A row stops at its first
/// distance over `tolerance_px`. Rows run in parallel (oneTBB); the result does not depend on the threads.
/// Load-time work: allocates.
[[nodiscard]] ImpostorShare impostor_share_between(const ImpostorBakeInput& owner, const ImpostorBakeInput& other,
                                                   float tolerance_px = kImpostorShareTolerancePx);

}  // namespace aloha
