#include "engine/gpu/window_target.hpp"

#include "engine/gpu/vk_error.hpp"

#define GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstring>

namespace aloha::gpu {

Result<ContextOptions> window_context_options(bool validation) {
    if (glfwVulkanSupported() != GLFW_TRUE) return gpu_error("GLFW reports no Vulkan loader/ICD support");
    uint32_t n = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&n);
    if (names == nullptr) return gpu_error("glfwGetRequiredInstanceExtensions returned nothing (no window system?)");
    ContextOptions o;
    o.validation = validation;
    for (uint32_t i = 0; i < n; ++i) o.instance_extensions.emplace_back(names[i]);
    o.device_extensions.emplace_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    return o;
}

Result<std::unique_ptr<WindowTarget>> WindowTarget::create(Context& ctx, GLFWwindow* window, bool vsync) {
    std::unique_ptr<WindowTarget> t(new WindowTarget(ctx, window));
    Status s = t->build(vsync);
    if (!s) return s.error();
    return t;
}

Status WindowTarget::build(bool vsync) {
    ALOHA_VK_RETURN(glfwCreateWindowSurface(ctx_.instance(), window_, nullptr, &surface_));
    VkBool32 supported = VK_FALSE;
    ALOHA_VK_RETURN(vkGetPhysicalDeviceSurfaceSupportKHR(ctx_.physical_device(), ctx_.queue_family(), surface_,
                                                         &supported));
    if (!supported) return gpu_error("the graphics queue of '" + ctx_.device_name() + "' cannot present here");
    uint32_t nf = 0;
    ALOHA_VK_RETURN(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx_.physical_device(), surface_, &nf, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(nf);
    ALOHA_VK_RETURN(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx_.physical_device(), surface_, &nf, formats.data()));
    if (formats.empty()) return gpu_error("surface reports no formats");
    format_ = formats[0].format;
    colour_space_ = formats[0].colorSpace;
    for (const auto& f : formats)
        if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) {
            format_ = f.format;
            colour_space_ = f.colorSpace;
            break;
        }
    uint32_t nm = 0;
    ALOHA_VK_RETURN(vkGetPhysicalDeviceSurfacePresentModesKHR(ctx_.physical_device(), surface_, &nm, nullptr));
    std::vector<VkPresentModeKHR> modes(nm);
    ALOHA_VK_RETURN(vkGetPhysicalDeviceSurfacePresentModesKHR(ctx_.physical_device(), surface_, &nm, modes.data()));
    present_mode_ = VK_PRESENT_MODE_FIFO_KHR;  // always available
    if (!vsync) {
        for (VkPresentModeKHR want : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
            if (std::find(modes.begin(), modes.end(), want) != modes.end()) {
                present_mode_ = want;
                break;
            }
    }
    Result<VkRenderPass> rp = create_render_pass(ctx_.device(), format_, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    if (!rp) return rp.error();
    render_pass_ = rp.value();
    return build_swapchain();
}

Status WindowTarget::build_swapchain() {
    VkSurfaceCapabilitiesKHR caps{};
    ALOHA_VK_RETURN(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx_.physical_device(), surface_, &caps));
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (caps.currentExtent.width != UINT32_MAX) {
        extent_ = caps.currentExtent;
    } else {
        extent_.width = std::clamp(uint32_t(w), caps.minImageExtent.width, caps.maxImageExtent.width);
        extent_.height = std::clamp(uint32_t(h), caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    if (extent_.width == 0 || extent_.height == 0) return {};  // minimised: build later
    uint32_t count = std::max(caps.minImageCount + 1, 3u);
    if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);
    const bool can_copy = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
    VkSwapchainCreateInfoKHR sci{};
    sci.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
    sci.surface = surface_;
    sci.minImageCount = count;
    sci.imageFormat = format_;
    sci.imageColorSpace = colour_space_;
    sci.imageExtent = extent_;
    sci.imageArrayLayers = 1;
    sci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (can_copy ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
    sci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    sci.preTransform = caps.currentTransform;
    sci.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                             ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                             : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha &
                                                                        -caps.supportedCompositeAlpha);
    sci.presentMode = present_mode_;
    sci.clipped = VK_TRUE;
    sci.oldSwapchain = swapchain_;
    VkSwapchainKHR fresh = VK_NULL_HANDLE;
    ALOHA_VK_RETURN(vkCreateSwapchainKHR(ctx_.device(), &sci, nullptr, &fresh));
    destroy_swapchain_objects();
    swapchain_ = fresh;
    ++generation_;

    uint32_t n = 0;
    ALOHA_VK_RETURN(vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, nullptr));
    images_.resize(n);
    ALOHA_VK_RETURN(vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, images_.data()));
    Result<Image> depth = Image::create(ctx_, extent_.width, extent_.height, kDepthFormat,
                                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    if (!depth) return depth.error();
    depth_ = std::move(depth).value();
    VkSemaphoreCreateInfo semi{};
    semi.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
    for (VkImage img : images_) {
        VkImageViewCreateInfo vci{};
        vci.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
        vci.image = img;
        vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vci.format = format_;
        vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        ALOHA_VK_RETURN(vkCreateImageView(ctx_.device(), &vci, nullptr, &view));
        views_.push_back(view);
        Result<VkFramebuffer> fb = create_framebuffer(ctx_.device(), render_pass_, view, depth_.view(), extent_.width, extent_.height);
        if (!fb) return fb.error();
        framebuffers_.push_back(fb.value());
        VkSemaphore s = VK_NULL_HANDLE;
        ALOHA_VK_RETURN(vkCreateSemaphore(ctx_.device(), &semi, nullptr, &s));
        render_done_.push_back(s);
    }
    for (uint32_t i = 0; i <= n; ++i) {
        VkSemaphore s = VK_NULL_HANDLE;
        ALOHA_VK_RETURN(vkCreateSemaphore(ctx_.device(), &semi, nullptr, &s));
        acquire_ring_.push_back(s);
    }
    if (can_copy) {
        Result<Buffer> rb = Buffer::create(ctx_, VkDeviceSize(extent_.width) * extent_.height * 4,
                                           VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        if (!rb) return rb.error();
        readback_ = std::move(rb).value();
    }
    recreate_ = false;
    return {};
}

void WindowTarget::destroy_swapchain_objects() {
    const VkDevice dev = ctx_.device();
    vkDeviceWaitIdle(dev);
    for (VkFramebuffer fb : framebuffers_) vkDestroyFramebuffer(dev, fb, nullptr);
    for (VkImageView v : views_) vkDestroyImageView(dev, v, nullptr);
    for (VkSemaphore s : render_done_) vkDestroySemaphore(dev, s, nullptr);
    for (VkSemaphore s : acquire_ring_) vkDestroySemaphore(dev, s, nullptr);
    framebuffers_.clear();
    views_.clear();
    render_done_.clear();
    acquire_ring_.clear();
    images_.clear();
    depth_.destroy();
    readback_.destroy();
    if (swapchain_ != VK_NULL_HANDLE) vkDestroySwapchainKHR(dev, swapchain_, nullptr);
    swapchain_ = VK_NULL_HANDLE;
}

WindowTarget::~WindowTarget() {
    destroy_swapchain_objects();
    if (render_pass_ != VK_NULL_HANDLE) vkDestroyRenderPass(ctx_.device(), render_pass_, nullptr);
    if (surface_ != VK_NULL_HANDLE) vkDestroySurfaceKHR(ctx_.instance(), surface_, nullptr);
}

Result<AcquiredImage> WindowTarget::acquire() {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (w == 0 || h == 0) return AcquiredImage{};  // minimised
    if (recreate_ || swapchain_ == VK_NULL_HANDLE || uint32_t(w) != extent_.width || uint32_t(h) != extent_.height) {
        Status s = build_swapchain();
        if (!s) return s.error();
        if (swapchain_ == VK_NULL_HANDLE) return AcquiredImage{};
    }
    for (int attempt = 0; attempt < 2; ++attempt) {
        VkSemaphore sem = acquire_ring_[acquire_counter_ % acquire_ring_.size()];
        uint32_t index = 0;
        const VkResult r = vkAcquireNextImageKHR(ctx_.device(), swapchain_, UINT64_MAX, sem, VK_NULL_HANDLE, &index);
        if (r == VK_ERROR_OUT_OF_DATE_KHR) {
            Status s = build_swapchain();
            if (!s) return s.error();
            if (swapchain_ == VK_NULL_HANDLE) return AcquiredImage{};
            continue;
        }
        if (r != VK_SUCCESS && r != VK_SUBOPTIMAL_KHR) return vk_error("vkAcquireNextImageKHR", r);
        if (r == VK_SUBOPTIMAL_KHR) recreate_ = true;  // use this image, rebuild next time
        ++acquire_counter_;
        AcquiredImage a;
        a.view = TargetView{render_pass_, framebuffers_[index], extent_, format_};
        a.index = index;
        a.acquired = sem;
        a.render_done = render_done_[index];
        return a;
    }
    return gpu_error("vkAcquireNextImageKHR: swapchain stayed out of date after recreation");
}

Status WindowTarget::present(const AcquiredImage& image) {
    if (image.view.framebuffer == VK_NULL_HANDLE) return {};
    VkPresentInfoKHR pi{};
    pi.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
    pi.waitSemaphoreCount = 1;
    pi.pWaitSemaphores = &image.render_done;
    pi.swapchainCount = 1;
    pi.pSwapchains = &swapchain_;
    pi.pImageIndices = &image.index;
    const VkResult r = vkQueuePresentKHR(ctx_.queue(), &pi);
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) {
        recreate_ = true;
        return {};
    }
    if (r != VK_SUCCESS) return vk_error("vkQueuePresentKHR", r);
    return {};
}

