// The impostor level's records and atlas layout, shared by the renderer (systems/render/crowd_renderer.hpp),
// its draw-order and far-layer planning, and the atlas bake.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace aloha {

/// How impostors drawn at full resolution show the baked pictures about the camera's direction and elevation and the
/// character's walk phase (the far layers always show the nearest; shaders/impostor.*).
enum class ImpostorViews : uint8_t {
    Nearest,  ///< the nearest direction, phase and band: one atlas read a fragment
    Blend,    ///< the weighted mean of the neighbouring pictures: up to four atlas reads a fragment
    Pick,     ///< one of the neighbouring pictures a pixel, by a 4 x 4 dither of their weights: one atlas read
};

/// The word for `views` on the command line and in reports: "nearest", "blend" or "pick".
[[nodiscard]] inline const char* impostor_views_name(ImpostorViews views) {
    return views == ImpostorViews::Blend ? "blend" : views == ImpostorViews::Pick ? "pick" : "nearest";
}

/// One impostor (the `impostor` geometric level): a camera-facing quad showing the cell of its type's atlas
/// (register_impostor_atlas) nearest the camera's direction and the walk phase. 64 bytes, copied as is.
struct ImpostorInstance {
    glm::vec4 position_scale{0.0f, 0.0f, 0.0f, 1.0f}; ///< xyz: character origin (world), w: its uniform scale
    glm::vec4 forward_phase{0.0f, 1.0f, 0.0f, 1.0f};  ///< xy: world (x, z) of the character's local +Z (unit);
                                                      ///< z: walk phase in [0, 1), < 0 the standing row;
                                                      ///< w: fade: 1 shown, (0, 1) dithered in, < 0 the complement
                                                      ///< of a mesh dithered at -w (shaders/impostor.frag)
    glm::vec4 colour{1.0f};                           ///< tint, multiplies the atlas albedo
    uint32_t atlas = 0;                               ///< id from CrowdRenderer::register_impostor_atlas
    uint32_t reserved[3] = {0, 0, 0};                 ///< padding (std430 uvec4)
};

/// ImpostorInstance::forward_phase.w of an impostor cross-faded with its mesh (or proxies) drawn at
/// `drawn_share` (DeformableMesh::dither, ProxyFade::share): -drawn_share, so the two cover each pixel once;
/// 1 (the whole impostor) when drawn_share <= 0.
[[nodiscard]] inline float impostor_fade(float drawn_share) { return drawn_share > 0.0f ? -drawn_share : 1.0f; }

/// How an impostor atlas image is laid out (systems/render/impostor_atlas.hpp builds one). The image's top
/// half holds colour cells (RGB premultiplied by coverage in alpha), the bottom half normal cells (0.5 + 0.5 N
/// in the bake camera's frame, premultiplied the same way); each half is `elevations` bands, one above the other,
/// of `directions` columns x `rows` rows. Band e shows the character from impostor_elevation(e, elevations) above
/// the horizon: its cells are the image plane of a camera looking down at that angle, centred on the pivot (the
/// point `bottom + height / 2` above the origin); band 0 is drawn on an upright quad, the others on a quad facing
/// the camera, stretched by impostor_band_stretch (shaders/impostor.vert).
struct ImpostorAtlasLayout {
    uint32_t directions = 16;  ///< columns: camera azimuths 2 pi c / directions in the character's frame (local +Z = 0)
    uint32_t rows = 9;         ///< per band: walk phases r / (rows - 1), then one standing row
    float width = 1.0f;        ///< the quad (one cell) in model units: width, centred on the origin
    float bottom = 0.0f;       ///< band 0 (level views): height of its lower edge above the origin
    float height = 1.8f;       ///< band 0: its height
    uint32_t elevations = 1;   ///< bands of views (>= 1): band 0 level, the others from above
    float elevated_height = 0.0f;  ///< bands 1.. : their cells' height in model units (> 0 when elevations > 1)
    float depth_ratio = 0.0f;  ///< the figure's mean depth along a level view over its height (impostor_band_stretch)
};

/// The most bands of views an atlas may have.
inline constexpr uint32_t kMaxImpostorElevations = 8;

/// impostor_blend_from's answer where impostors do not blend (they are drawn with the nearest-view pipeline, every quad
/// showing its nearest view and phase); also the largest value the push word's upper bits hold (impostor_mode_bits).
inline constexpr uint32_t kImpostorNeverBlend = 0xffffffu;

