// Impostor atlases in the bake cache (engine/core/blob_store.hpp): a load reads a type's atlas back instead of
// rendering it again when nothing the bake reads has changed. The key is a 128-bit digest of everything the bake
// reads (ImpostorBakeInput: the mesh in every row's pose, its UVs, materials and textures, the directions and
// cell size) and of the device that renders it (vendor, device, driver version, pipeline-cache UUID: another
// driver rasterises differently); the store's code version (skin_bake_code_version: the digest of the library's
// sources, shaders and build settings) covers the bake code and its shaders, which are compiled into the library.
#pragma once

#include "systems/render/impostor_atlas.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace aloha {

/// The bake cache key of the atlas `in` bakes on a device with `device` properties.
[[nodiscard]] std::vector<uint8_t> impostor_atlas_key(const VkPhysicalDeviceProperties& device, const ImpostorBakeInput& in);

/// An atlas as the cache's payload: the image (size, texels, sampling), its layout and its GPU bytes.
[[nodiscard]] std::vector<uint8_t> write_impostor_atlas(const ImpostorAtlas& atlas);

/// The atlas a payload of write_impostor_atlas holds, or nothing when the bytes are not one whole, consistent
/// payload (wrong length, a size that disagrees with its texels, a layout with no cells). build_ms is 0.
[[nodiscard]] std::optional<ImpostorAtlas> read_impostor_atlas(std::span<const uint8_t> bytes);

}  // namespace aloha
