#include "engine/gpu/device_choice.hpp"

#include "engine/gpu/vk_error.hpp"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <cctype>

namespace aloha::gpu {
namespace {

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

bool usable(const DeviceSummary& d) {
    return d.has_graphics_queue && d.api_version >= VK_API_VERSION_1_2;
}

bool is_cpu(const DeviceSummary& d) { return d.type == VK_PHYSICAL_DEVICE_TYPE_CPU; }

// Lower rank = preferred in Auto mode.
int auto_rank(const DeviceSummary& d) {
    switch (d.type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

std::string list_devices(std::span<const DeviceSummary> devices) {
    std::string out;
    for (size_t i = 0; i < devices.size(); ++i) {
        if (!out.empty()) out += ", ";
        out += std::to_string(i) + ": " + devices[i].name;
        if (!usable(devices[i])) out += " (unusable: needs Vulkan 1.2 and a graphics queue)";
    }
    return out.empty() ? "none" : out;
}

}  // namespace

Result<DeviceChoice> parse_device_choice(std::string_view text, std::string_view source) {
    const std::string t = lower(text);
    DeviceChoice c;
    if (t.empty() || t == "auto") return c;
    if (t == "lavapipe" || t == "llvmpipe" || t == "cpu") {
        c.kind = DeviceChoice::Kind::Cpu;
        return c;
    }
    if (t == "gpu") {
        c.kind = DeviceChoice::Kind::Gpu;
        return c;
    }
    if (t.size() <= 4 && std::all_of(t.begin(), t.end(), [](char ch) { return ch >= '0' && ch <= '9'; })) {
        c.kind = DeviceChoice::Kind::Index;
        c.index = static_cast<uint32_t>(std::stoul(t));
        return c;
    }
    Error e = gpu_error(std::string(source) + "='" + std::string(text) +
                        "' is not a device choice: use 'lavapipe' (or 'cpu'), 'gpu', 'auto' or a device index");
    e.path = std::string(source);
    return e;
}

Result<uint32_t> pick_device(std::span<const DeviceSummary> devices, const DeviceChoice& choice) {
    switch (choice.kind) {
        case DeviceChoice::Kind::Index:
            if (choice.index < devices.size() && usable(devices[choice.index])) return choice.index;
            return gpu_error("device index " + std::to_string(choice.index) +
                             " is not a usable device; devices: " + list_devices(devices));
        case DeviceChoice::Kind::Cpu:
            for (uint32_t i = 0; i < devices.size(); ++i)
                if (usable(devices[i]) && is_cpu(devices[i])) return i;
            return gpu_error("no CPU (lavapipe) Vulkan device; devices: " + list_devices(devices));
        case DeviceChoice::Kind::Gpu:
            for (int rank = 0; rank < 3; ++rank)
                for (uint32_t i = 0; i < devices.size(); ++i)
                    if (usable(devices[i]) && auto_rank(devices[i]) == rank) return i;
            return gpu_error("no GPU Vulkan device; devices: " + list_devices(devices));
        case DeviceChoice::Kind::Auto:
            break;
    }
    int best_rank = 99;
    uint32_t best = 0;
    for (uint32_t i = 0; i < devices.size(); ++i) {
        if (!usable(devices[i])) continue;
        const int r = auto_rank(devices[i]);
        if (r < best_rank) {
            best_rank = r;
            best = i;
        }
    }
    if (best_rank == 99) return gpu_error("no usable Vulkan device; devices: " + list_devices(devices));
    return best;
}

}  // namespace aloha::gpu