/// An impostor draw's push offsets.w: the atlas's bands of views (1 to kMaxImpostorElevations) in the low 8 bits, and
/// above them `upper`: for the blending pipeline (LitPipelines::impostor_blend) the quad height in pixels from which
/// neighbouring views and walk phases are blended (shaders/impostor.vert: the nearest one at or below it, a linear
/// blend from twice it, a ramp between; 0: blended at any size); for the nearest-view pipeline the alpha test's
/// threshold in 255ths (impostor_alpha_test_bits: a texel shows where its coverage reaches it).
[[nodiscard]] inline uint32_t impostor_mode_bits(uint32_t elevations, uint32_t upper) {
    return elevations | std::min(upper, kImpostorNeverBlend) << 8;
}

/// The nearest-view pipeline's alpha test for coverage `threshold` (0, 1]: in 255ths, rounded, 1 to 255 (one half:
/// 128, which shows exactly the texels a test against 0.5 shows: 8-bit coverage k / 255 >= 0.5 for k >= 128).
[[nodiscard]] inline uint32_t impostor_alpha_test_bits(float threshold) {
    return static_cast<uint32_t>(std::clamp(std::round(threshold * 255.0f), 1.0f, 255.0f));
}

/// The blend limit of the impostors drawn at full resolution: never when `blend` is off; else from the far layer's limit
/// `far_below_px` (pixels on the target), so that an impostor shows its nearest view as it reaches the far layer
/// (which draws the nearest: blending there would cost up to three fetches a fragment over the whole far crowd) and
/// blends fully from twice that size; at any size when there is no far layer (`far_below_px` <= 0).
[[nodiscard]] inline uint32_t impostor_blend_from(bool blend, float far_below_px) {
    if (!blend) return kImpostorNeverBlend;
    if (!(far_below_px > 0.0f)) return 0;
    return static_cast<uint32_t>(std::clamp(std::round(far_below_px), 1.0f, static_cast<float>(kImpostorNeverBlend - 1)));
}

/// The elevation (radians above the horizon) band `e` of `elevations` views the character from: evenly from level to
/// straight down, e x 90 / (elevations - 1) degrees (three bands: 0, 45 and 90; one band: level). The shader shows
/// the band nearest the camera's elevation (band 0 for a camera below the pivot), within 90 / (2 (elevations - 1))
/// degrees of it, or blending (the impostor_blend pipeline) the two bands either side of it. Requires e < elevations.
[[nodiscard]] inline float impostor_elevation(uint32_t e, uint32_t elevations) {
    return elevations > 1 ? 1.57079633f * static_cast<float>(e) / static_cast<float>(elevations - 1) : 0.0f;
}

/// How much taller a band's picture is drawn than baked when seen from elevation `seen` (radians) instead of its own
/// `baked`: a figure of height h and depth d along the view spans about h cos a + d sin a on the image plane of a
/// view from elevation a, so its picture from `baked` is stretched by (cos seen + k sin seen) / (cos baked + k sin
/// baked), k = d / h (ImpostorAtlasLayout::depth_ratio), on a quad facing the camera: its silhouette as tall as the
/// figure's would be (shaders/impostor.vert does this for the bands from above). 1 where seen = baked.
[[nodiscard]] inline float impostor_band_stretch(float seen, float baked, float depth_ratio) {
    return (std::cos(seen) + depth_ratio * std::sin(seen)) / (std::cos(baked) + depth_ratio * std::sin(baked));
}

/// The tallest of an impostor's quads in model units, whichever band it shows and from wherever it is seen (all are
/// centred on the pivot and `width` wide: the far layer's bounds): band 0's upright quad, or a band from above at
/// its largest stretch over the elevations it is shown at (within half a band's step of its own).
[[nodiscard]] inline float impostor_quad_height(const ImpostorAtlasLayout& l) {
    float tallest = l.height;
    if (l.elevations < 2) return tallest;
    const float step = 1.57079633f / static_cast<float>(l.elevations - 1);
    const float peak = std::atan(l.depth_ratio);  // where cos a + k sin a is largest
    for (uint32_t e = 1; e < l.elevations; ++e) {
        const float baked = impostor_elevation(e, l.elevations);
        const float seen = std::clamp(peak, baked - 0.5f * step, std::min(baked + 0.5f * step, 1.57079633f));
        tallest = std::max(tallest, l.elevated_height * impostor_band_stretch(seen, baked, l.depth_ratio));
    }
    return tallest;
}

}  // namespace aloha
