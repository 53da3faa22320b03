#include "host/tool/viewer_gui.hpp"

#include "engine/gpu/offscreen_target.hpp"
#include "engine/gpu/vk_error.hpp"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <algorithm>
#include <atomic>

namespace aloha::tool {

namespace {

std::atomic<int> g_backend_error{VK_SUCCESS};

void check_vk(VkResult r) {
    if (r != VK_SUCCESS) {
        int expected = VK_SUCCESS;
        g_backend_error.compare_exchange_strong(expected, static_cast<int>(r));
    }
}

}  // namespace

VkResult GuiLayer::backend_error() { return static_cast<VkResult>(g_backend_error.load()); }

Result<std::unique_ptr<GuiLayer>> GuiLayer::create(gpu::Context& ctx, GLFWwindow* window,
                                                   const gpu::WindowTarget& target) {
    std::unique_ptr<GuiLayer> g(new GuiLayer(ctx));
    if (Status s = g->init(window, target); !s.ok()) return s.error();
    return g;
}

Status GuiLayer::init(GLFWwindow* window, const gpu::WindowTarget& target) {
    const VkDevice dev = ctx_.device();
    // The overlay pass: the WindowTarget's attachments (so its framebuffers fit), colour loaded.
    Result<VkRenderPass> rp = gpu::create_render_pass(dev, target.colour_format(), VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                                                      /*load_colour=*/true);
    if (!rp) return rp.error();
    render_pass_ = rp.value();

    VkDescriptorPoolSize sizes[1] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8}};
    VkDescriptorPoolCreateInfo dpi{};
    dpi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    dpi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    dpi.maxSets = 8;
    dpi.poolSizeCount = 1;
    dpi.pPoolSizes = sizes;
    ALOHA_VK_RETURN(vkCreateDescriptorPool(dev, &dpi, nullptr, &pool_));

    const uint32_t images = std::max(target.image_count(), 2u);
    slots_.resize(images);
    for (Slot& s : slots_) {
        VkCommandBufferAllocateInfo ai{};
        ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
        ai.commandPool = ctx_.command_pool();
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        ALOHA_VK_RETURN(vkAllocateCommandBuffers(dev, &ai, &s.cmd));
        VkFenceCreateInfo fi{};
        fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
        fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
        ALOHA_VK_RETURN(vkCreateFence(dev, &fi, nullptr, &s.fence));
    }

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    imgui_context_ = true;
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // never write imgui.ini into the user's folder
    ImGui::StyleColorsDark();
    if (!ImGui_ImplGlfw_InitForVulkan(window, /*install_callbacks=*/true))
        return gpu::gpu_error("ImGui_ImplGlfw_InitForVulkan failed");
    glfw_backend_ = true;

    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = ctx_.instance();
    info.PhysicalDevice = ctx_.physical_device();
    info.Device = dev;
    info.QueueFamily = ctx_.queue_family();
    info.Queue = ctx_.queue();
    info.PipelineCache = VK_NULL_HANDLE;
    info.DescriptorPool = pool_;
    info.Subpass = 0;
    info.MinImageCount = 2;
    info.ImageCount = images;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.Allocator = nullptr;
    info.CheckVkResultFn = check_vk;
    if (!ImGui_ImplVulkan_Init(&info, render_pass_)) return gpu::gpu_error("ImGui_ImplVulkan_Init failed");
    vulkan_backend_ = true;

    bool fonts_ok = false;
    Status up = ctx_.submit_once([&](VkCommandBuffer cmd) { fonts_ok = ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    if (!up.ok()) return up;
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    if (!fonts_ok) return gpu::gpu_error("ImGui_ImplVulkan_CreateFontsTexture failed");
    if (backend_error() != VK_SUCCESS) return gpu::vk_error("ImGui Vulkan backend", backend_error());
    return {};
}

GuiLayer::~GuiLayer() {
    const VkDevice dev = ctx_.device();
    vkDeviceWaitIdle(dev);
    if (vulkan_backend_) ImGui_ImplVulkan_Shutdown();
    if (glfw_backend_) ImGui_ImplGlfw_Shutdown();
    if (imgui_context_) ImGui::DestroyContext();
    for (Slot& s : slots_) {
        if (s.fence != VK_NULL_HANDLE) vkDestroyFence(dev, s.fence, nullptr);
        if (s.cmd != VK_NULL_HANDLE) vkFreeCommandBuffers(dev, ctx_.command_pool(), 1, &s.cmd);
    }
    if (pool_ != VK_NULL_HANDLE) vkDestroyDescriptorPool(dev, pool_, nullptr);
    if (render_pass_ != VK_NULL_HANDLE) vkDestroyRenderPass(dev, render_pass_, nullptr);
}

void GuiLayer::new_frame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void GuiLayer::discard_frame() { ImGui::EndFrame(); }

Status GuiLayer::submit(const gpu::AcquiredImage& image) {
    ImGui::Render();
    ImDrawData* draw = ImGui::GetDrawData();
    // Slot k is reused every slots_.size() submits, as are ImGui's own per-frame vertex buffers (it
    // cycles through ImageCount sets, one per RenderDrawData call): waiting for this slot's fence
    // guarantees the set ImGui is about to overwrite is no longer read by the GPU.
    Slot& slot = slots_[frame_ % slots_.size()];
    ++frame_;
    const VkDevice dev = ctx_.device();
    ALOHA_VK_RETURN(vkWaitForFences(dev, 1, &slot.fence, VK_TRUE, UINT64_MAX));
    ALOHA_VK_RETURN(vkResetFences(dev, 1, &slot.fence));
    ALOHA_VK_RETURN(vkResetCommandBuffer(slot.cmd, 0));
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    ALOHA_VK_RETURN(vkBeginCommandBuffer(slot.cmd, &bi));
    VkRenderPassBeginInfo rbi{};
    rbi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rbi.renderPass = render_pass_;
    rbi.framebuffer = image.view.framebuffer;
    rbi.renderArea.extent = image.view.extent;
    vkCmdBeginRenderPass(slot.cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(draw, slot.cmd);
    vkCmdEndRenderPass(slot.cmd);
    ALOHA_VK_RETURN(vkEndCommandBuffer(slot.cmd));
    // No wait semaphore: the crowd frame was submitted earlier to the same queue (it waited for the
    // acquire), and the pass's external dependency orders this pass after it.
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &slot.cmd;
    si.signalSemaphoreCount = image.render_done != VK_NULL_HANDLE ? 1 : 0;
    si.pSignalSemaphores = &image.render_done;
    ALOHA_VK_RETURN(vkQueueSubmit(ctx_.queue(), 1, &si, slot.fence));
    if (backend_error() != VK_SUCCESS) return gpu::vk_error("ImGui Vulkan backend", backend_error());
    return {};
}

}  // namespace aloha::tool
