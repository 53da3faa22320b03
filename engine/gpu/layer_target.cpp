#include "engine/gpu/layer_target.hpp"

#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"

#include <utility>

namespace aloha::gpu {

Result<LayerTarget> LayerTarget::create(const Context& ctx, uint32_t width, uint32_t height, VkFormat colour_format) {
    LayerTarget t;
    Result<Attachments> attachments = Attachments::create(ctx, width, height, colour_format, VK_IMAGE_USAGE_SAMPLED_BIT,
                                                          VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                                          /*keep_depth=*/true);
    if (!attachments) return attachments.error();
    t.attachments_ = std::move(attachments).value();
    t.device_ = ctx.device();
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
    : attachments_(std::move(other.attachments_)),
      device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      sampler_(std::exchange(other.sampler_, VK_NULL_HANDLE)),
      depth_sampler_(std::exchange(other.depth_sampler_, VK_NULL_HANDLE)) {}

LayerTarget& LayerTarget::operator=(LayerTarget&& other) noexcept {
    if (this != &other) {
        destroy();
        attachments_ = std::move(other.attachments_);
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        sampler_ = std::exchange(other.sampler_, VK_NULL_HANDLE);
        depth_sampler_ = std::exchange(other.depth_sampler_, VK_NULL_HANDLE);
    }
    return *this;
}

void LayerTarget::destroy() {
    if (device_ != VK_NULL_HANDLE) {
        if (sampler_ != VK_NULL_HANDLE) vkDestroySampler(device_, sampler_, nullptr);
        if (depth_sampler_ != VK_NULL_HANDLE) vkDestroySampler(device_, depth_sampler_, nullptr);
    }
    sampler_ = depth_sampler_ = VK_NULL_HANDLE;
    device_ = VK_NULL_HANDLE;
    attachments_.destroy();
}

}  // namespace aloha::gpu
