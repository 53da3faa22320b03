#include "engine/gpu/layer_target.hpp"

#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"

#include <utility>

namespace aloha::gpu {

Result<LayerTarget> LayerTarget::create(const Context& ctx, uint32_t width, uint32_t height, VkFormat colour_format) {
    LayerTarget t;
    t.device_ = ctx.device();
    Result<Image> colour = Image::create(ctx, width, height, colour_format,
                                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    if (!colour) return colour.error();
    t.colour_ = std::move(colour).value();
    Result<Image> depth = Image::create(ctx, width, height, kDepthFormat,
                                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    if (!depth) return depth.error();
    t.depth_ = std::move(depth).value();
    Result<VkRenderPass> rp = create_render_pass(t.device_, colour_format, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                                  /*load_colour=*/false, /*keep_depth=*/true);
    if (!rp) return rp.error();
    t.render_pass_ = rp.value();
    Result<VkFramebuffer> fb = create_framebuffer(t.device_, t.render_pass_, t.colour_.view(), t.depth_.view(), width, height);
    if (!fb) return fb.error();
    t.framebuffer_ = fb.value();
    VkSamplerCreateInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
    si.magFilter = VK_FILTER_LINEAR;
    si.minFilter = VK_FILTER_LINEAR;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    si.maxLod = 0.0f;
    ALOHA_VK_RETURN(vkCreateSampler(t.device_, &si, nullptr, &t.sampler_));
    si.magFilter = si.minFilter = VK_FILTER_NEAREST;
    ALOHA_VK_RETURN(vkCreateSampler(t.device_, &si, nullptr, &t.depth_sampler_));
    return t;
}

LayerTarget::LayerTarget(LayerTarget&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      colour_(std::move(other.colour_)),
      depth_(std::move(other.depth_)),
      render_pass_(std::exchange(other.render_pass_, VK_NULL_HANDLE)),
      framebuffer_(std::exchange(other.framebuffer_, VK_NULL_HANDLE)),
      sampler_(std::exchange(other.sampler_, VK_NULL_HANDLE)),
      depth_sampler_(std::exchange(other.depth_sampler_, VK_NULL_HANDLE)) {}

LayerTarget& LayerTarget::operator=(LayerTarget&& other) noexcept {
    if (this != &other) {
        destroy();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        colour_ = std::move(other.colour_);
        depth_ = std::move(other.depth_);
        render_pass_ = std::exchange(other.render_pass_, VK_NULL_HANDLE);
        framebuffer_ = std::exchange(other.framebuffer_, VK_NULL_HANDLE);
        sampler_ = std::exchange(other.sampler_, VK_NULL_HANDLE);
        depth_sampler_ = std::exchange(other.depth_sampler_, VK_NULL_HANDLE);
    }
    return *this;
}

TargetView LayerTarget::view() const {
    return {render_pass_, framebuffer_, colour_.extent(), colour_.format()};
}

void LayerTarget::destroy() {
    if (device_ == VK_NULL_HANDLE) return;
    if (sampler_ != VK_NULL_HANDLE) vkDestroySampler(device_, sampler_, nullptr);
    if (depth_sampler_ != VK_NULL_HANDLE) vkDestroySampler(device_, depth_sampler_, nullptr);
    if (framebuffer_ != VK_NULL_HANDLE) vkDestroyFramebuffer(device_, framebuffer_, nullptr);
    if (render_pass_ != VK_NULL_HANDLE) vkDestroyRenderPass(device_, render_pass_, nullptr);
    sampler_ = depth_sampler_ = VK_NULL_HANDLE;
    framebuffer_ = VK_NULL_HANDLE;
    render_pass_ = VK_NULL_HANDLE;
    colour_.destroy();
    depth_.destroy();
    device_ = VK_NULL_HANDLE;
}

}  // namespace aloha::gpu
