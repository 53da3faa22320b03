// Texture upload: staging buffer -> mip 0, blits down the chain, then shader-read layout.
#include "engine/gpu/texture.hpp"

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace aloha::gpu {

namespace {

void barrier(VkCommandBuffer cmd, VkImage image, uint32_t mip, VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
             VkAccessFlags dst_access, VkPipelineStageFlags src_stage, VkPipelineStageFlags dst_stage) {
    VkImageMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

// The view over all `mips` levels and a sampler (`filter` within a level, `mipmap` between levels).
Status make_view_and_sampler(VkDevice device, VkImage image, VkFormat format, uint32_t mips, VkFilter filter,
                             VkSamplerMipmapMode mipmap, VkSamplerAddressMode u, VkSamplerAddressMode v, VkImageView* view, VkSampler* sampler) {
    VkImageViewCreateInfo vci{};
    vci.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vci.image = image;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = format;
    vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, mips, 0, 1};
    ALOHA_VK_RETURN(vkCreateImageView(device, &vci, nullptr, view));
    VkSamplerCreateInfo sci{};
    sci.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
    sci.magFilter = filter;
    sci.minFilter = filter;
    sci.mipmapMode = mipmap;
    sci.addressModeU = u;
    sci.addressModeV = v;
    sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    sci.maxLod = static_cast<float>(mips);
    ALOHA_VK_RETURN(vkCreateSampler(device, &sci, nullptr, sampler));
    return {};
}

}  // namespace

Result<Texture> Texture::create(const Context& ctx, uint32_t width, uint32_t height, std::span<const uint8_t> rgba,
                                const SamplerDesc& desc) {
    if (width == 0 || height == 0) return gpu_error("Texture::create: width and height must be > 0");
    if (rgba.size() != size_t{width} * height * 4)
        return gpu_error("Texture::create: " + std::to_string(rgba.size()) + " bytes for " + std::to_string(width) + " x " +
                         std::to_string(height) + " RGBA8 pixels");
    Texture t;
    t.device_ = ctx.device();
    t.mips_ = 1;
    for (uint32_t s = std::max(width, height); s > 1; s /= 2) ++t.mips_;
    const VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    if (Status st = create_bound_image(ctx, width, height, format, t.mips_, usage, &t.image_, &t.memory_); !st) return st.error();

    Result<Buffer> staging = Buffer::create(ctx, rgba.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    if (!staging) return staging.error();
    staging.value().write(std::as_bytes(rgba));
    const VkImage image = t.image_;
    const uint32_t mips = t.mips_;
    Status up = ctx.submit_once([&](VkCommandBuffer cmd) {
        for (uint32_t m = 0; m < mips; ++m)
            barrier(cmd, image, m, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {width, height, 1};
        vkCmdCopyBufferToImage(cmd, staging.value().handle(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        int32_t w = static_cast<int32_t>(width), h = static_cast<int32_t>(height);
        for (uint32_t m = 1; m < mips; ++m) {
            barrier(cmd, image, m - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m - 1, 0, 1};
            blit.srcOffsets[1] = {w, h, 1};
            w = std::max(w / 2, 1);
            h = std::max(h / 2, 1);
            blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
            blit.dstOffsets[1] = {w, h, 1};
            vkCmdBlitImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
            barrier(cmd, image, m - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_READ_BIT,
                    VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
        }
        barrier(cmd, image, mips - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    });
    if (!up) return up.error();

    if (Status st = make_view_and_sampler(t.device_, t.image_, format, t.mips_, desc.nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR,
                                          desc.blend_mips ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                          desc.address_u, desc.address_v, &t.view_, &t.sampler_);
        !st)
        return st.error();
    return t;
}

Result<Texture> Texture::create_rg32ui(const Context& ctx, uint32_t width, uint32_t height, uint32_t levels,
                                       std::span<const uint32_t> texels) {
    if (width == 0 || height == 0 || levels == 0) return gpu_error("Texture::create_rg32ui: width, height and levels must be > 0");
    uint32_t full = 1;
    for (uint32_t s = std::max(width, height); s > 1; s /= 2) ++full;
    if (levels > full)
        return gpu_error("Texture::create_rg32ui: " + std::to_string(levels) + " levels for " + std::to_string(width) + " x " +
                         std::to_string(height) + " texels (at most " + std::to_string(full) + ")");
    std::vector<VkBufferImageCopy> copies(levels);
    VkDeviceSize offset = 0;
    for (uint32_t m = 0; m < levels; ++m) {
        const uint32_t w = std::max(width >> m, 1u), h = std::max(height >> m, 1u);
        copies[m] = {};
        copies[m].bufferOffset = offset;
        copies[m].imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
        copies[m].imageExtent = {w, h, 1};
        offset += VkDeviceSize{w} * h * 2 * sizeof(uint32_t);
    }
    if (texels.size_bytes() != offset)
        return gpu_error("Texture::create_rg32ui: " + std::to_string(texels.size()) + " words for " + std::to_string(levels) +
                         " levels of " + std::to_string(width) + " x " + std::to_string(height) + " two-word texels");
    Texture t;
    t.device_ = ctx.device();
    t.mips_ = levels;
    const VkFormat format = VK_FORMAT_R32G32_UINT;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    if (Status st = create_bound_image(ctx, width, height, format, levels, usage, &t.image_, &t.memory_); !st) return st.error();
    Result<Buffer> staging = Buffer::create(ctx, texels.size_bytes(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    if (!staging) return staging.error();
    staging.value().write(std::as_bytes(texels));
    const VkImage image = t.image_;
    Status up = ctx.submit_once([&](VkCommandBuffer cmd) {
        for (uint32_t m = 0; m < levels; ++m)
            barrier(cmd, image, m, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        vkCmdCopyBufferToImage(cmd, staging.value().handle(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, levels, copies.data());
        for (uint32_t m = 0; m < levels; ++m)
            barrier(cmd, image, m, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    });
    if (!up) return up.error();
    if (Status st = make_view_and_sampler(t.device_, t.image_, format, levels, VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                          VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, &t.view_, &t.sampler_);
        !st)
        return st.error();
    return t;
}

Texture::Texture(Texture&& o) noexcept
    : device_(std::exchange(o.device_, VK_NULL_HANDLE)),
      image_(std::exchange(o.image_, VK_NULL_HANDLE)),
      memory_(std::exchange(o.memory_, VK_NULL_HANDLE)),
      view_(std::exchange(o.view_, VK_NULL_HANDLE)),
      sampler_(std::exchange(o.sampler_, VK_NULL_HANDLE)),
      mips_(o.mips_) {}

Texture& Texture::operator=(Texture&& o) noexcept {
    if (this != &o) {
        destroy();
        device_ = std::exchange(o.device_, VK_NULL_HANDLE);
        image_ = std::exchange(o.image_, VK_NULL_HANDLE);
        memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
        view_ = std::exchange(o.view_, VK_NULL_HANDLE);
        sampler_ = std::exchange(o.sampler_, VK_NULL_HANDLE);
        mips_ = o.mips_;
    }
    return *this;
}

void Texture::destroy() {
    if (device_ == VK_NULL_HANDLE) return;
    if (sampler_ != VK_NULL_HANDLE) vkDestroySampler(device_, sampler_, nullptr);
    if (view_ != VK_NULL_HANDLE) vkDestroyImageView(device_, view_, nullptr);
    if (image_ != VK_NULL_HANDLE) vkDestroyImage(device_, image_, nullptr);
    if (memory_ != VK_NULL_HANDLE) vkFreeMemory(device_, memory_, nullptr);
    device_ = VK_NULL_HANDLE;
    sampler_ = VK_NULL_HANDLE;
    view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
}

}  // namespace aloha::gpu
