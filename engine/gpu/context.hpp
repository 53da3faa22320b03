// The Vulkan context: instance (+ optional validation and debug messenger), physical device choice,
// logical device, one graphics queue, a command pool and a blocking one-shot submit helper.
#pragma once

#include "engine/core/result.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace aloha::gpu {

/// How to create a Context.
struct ContextOptions {
    /// Enable VK_LAYER_KHRONOS_validation (+ synchronisation validation) and a debug messenger that counts
    /// warnings and errors. Creation fails when the layer is missing.
    bool validation = false;
    /// Device choice ("lavapipe"/"cpu", "gpu", "auto" or an index). Empty: read env ALOHA_DEVICE, then auto.
    std::string device;
    /// Extra instance extensions (e.g. from glfwGetRequiredInstanceExtensions); all must be present.
    std::vector<std::string> instance_extensions;
    /// Extra device extensions (e.g. VK_KHR_swapchain); the chosen device must support all of them.
    std::vector<std::string> device_extensions;
    /// Application name reported to the driver.
    std::string app_name = "aloha";
    /// Optional log to receive validation messages; it outlives the Context, so a test can check that
    /// destruction itself reported nothing. Null: the Context keeps its own.
    std::shared_ptr<struct ValidationLog> log;
    /// On a CPU device (lavapipe), keep freed heap memory mapped (gpu::keep_freed_heap, process-wide): without
    /// it the binner's per-frame memory is page-faulted in again every frame.
    bool keep_freed_heap = true;
};

/// Thread-safe store of validation messages; the debug messenger writes into it.
struct ValidationLog {
    mutable std::mutex mutex;         ///< guards the members below
    uint32_t count = 0;               ///< warnings + errors seen since creation or the last clear
    std::vector<std::string> messages;///< their text (the first 256 are kept)
};

/// Owns every core Vulkan object. Not copyable or movable (the messenger holds a pointer to it); create it
/// with Context::create and destroy it after every object made from it. Use it from one thread at a time
/// (queue and command pool are not synchronised); only the validation log is thread-safe.
class Context {
public:
    /// Creates instance, (validation), device and queue as `options` say. Every Vulkan failure comes back as
    /// an Error whose code is the VkResult and whose message names the call.
    [[nodiscard]] static Result<std::unique_ptr<Context>> create(const ContextOptions& options);
    /// Waits for the device to go idle, then destroys everything in reverse order of creation.
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    /// The instance handle.
    [[nodiscard]] VkInstance instance() const { return instance_; }
    /// The chosen physical device.
    [[nodiscard]] VkPhysicalDevice physical_device() const { return physical_; }
    /// The logical device.
    [[nodiscard]] VkDevice device() const { return device_; }
    /// The graphics (and transfer) queue.
    [[nodiscard]] VkQueue queue() const { return queue_; }
    /// Family index of queue().
    [[nodiscard]] uint32_t queue_family() const { return queue_family_; }
    /// A command pool on queue_family() whose buffers may be reset individually.
    [[nodiscard]] VkCommandPool command_pool() const { return pool_; }
    /// Properties of the chosen physical device (name, limits, type).
    [[nodiscard]] const VkPhysicalDeviceProperties& properties() const { return props_; }
    /// Name of the chosen device ("llvmpipe (LLVM 15.0.6, 256 bits)").
    [[nodiscard]] std::string device_name() const { return props_.deviceName; }
    /// True when the chosen device is a CPU implementation (lavapipe).
    [[nodiscard]] bool is_cpu_device() const { return props_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }
    /// True when queue() supports timestamp queries.
    [[nodiscard]] bool timestamps_supported() const { return timestamp_valid_bits_ > 0; }
    /// Nanoseconds per timestamp tick.
    [[nodiscard]] float timestamp_period_ns() const { return props_.limits.timestampPeriod; }

    /// Index of a memory type allowed by `type_bits` having all `wanted` flags, or an error.
    [[nodiscard]] Result<uint32_t> find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags wanted) const;
    /// Records commands with `record` into a fresh command buffer, submits it and waits for completion.
    [[nodiscard]] Status submit_once(const std::function<void(VkCommandBuffer)>& record) const;
    /// Waits until the device has no work left.
    [[nodiscard]] Status wait_idle() const;

    /// Number of validation warnings and errors reported (0 when validation is off).
    [[nodiscard]] uint32_t validation_message_count() const;
    /// Text of the validation warnings and errors reported (at most 256 kept).
    [[nodiscard]] std::vector<std::string> validation_messages() const;
    /// Forgets the messages seen so far (count back to 0).
    void clear_validation_messages();
    /// True when the validation layer is active.
    [[nodiscard]] bool validation_enabled() const { return messenger_ != VK_NULL_HANDLE; }

private:
    Context() = default;
    Status init(const ContextOptions& options);

    std::shared_ptr<ValidationLog> log_ = std::make_shared<ValidationLog>();
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties props_{};
    VkPhysicalDeviceMemoryProperties mem_props_{};
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    uint32_t timestamp_valid_bits_ = 0;
    VkCommandPool pool_ = VK_NULL_HANDLE;
};

}  // namespace aloha::gpu
