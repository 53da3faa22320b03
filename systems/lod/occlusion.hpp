// The lod_occlusion system: a cheap estimate of how much of each character is hidden behind the
// crowd in front of it. Nearer characters are rasterised into a coarse screen-space depth grid twice:
// as conservative inner shapes (torso, neck and head cores that every level's body covers), against
// which each visible character's bounds are tested (LodAttributes::occluded = 1: certainly hidden),
// and as body-sized shapes (legs, torso, head), against which the character's own body shapes are
// tested (occluded below 1: the estimated share of its body behind nearer bodies).
#pragma once

#include "components/lod.hpp"
#include "components/transform.hpp"
#include "systems/lod/attributes.hpp"

#include <span>
#include <string>
#include <vector>

namespace aloha {

/// The shapes and resolution of the estimate. Cores are vertical cylinders on the character's axis,
/// given as fractions of its height (y from the feet, radius); they must lie inside the drawn body
/// at every level and pose, so that "covered by cores" means "covered by bodies".
struct OcclusionParams {
    float cell_px = 2.0f;            ///< grid cell size in pixels (>= 1)
    float torso_y0 = 0.50f;          ///< torso core bottom (hips), fraction of height
    float torso_y1 = 0.78f;          ///< torso core top (below the shoulders)
    float torso_radius = 0.05f;      ///< torso core radius, fraction of height (8.75 cm at 1.75 m)
    float neck_y0 = 0.78f;           ///< neck core bottom (the torso core's top: no gap between them)
    float neck_y1 = 0.885f;          ///< neck core top (the head core's bottom)
    float neck_radius = 0.022f;      ///< neck core radius, fraction of height (3.9 cm at 1.75 m: inside the
                                     ///< 4 cm neck proxy box)
    float head_y0 = 0.885f;          ///< head core bottom (chin)
    float head_y1 = 0.97f;           ///< head core top
    float head_radius = 0.036f;      ///< head core radius, fraction of height
    /// Body-sized shapes of the estimate (not conservative: about the body's own widths, legs together),
    /// fractions of the height: y0, y1 from the feet, radius. Nearer characters' shapes, at their axis
    /// depth, cover the cells whose centres they hold; a character's own shapes give the cells counted.
    struct BodyShape {
        float y0, y1, radius;
    };
    BodyShape body_legs{0.0f, 0.48f, 0.075f};   ///< hips down, both legs (26 cm wide at 1.75 m)
    BodyShape body_torso{0.48f, 0.82f, 0.11f};  ///< hips to shoulders (38.5 cm wide)
    BodyShape body_head{0.82f, 1.0f, 0.055f};   ///< chin and head (19 cm wide)
    float body_cell_px = 4.0f;            ///< the estimate's grid cell size in pixels (>= 1)
    float enter_margin_px = 8.0f;    ///< a drawn character's bounds are grown by this much on screen before
                                     ///< testing, so becoming hidden needs a margin that staying hidden does
                                     ///< not (spatial hysteresis: no flicker from a pixel of sway)
};

/// Side of the square blocks of cells summarised for pass 2 (OcclusionGrid::block_nearest).
inline constexpr int kOcclusionBlock = 8;

/// Scratch that lives across frames: the depth grid (farthest core depth per cell, min over cores).
struct OcclusionGrid {
    int width = 0, height = 0;       ///< cells
    std::vector<float> depth;        ///< width * height view depths; +inf = nothing in front
    std::vector<float> part_depth;   ///< scratch of pass 1 in parts: the depths of parts 1.. (part 0 fills `depth`)
    /// Summary of `depth` per block of kOcclusionBlock x kOcclusionBlock cells (MergeParts fills it): the
    /// nearest and the farthest depth in the block, so pass 2 can answer "no cell covered" or "every cell
    /// covered" for a rectangle from its blocks without reading its cells (the same answer as cell by cell).
    int block_width = 0, block_height = 0;
    std::vector<float> block_nearest, block_farthest;
    std::vector<float> body;         ///< the estimate's grid (body_width x body_height): nearest body-shape axis depth per cell (+inf: none)
    std::vector<float> part_body;    ///< scratch of pass 1 in parts for `body`, as part_depth
    std::vector<float> body_block_nearest;  ///< nearest `body` depth per block (the estimate's quick "none")
    int body_width = 0, body_height = 0;              ///< the estimate's grid, cells
    int body_block_width = 0, body_block_height = 0;  ///< its blocks (body_block_nearest)
    /// Sizes the grids for `viewport_px`, `cell_px` and `body_cell_px`; allocates only when they grow.
    void resize(glm::vec2 viewport_px, float cell_px, float body_cell_px);
};

/// Fills LodAttributes::occluded for a crowd (all characters at once: every one may hide another).
///
/// Pass 1: for each core (wholly beyond the near plane: one the near plane cuts is drawn with a hole) of each visible character, the inner screen
/// rectangle of the core (the horizontal extent it covers at every height between its ends, at its
/// farthest depth) is rasterised inwards (only whole cells) with the core's farthest view depth.
/// Pass 1 also rasterises each visible character's body shapes (OcclusionParams::BodyShape) at their
/// axis depth into the estimate's grid, every cell whose centre they hold at every height (the inner
/// rectangle: an axis leaning on screen covers only the width it keeps from top to bottom).
/// Pass 2: for each visible character the outer rectangle of its bounds box (radius, height) is
/// rasterised outwards (grown by enter_margin_px unless the character is drawn Hidden now); when every
/// cell it touches (on screen) holds a core nearer than the bounds' nearest depth, occluded = 1 (every
/// cell checked). Otherwise occluded = the estimate, at most 0.99: the share of the cells of the
/// character's own body shapes (outer rectangles) whose body depth is nearer than its axis depth less
/// its torso radius, counted on every cell or on an even sample of about 16 per shape. A character's own
/// shapes never cover it (they are behind its nearest point). 0 for characters not visible or crossing
/// the near plane, and an estimate of 0 for characters under 4 cells of the estimate's grid tall (16 px
/// by default: their shapes are a cell or two wide) and from shapes narrower than a cell.
struct OcclusionJob {
    std::span<const Transform> transforms;    ///< n entries
    std::span<const Bounds> bounds;           ///< n entries, or empty (default Bounds)
    std::span<const GeomLod> geom;            ///< n entries (current levels: Hidden ones get no margin), or empty
    LodCamera camera;                         ///< the camera the attributes were measured with
    OcclusionParams params;                   ///< shapes and grid resolution
    OcclusionGrid* grid = nullptr;            ///< required: scratch, resized as needed
    std::span<LodAttributes> attributes;      ///< n entries: `visible` read, `occluded` written

