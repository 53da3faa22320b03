#include "engine/gpu/vk_error.hpp"

#include <string>

namespace aloha::gpu {

const char* vk_result_name(VkResult result) {
    switch (result) {
#define ALOHA_VK_CASE(x) \
    case x:              \
        return #x;
        ALOHA_VK_CASE(VK_SUCCESS)
        ALOHA_VK_CASE(VK_NOT_READY)
        ALOHA_VK_CASE(VK_TIMEOUT)
        ALOHA_VK_CASE(VK_EVENT_SET)
        ALOHA_VK_CASE(VK_EVENT_RESET)
        ALOHA_VK_CASE(VK_INCOMPLETE)
        ALOHA_VK_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        ALOHA_VK_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        ALOHA_VK_CASE(VK_ERROR_INITIALIZATION_FAILED)
        ALOHA_VK_CASE(VK_ERROR_DEVICE_LOST)
        ALOHA_VK_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        ALOHA_VK_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        ALOHA_VK_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        ALOHA_VK_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        ALOHA_VK_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        ALOHA_VK_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        ALOHA_VK_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        ALOHA_VK_CASE(VK_ERROR_FRAGMENTED_POOL)
        ALOHA_VK_CASE(VK_ERROR_UNKNOWN)
        ALOHA_VK_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        ALOHA_VK_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        ALOHA_VK_CASE(VK_ERROR_FRAGMENTATION)
        ALOHA_VK_CASE(VK_ERROR_SURFACE_LOST_KHR)
        ALOHA_VK_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        ALOHA_VK_CASE(VK_SUBOPTIMAL_KHR)
        ALOHA_VK_CASE(VK_ERROR_OUT_OF_DATE_KHR)
#undef ALOHA_VK_CASE
        default:
            return nullptr;
    }
}

Error vk_error(std::string_view call, VkResult result) {
    Error e;
    e.kind = ErrorKind::Gpu;
    e.path = "vulkan";
    const char* name = vk_result_name(result);
    e.message = std::string(call) + " failed: " +
                (name ? std::string(name) : "VkResult(" + std::to_string(static_cast<int>(result)) + ")");
    e.code = static_cast<int64_t>(result);
    return e;
}

Error gpu_error(std::string message, int64_t code) {
    Error e;
    e.kind = ErrorKind::Gpu;
    e.path = "vulkan";
    e.message = std::move(message);
    e.code = code;
    return e;
}

}  // namespace aloha::gpu
