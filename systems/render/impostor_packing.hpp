// Impostor atlas packing: the baked RGBA8 atlas (colour half on top, normal half below) turned into one
// texture of 64-bit texels, colour and normal of the same atlas point side by side (R32G32_UINT, each word
// four 8-bit channels), with its mip chain made here, so that shaders/impostor.frag reads both with one
// texelFetch instead of two (on lavapipe each fetch is a per-pixel gather; docs/PERFORMANCE.md).
#pragma once

#include "engine/assets/surface_material.hpp"

#include <cstdint>
#include <vector>

namespace aloha {

/// One half-height atlas with its mip chain: level m is max(width >> m, 1) x max(height >> m, 1) texels,
/// levels follow one another in `texels`, two words a texel (colour, then normal: r | g << 8 | b << 16 | a << 24,
/// what GLSL's unpackUnorm4x8 reads back).
struct PackedImpostorAtlas {
    uint32_t width = 0;             ///< level 0 texels across (the atlas's width)
    uint32_t height = 0;            ///< level 0 texels down (half the atlas's height)
    uint32_t levels = 0;            ///< 1 + floor(log2(max(width, height)))
    std::vector<uint32_t> texels;   ///< every level, rows top to bottom, (colour, normal) word pairs
};

/// Level `m` of a mip chain of RGBA8 texels from level m - 1 (`src`, sw x sh) as vkCmdBlitImage with
/// VK_FILTER_LINEAR makes it: each destination texel's centre mapped into the source and sampled bilinearly
/// there (clamped to the edge), rounded to the nearest 8-bit value; for even sizes the mean of 2 x 2 texels.
[[nodiscard]] std::vector<uint8_t> downsample_rgba8(const std::vector<uint8_t>& src, uint32_t sw, uint32_t sh);

/// Packs `image` (colour half on top, normal half below: an even height; rows top to bottom) with a full mip
/// chain of each half made by downsample_rgba8, the halves mipped apart so that no level mixes colour into
/// normals. Precondition: width > 0, even height > 0, rgba of width * height * 4 bytes.
[[nodiscard]] PackedImpostorAtlas pack_impostor_atlas(const TextureImage& image);

}  // namespace aloha
