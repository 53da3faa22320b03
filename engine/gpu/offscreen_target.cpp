#include "engine/gpu/offscreen_target.hpp"

#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"

#include <cstring>
#include <utility>

namespace aloha::gpu {

Result<VkRenderPass> create_render_pass(VkDevice device, VkFormat colour_format, VkImageLayout final_layout,
                                        bool load_colour, bool keep_depth) {
    VkAttachmentDescription att[2]{};
    att[0].format = colour_format;
    att[0].samples = VK_SAMPLE_COUNT_1_BIT;
    att[0].loadOp = load_colour ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    att[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    att[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    att[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    att[0].initialLayout = load_colour ? final_layout : VK_IMAGE_LAYOUT_UNDEFINED;  // loaded: where the last pass left it
    att[0].finalLayout = final_layout;
    att[1] = att[0];
    att[1].format = kDepthFormat;
    att[1].loadOp = load_colour ? VK_ATTACHMENT_LOAD_OP_DONT_CARE : VK_ATTACHMENT_LOAD_OP_CLEAR;  // overlays do not depth-test
    att[1].storeOp = keep_depth ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    att[1].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    att[1].finalLayout = keep_depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    VkAttachmentReference colour_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &colour_ref;
    sub.pDepthStencilAttachment = &depth_ref;
    // Earlier reads (readback copy, present, a later pass sampling a layer) and attachment writes (an earlier
    // pass on the queue) finish before this pass loads or writes; this pass's writes finish before later
    // transfers (readback) or fragment shaders (a composited layer, gpu::LayerTarget) read.
    VkSubpassDependency deps[2]{};
    deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    deps[0].dstSubpass = 0;
    deps[0].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
                           VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                           VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    deps[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                            VK_ACCESS_TRANSFER_READ_BIT;
    deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
                            VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                            VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
    deps[1].srcSubpass = 0;
    deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT;
    VkRenderPassCreateInfo rpi{};
    rpi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    rpi.attachmentCount = 2;
    rpi.pAttachments = att;
    rpi.subpassCount = 1;
    rpi.pSubpasses = &sub;
    rpi.dependencyCount = 2;
    rpi.pDependencies = deps;
    VkRenderPass rp = VK_NULL_HANDLE;
    ALOHA_VK_RETURN(vkCreateRenderPass(device, &rpi, nullptr, &rp));
    return rp;
}

Result<VkFramebuffer> create_framebuffer(VkDevice device, VkRenderPass render_pass, VkImageView colour, VkImageView depth,
                                         uint32_t width, uint32_t height) {
    const VkImageView views[2] = {colour, depth};
    VkFramebufferCreateInfo fci{};
    fci.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fci.renderPass = render_pass;
    fci.attachmentCount = 2;
    fci.pAttachments = views;
    fci.width = width;
    fci.height = height;
    fci.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    ALOHA_VK_RETURN(vkCreateFramebuffer(device, &fci, nullptr, &fb));
    return fb;
}

void begin_render_pass(VkCommandBuffer cmd, const TargetView& target, const VkClearColorValue& clear) {
    VkClearValue clears[2]{};
    clears[0].color = clear;
    clears[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo rbi{};
    rbi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rbi.renderPass = target.render_pass;
    rbi.framebuffer = target.framebuffer;
    rbi.renderArea = {{0, 0}, target.extent};
    rbi.clearValueCount = 2;
    rbi.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
}

Result<Attachments> Attachments::create(const Context& ctx, uint32_t width, uint32_t height, VkFormat colour_format,
                                       VkImageUsageFlags colour_usage, VkImageUsageFlags depth_usage, VkImageLayout final_layout,
                                       bool keep_depth) {
    Attachments a;
    a.device_ = ctx.device();
    Result<Image> colour = Image::create(ctx, width, height, colour_format, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | colour_usage,
                                         VK_IMAGE_ASPECT_COLOR_BIT);
    if (!colour) return colour.error();
    a.colour_ = std::move(colour).value();
    Result<Image> depth = Image::create(ctx, width, height, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | depth_usage,
                                        VK_IMAGE_ASPECT_DEPTH_BIT);
    if (!depth) return depth.error();
    a.depth_ = std::move(depth).value();
    Result<VkRenderPass> rp = create_render_pass(a.device_, colour_format, final_layout, /*load_colour=*/false, keep_depth);
    if (!rp) return rp.error();
    a.render_pass_ = rp.value();
    Result<VkFramebuffer> fb = create_framebuffer(a.device_, a.render_pass_, a.colour_.view(), a.depth_.view(), width, height);
    if (!fb) return fb.error();
    a.framebuffer_ = fb.value();
    return a;
}

Attachments::Attachments(Attachments&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      colour_(std::move(other.colour_)),
      depth_(std::move(other.depth_)),
      render_pass_(std::exchange(other.render_pass_, VK_NULL_HANDLE)),
      framebuffer_(std::exchange(other.framebuffer_, VK_NULL_HANDLE)) {}

Attachments& Attachments::operator=(Attachments&& other) noexcept {
    if (this != &other) {
        destroy();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        colour_ = std::move(other.colour_);
        depth_ = std::move(other.depth_);
        render_pass_ = std::exchange(other.render_pass_, VK_NULL_HANDLE);
        framebuffer_ = std::exchange(other.framebuffer_, VK_NULL_HANDLE);
    }
    return *this;
}

TargetView Attachments::view() const {
    return TargetView{render_pass_, framebuffer_, colour_.extent(), colour_.format()};
}

void Attachments::destroy() {
    if (device_ != VK_NULL_HANDLE) {
        if (framebuffer_ != VK_NULL_HANDLE) vkDestroyFramebuffer(device_, framebuffer_, nullptr);
        if (render_pass_ != VK_NULL_HANDLE) vkDestroyRenderPass(device_, render_pass_, nullptr);
    }
    framebuffer_ = VK_NULL_HANDLE;
    render_pass_ = VK_NULL_HANDLE;
    depth_.destroy();
    colour_.destroy();
    device_ = VK_NULL_HANDLE;
}

Result<OffscreenTarget> OffscreenTarget::create(const Context& ctx, uint32_t width, uint32_t height, bool srgb) {
    OffscreenTarget t;
    const VkFormat fmt = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    Result<Attachments> attachments = Attachments::create(ctx, width, height, fmt,
                                                          VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, 0,
                                                          VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, /*keep_depth=*/false);
    if (!attachments) return attachments.error();
    t.attachments_ = std::move(attachments).value();
    Result<Buffer> rb = Buffer::create(ctx, VkDeviceSize(width) * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    if (!rb) return rb.error();
    t.readback_ = std::move(rb).value();

    // Clear once and leave the colour image in TRANSFER_SRC_OPTIMAL, the layout every pass ends in,
    // so read_back() is valid even before anything is drawn.
    const VkImage image = t.colour().handle();
    Status s = ctx.submit_once([image](VkCommandBuffer cmd) {
        record_colour_transition(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                 {0, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT},
                                 {VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT});
        const VkClearColorValue zero{};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
        record_colour_transition(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                 {VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT},
                                 {VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT});
    });
    if (!s) return s.error();
    return t;
}

void OffscreenTarget::destroy() {
    readback_.destroy();
    attachments_.destroy();
}

Result<Rgba8Image> OffscreenTarget::read_back(const Context& ctx) const {
    const VkExtent2D ext = extent();
    const VkImage image = colour().handle();
    const VkBuffer dst = readback_.handle();
    Status s = ctx.submit_once([&](VkCommandBuffer cmd) {
        // Make earlier render-pass writes available to this copy (same queue, earlier submission).
        VkMemoryBarrier mb{};
        mb.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
        mb.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &mb, 0, nullptr, 0, nullptr);
        record_image_to_host_copy(cmd, image, ext, dst);
    });
    if (!s) return s.error();
    return image_from_mapped(readback_.mapped(), ext);
}

void record_colour_transition(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                              BarrierSide before, BarrierSide after) {
    VkImageMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    b.srcAccessMask = before.access;
    b.dstAccessMask = after.access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, before.stage, after.stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

void record_image_to_host_copy(VkCommandBuffer cmd, VkImage image, VkExtent2D extent, VkBuffer dst) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, 1, &region);
    VkMemoryBarrier hb{};
    hb.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    hb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    hb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &hb, 0, nullptr, 0, nullptr);
}

Rgba8Image image_from_mapped(const void* mapped, VkExtent2D extent) {
    Rgba8Image out;
    out.width = extent.width;
    out.height = extent.height;
    out.pixels.resize(size_t(extent.width) * extent.height * 4);
    std::memcpy(out.pixels.data(), mapped, out.pixels.size());
    return out;
}

}  // namespace aloha::gpu