    /// Checks sizes, grid and parameters; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Writes attributes[i].occluded for every i; returns how many are fully occluded. Requires Validate().
    /// The same as Rasterise() then Test(0, n), or ClearAll() where NoneCanBeHidden().
    size_t Run() const;
    /// True when fewer than two characters are visible: only visible characters hide others and nobody hides
    /// themselves, so every occluded is 0 and the grid need not be filled (a close-up's one character: the grid's
    /// fill and summary cost ~0.3 ms a frame at 1280 x 720). Requires Validate().
    [[nodiscard]] bool NoneCanBeHidden() const;
    /// Writes occluded = 0 for every character (what the passes give where NoneCanBeHidden()). Requires Validate().
    void ClearAll() const;
    /// Pass 1 alone: sizes and fills the grid. Requires Validate().
    void Rasterise() const;
    /// Pass 1 in `parts` (>= 1) parts that may run concurrently: PrepareParts(parts), then RasterisePart(p,
    /// parts) for every p (each rasterises an even share of the characters into a grid of its own), then
    /// MergeParts(parts) (the nearest depth of each cell). Gives the grid of Rasterise() bit for bit: a
    /// cell's depth is the least of the same depths in any order. Requires Validate().
    void PrepareParts(size_t parts) const;
    /// Rasterises the cores of part `part` of `parts` into its own grid (see PrepareParts).
    void RasterisePart(size_t part, size_t parts) const;
    /// Folds parts 1.. into the grid (see PrepareParts) and summarises it per block for pass 2.
    void MergeParts(size_t parts) const;
    /// Pass 2 alone for characters [begin, end) after Rasterise(); returns how many are fully occluded.
    /// Disjoint ranges may run concurrently (the grid is only read).
    size_t Test(size_t begin, size_t end) const;
};

}  // namespace aloha
