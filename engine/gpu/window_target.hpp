// A GLFW window as a render target: surface, swapchain (+ depth, render pass, framebuffers), acquire /
// present, recreation on resize. Lives in aloha_gpu_window (aloha::gpu_window), the only library that
// links GLFW; headless code never includes this header.
#pragma once

#include "engine/core/result.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/offscreen_target.hpp"

#include <vulkan/vulkan.h>

#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace aloha::gpu {

/// ContextOptions for drawing into GLFW windows: GLFW's instance extensions + VK_KHR_swapchain.
/// Requires glfwInit() to have succeeded; errors when GLFW reports no Vulkan support.
[[nodiscard]] Result<ContextOptions> window_context_options(bool validation);

/// One acquired swapchain image, ready to be drawn into and presented.
struct AcquiredImage {
    TargetView view;                            ///< framebuffer of this image; null framebuffer = skip frame
    uint32_t index = 0;                         ///< swapchain image index
    VkSemaphore acquired = VK_NULL_HANDLE;      ///< signalled when the image may be written (wait on it)
    VkSemaphore render_done = VK_NULL_HANDLE;   ///< signal it when drawing is done; present() waits on it
};

/// Swapchain on a GLFW window. The window must outlive it; destroy it before the Context.
class WindowTarget {
public:
    /// Creates surface and swapchain for `window` (created with GLFW_CLIENT_API = GLFW_NO_API) on `ctx`
    /// (made from window_context_options). Picks B8G8R8A8_UNORM or R8G8B8A8_UNORM (non-sRGB, so colours
    /// match the offscreen target); `vsync` false prefers MAILBOX/IMMEDIATE over FIFO.
    [[nodiscard]] static Result<std::unique_ptr<WindowTarget>> create(Context& ctx, GLFWwindow* window,
                                                                      bool vsync = true);
    /// Waits for the device, then destroys swapchain objects and the surface.
    ~WindowTarget();
    WindowTarget(const WindowTarget&) = delete;
    WindowTarget& operator=(const WindowTarget&) = delete;

    /// Acquires the next image, recreating the swapchain first when the window size changed or the last
    /// present reported it out of date. A minimised (0 x 0) window gives a null framebuffer: skip the frame.
    [[nodiscard]] Result<AcquiredImage> acquire();
    /// Presents `image` after its render_done semaphore; marks the swapchain for recreation when out of date.
    [[nodiscard]] Status present(const AcquiredImage& image);
    /// Copies `image` to the CPU as RGBA8 (swizzling BGRA); call after its draw was submitted and before
    /// present(). Waits for the queue.
    [[nodiscard]] Result<Rgba8Image> read_back(const AcquiredImage& image);
    /// Asks for recreation at the next acquire (e.g. from a GLFW framebuffer-size callback).
    void notify_resized() { recreate_ = true; }

    /// Colour format of the swapchain images (give it to RendererOptions::colour_format).
    [[nodiscard]] VkFormat colour_format() const { return format_; }
    /// Current swapchain size in pixels.
    [[nodiscard]] VkExtent2D extent() const { return extent_; }
    /// Number of swapchain images.
    [[nodiscard]] uint32_t image_count() const { return static_cast<uint32_t>(images_.size()); }
    /// Times the swapchain was (re)created, including the first.
    [[nodiscard]] uint32_t swapchain_generation() const { return generation_; }

private:
    WindowTarget(Context& ctx, GLFWwindow* window) : ctx_(ctx), window_(window) {}
    Status build(bool vsync);
    Status build_swapchain();
    void destroy_swapchain_objects();

    Context& ctx_;
    GLFWwindow* window_ = nullptr;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkColorSpaceKHR colour_space_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    VkPresentModeKHR present_mode_ = VK_PRESENT_MODE_FIFO_KHR;
    VkExtent2D extent_{0, 0};
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkFramebuffer> framebuffers_;
    std::vector<VkSemaphore> render_done_;     // one per image
    std::vector<VkSemaphore> acquire_ring_;    // image_count + 1, used round-robin
    Image depth_;
    Buffer readback_;
    uint64_t acquire_counter_ = 0;
    uint32_t generation_ = 0;
    bool recreate_ = false;
};

}  // namespace aloha::gpu
