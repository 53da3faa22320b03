// Turning VkResult failures into aloha::Error values that name the Vulkan call that failed.
#pragma once

#include "engine/core/result.hpp"

#include <vulkan/vulkan.h>

#include <string_view>

namespace aloha::gpu {

/// Returns the enumerator name of `result` ("VK_ERROR_DEVICE_LOST"), or nullptr when it is not known.
[[nodiscard]] const char* vk_result_name(VkResult result);

/// Builds an Error for a failed Vulkan call: message "<call> failed: <name>", code = the VkResult,
/// path = "vulkan". Requires `result` != VK_SUCCESS.
[[nodiscard]] Error vk_error(std::string_view call, VkResult result);

/// Builds an Error for a Vulkan-side problem that has no VkResult (no device, missing feature).
[[nodiscard]] Error gpu_error(std::string message, int64_t code = 0);

}  // namespace aloha::gpu

/// Evaluates a Vulkan call; on failure returns vk_error("<call text>", result) from the enclosing function
/// (which must return Status or Result<T>).
#define ALOHA_VK_RETURN(call)                                                   \
    do {                                                                        \
        const VkResult aloha_vk_result_ = (call);                               \
        if (aloha_vk_result_ != VK_SUCCESS)                                     \
            return ::aloha::gpu::vk_error(#call, aloha_vk_result_);             \
    } while (0)
