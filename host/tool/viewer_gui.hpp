// Dear ImGui on a WindowTarget: the ImGui context with its GLFW and Vulkan backends, and a second
// render pass that draws the overlay over the crowd frame already in the swapchain image (colour
// loaded, not cleared) and signals the image's render_done semaphore for present().
#pragma once

#include "engine/core/result.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/window_target.hpp"

#include <vulkan/vulkan.h>

#include <memory>
#include <vector>

struct GLFWwindow;

namespace aloha::tool {

/// Owns the ImGui context and its Vulkan objects. One per process (ImGui's backends are global).
/// Destroy it before the WindowTarget and the Context.
class GuiLayer {
public:
    /// Creates the ImGui context (no imgui.ini), installs the GLFW callbacks on `window`, builds the
    /// overlay render pass (compatible with `target`'s framebuffers), a descriptor pool, one command
    /// buffer + fence per swapchain image, and uploads the font atlas. Errors name the Vulkan call.
    [[nodiscard]] static Result<std::unique_ptr<GuiLayer>> create(gpu::Context& ctx, GLFWwindow* window,
                                                                 const gpu::WindowTarget& target);
    /// Waits for the device, shuts the backends down and releases everything.
    ~GuiLayer();
    GuiLayer(const GuiLayer&) = delete;
    GuiLayer& operator=(const GuiLayer&) = delete;

    /// Starts an ImGui frame (backends + ImGui::NewFrame). Call once per loop iteration.
    void new_frame();
    /// Ends the ImGui frame without drawing it (when the image is skipped, e.g. minimised window).
    void discard_frame();
    /// Renders the ImGui frame and submits its pass into `image` after the crowd frame already
    /// submitted to the same queue; signals image.render_done. Requires a non-null framebuffer.
    [[nodiscard]] Status submit(const gpu::AcquiredImage& image);
    /// First Vulkan error ImGui's backend reported through its check callback (VK_SUCCESS if none).
    [[nodiscard]] static VkResult backend_error();

private:
    explicit GuiLayer(gpu::Context& ctx) : ctx_(ctx) {}
    Status init(GLFWwindow* window, const gpu::WindowTarget& target);

    struct Slot {
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
    };

    gpu::Context& ctx_;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    std::vector<Slot> slots_;
    uint64_t frame_ = 0;
    bool imgui_context_ = false;
    bool glfw_backend_ = false;
    bool vulkan_backend_ = false;
};

}  // namespace aloha::tool
