// PNG files for frame captures and golden images (libpng, RGBA8).
#pragma once

#include "engine/core/result.hpp"
#include "engine/gpu/offscreen_target.hpp"

#include <cstdint>
#include <span>
#include <string>

namespace aloha::gpu {

/// Writes `rgba` (width * height * 4 bytes, top row first) as an 8-bit RGBA PNG at `path`.
/// Errors name the file and say what failed (size mismatch, cannot open, libpng error).
[[nodiscard]] Status write_png(const std::string& path, uint32_t width, uint32_t height,
                               std::span<const uint8_t> rgba);

/// Reads any 8-bit or 16-bit PNG at `path` and returns it converted to RGBA8.
/// Errors name the file (missing, not a PNG, corrupt).
[[nodiscard]] Result<Rgba8Image> read_png(const std::string& path);

}  // namespace aloha::gpu
