// Tolerant image comparison and golden-image checks for rendering tests and tools.
#pragma once

#include "engine/core/result.hpp"
#include "engine/gpu/offscreen_target.hpp"

#include <cstdint>
#include <string>

namespace aloha {

/// How two RGBA8 images differ.
struct ImageDiff {
    bool same_size = false;          ///< false: sizes differ and nothing else is meaningful
    uint64_t differing_pixels = 0;   ///< pixels with some channel differing by more than the threshold
    double differing_fraction = 0.0; ///< differing_pixels / pixel count
    int max_channel_diff = 0;        ///< largest absolute channel difference over all pixels
};

/// Compares `a` and `b` pixel by pixel; a pixel differs when any channel differs by more than
/// `per_pixel_threshold` (0-255).
[[nodiscard]] ImageDiff compare_images(const gpu::Rgba8Image& a, const gpu::Rgba8Image& b,
                                       int per_pixel_threshold);

/// Tolerances for check_golden.
struct GoldenOptions {
    int per_pixel_threshold = 8;     ///< channel difference (LSB) a pixel may have and still match
    double max_fraction = 0.005;     ///< largest fraction of differing pixels that still passes
    std::string actual_dump_path;    ///< where to write `actual` when the check fails ("" = nowhere)
};

/// Compares `actual` with the PNG at `golden_path` under `options`. When env ALOHA_UPDATE_GOLDEN=1 it
/// writes `actual` to `golden_path` instead and succeeds. A missing golden file is an error (naming it and
/// the env var) unless updating; a mismatch is an error giving the differing fraction and largest difference.
[[nodiscard]] Status check_golden(const gpu::Rgba8Image& actual, const std::string& golden_path,
                                  const GoldenOptions& options = {});

}  // namespace aloha
