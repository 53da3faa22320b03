// Choosing the physical device: a real GPU when present, else lavapipe; overridable by name or index.
// Pure functions over a device summary, so the policy is testable without Vulkan.
#pragma once

#include "engine/core/result.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace aloha::gpu {

/// What the user asked for (ContextOptions::device or env ALOHA_DEVICE).
struct DeviceChoice {
    /// Auto: prefer discrete, then integrated/virtual GPU, then CPU. Cpu: a CPU device (lavapipe).
    /// Gpu: a non-CPU device (error when none). Index: the device at `index` in enumeration order.
    enum class Kind : uint8_t { Auto, Cpu, Gpu, Index };
    Kind kind = Kind::Auto;
    uint32_t index = 0;  ///< meaningful when kind == Index
};

/// Summary of one enumerated physical device, as the selection policy sees it.
struct DeviceSummary {
    std::string name;            ///< VkPhysicalDeviceProperties::deviceName
    int type = 0;                ///< VkPhysicalDeviceType value
    uint32_t api_version = 0;    ///< VkPhysicalDeviceProperties::apiVersion
    bool has_graphics_queue = false;  ///< some queue family supports graphics
};

/// Parses "" or "auto" (Auto), "lavapipe"/"llvmpipe"/"cpu" (Cpu), "gpu" (Gpu) or a decimal index.
/// Case-insensitive. `source` names where the text came from ("ALOHA_DEVICE") for the error message.
[[nodiscard]] Result<DeviceChoice> parse_device_choice(std::string_view text, std::string_view source);

/// Picks the index into `devices` satisfying `choice`; devices without a graphics queue or below
/// Vulkan 1.2 are never picked. Returns an error naming the choice and the devices seen when none fits.
[[nodiscard]] Result<uint32_t> pick_device(std::span<const DeviceSummary> devices, const DeviceChoice& choice);

}  // namespace aloha::gpu
