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

}  // namespace aloha::tool
