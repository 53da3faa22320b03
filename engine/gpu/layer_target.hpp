// A render target drawn in one render pass and sampled by a later pass of the same command buffer: a layer
// composited into the frame (the far crowd drawn at half resolution, systems/render/far_layer.hpp).
#pragma once

#include "engine/core/result.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/offscreen_target.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>

namespace aloha::gpu {

class Context;

/// A colour + D32 depth target whose render pass (create_render_pass, so pipelines built for any ALOHA
/// target draw into it) clears both and leaves the colour in SHADER_READ_ONLY_OPTIMAL and the depth in
/// DEPTH_STENCIL_READ_ONLY_OPTIMAL, their writes made visible to later fragment-shader reads; with a linear,
/// edge-clamped sampler for the colour and a nearest one for the depth. Move-only.
class LayerTarget {
public:
    /// Creates a `width` x `height` layer (both > 0) of `colour_format` (a format the renderer's
    /// pipelines were built for). Errors: Vulkan failures.
    [[nodiscard]] static Result<LayerTarget> create(const Context& ctx, uint32_t width, uint32_t height, VkFormat colour_format);
    LayerTarget() = default;
    ~LayerTarget() { destroy(); }
    LayerTarget(LayerTarget&& other) noexcept;
    LayerTarget& operator=(LayerTarget&& other) noexcept;
    LayerTarget(const LayerTarget&) = delete;
    LayerTarget& operator=(const LayerTarget&) = delete;

    /// The view a renderer draws into.
    [[nodiscard]] TargetView view() const { return attachments_.view(); }
    /// Size in pixels ({0, 0} before create).
    [[nodiscard]] VkExtent2D extent() const { return attachments_.extent(); }
    /// The colour image's view, for a combined image sampler in SHADER_READ_ONLY_OPTIMAL.
    [[nodiscard]] VkImageView colour_view() const { return attachments_.colour().view(); }
    /// Linear filtering, clamped to the edge, no mips.
    [[nodiscard]] VkSampler sampler() const { return sampler_; }
    /// The depth image's view, for a combined image sampler in DEPTH_STENCIL_READ_ONLY_OPTIMAL.
    [[nodiscard]] VkImageView depth_view() const { return attachments_.depth().view(); }
    /// Nearest filtering, clamped to the edge (for the depth).
    [[nodiscard]] VkSampler depth_sampler() const { return depth_sampler_; }
    /// Releases everything now (also done by the destructor); the device must not be using it.
    void destroy();

private:
    Attachments attachments_;
    VkDevice device_ = VK_NULL_HANDLE;  // the samplers'
    VkSampler sampler_ = VK_NULL_HANDLE;
    VkSampler depth_sampler_ = VK_NULL_HANDLE;
};

}  // namespace aloha::gpu
