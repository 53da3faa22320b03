// Per-pixel comparisons of RGBA8 frames for `aloha profile --fidelity`: the LOD frame against its
// full-detail reference (PSNR), against the frame before (the picture's change), and the change of its
// error against the reference from one frame to the next (what the LOD alone changed).
//
// Every image is RGBA8, row-major, alpha ignored; images of different sizes compare over the shorter.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace aloha::tool {

/// PSNR of `a` against `b` over RGB, in dB; identical images give 99.
[[nodiscard]] double psnr_db(std::span<const uint8_t> a, std::span<const uint8_t> b);

/// Per pixel, the summed |RGB change| from `before` to `now` (0..765) in `out`, and the mean absolute
/// change over every pixel and channel as a fraction of full scale (0..1) returned. Requires the two
/// images to be the same size (else 0, `out` empty).
double change_map(std::span<const uint8_t> now, std::span<const uint8_t> before, std::vector<uint16_t>& out);

/// The change of the LOD picture's error from one frame to the next: per pixel and channel,
/// |(lod - reference) - (lod_before - reference_before)|, summed over RGB (0..1530) into `out` (one
/// entry per pixel), and the mean over every pixel and channel as a fraction of full scale (0..2) returned.
/// Whatever the reference shares with the LOD picture (the camera moving, characters walking, the light)
/// cancels; what is left is the LOD's own change: a level switch that pops shows here at full size, a
/// cross-fade spreads it over its frames. Requires the four images to be the same size (else 0, `out` empty).
double error_change(std::span<const uint8_t> lod, std::span<const uint8_t> reference, std::span<const uint8_t> lod_before,
                    std::span<const uint8_t> reference_before, std::vector<uint16_t>& out);

/// How one picture's characters cover a reference picture's (silhouettes, where PSNR over the whole frame hardly sees a
/// far crowd drawn too small or not at all). A pixel is a character's where it differs from the reference's background
/// (its most common colour) by more than kSilhouetteLevels summed over RGB.
struct SilhouetteCoverage {
    uint64_t reference_pixels = 0;  ///< the reference's character pixels
    uint64_t pixels = 0;            ///< the other picture's
    double covered = 1.0;           ///< share of the reference's with one of the other's within 1 px (1 when it has none)
    double on_reference = 1.0;      ///< share of the other's with one of the reference's within 1 px (1 when it has none)
};

/// Summed |RGB| difference from the background over which a pixel is a character's (a tenth of one channel's range,
/// over the 8-bit noise of shading and dithering at the background's edge).
inline constexpr int kSilhouetteLevels = 24;

/// SilhouetteCoverage of `image` against `reference`, both `width` pixels wide (RGBA8 rows). Requires the two images to
/// be the same size, a whole number of rows (else all zero counts).
[[nodiscard]] SilhouetteCoverage silhouette_coverage(std::span<const uint8_t> image, std::span<const uint8_t> reference, uint32_t width);

}  // namespace aloha::tool