Result<Rgba8Image> WindowTarget::read_back(const AcquiredImage& image) {
    if (image.view.framebuffer == VK_NULL_HANDLE || image.index >= images_.size())
        return gpu_error("WindowTarget::read_back: no image (minimised window?)");
    if (readback_.handle() == VK_NULL_HANDLE)
        return gpu_error("WindowTarget::read_back: the surface does not allow TRANSFER_SRC on swapchain images");
    const VkImage img = images_[image.index];
    const VkExtent2D ext = extent_;
    const VkBuffer dst = readback_.handle();
    Status s = ctx_.submit_once([&](VkCommandBuffer cmd) {
        record_colour_transition(cmd, img, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                 {VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT},
                                 {VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT});
        record_image_to_host_copy(cmd, img, ext, dst);
        record_colour_transition(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                                 {VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT},
                                 {0, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT});
    });
    if (!s) return s.error();
    Rgba8Image out = image_from_mapped(readback_.mapped(), ext);
    if (format_ == VK_FORMAT_B8G8R8A8_UNORM || format_ == VK_FORMAT_B8G8R8A8_SRGB)
        for (size_t i = 0; i < out.pixels.size(); i += 4) std::swap(out.pixels[i], out.pixels[i + 2]);
    return out;
}

}  // namespace aloha::gpu
