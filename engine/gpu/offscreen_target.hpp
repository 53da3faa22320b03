// Render targets: the view a renderer draws into, and a headless colour + depth target with CPU readback.
#pragma once

#include "engine/core/result.hpp"
#include "engine/gpu/buffer.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace aloha::gpu {

class Context;

/// Depth format of every ALOHA target.
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

/// What a renderer needs to draw into one image: a render pass (colour + D32 depth, both cleared),
/// the framebuffer of this image, its size and colour format. Valid while the owning target lives.
struct TargetView {
    VkRenderPass render_pass = VK_NULL_HANDLE;  ///< colour attachment 0 + depth attachment 1
    VkFramebuffer framebuffer = VK_NULL_HANDLE; ///< framebuffer for this image
    VkExtent2D extent{0, 0};                    ///< size in pixels
    VkFormat colour_format = VK_FORMAT_UNDEFINED; ///< colour attachment format
};

/// Creates a render pass with one colour attachment of `colour_format` (cleared, stored, ending in
/// `final_layout`) and one kDepthFormat attachment (cleared, not stored). `load_colour`: the colour
/// is loaded instead, starting in `final_layout` (a pass drawn over an earlier one, e.g. the viewer's
/// overlay), and depth is not cleared. `keep_depth`: the depth is stored and ends in
/// DEPTH_STENCIL_READ_ONLY_OPTIMAL, for a later pass to sample (gpu::LayerTarget). Passes differing only in
/// `load_colour` and `keep_depth` are compatible (same framebuffers, same pipelines). Caller destroys it.
[[nodiscard]] Result<VkRenderPass> create_render_pass(VkDevice device, VkFormat colour_format,
                                                      VkImageLayout final_layout, bool load_colour = false,
                                                      bool keep_depth = false);

/// Creates the framebuffer of `render_pass` (create_render_pass's) over `colour` and `depth` views of
/// `width` x `height`. Caller destroys it.
[[nodiscard]] Result<VkFramebuffer> create_framebuffer(VkDevice device, VkRenderPass render_pass, VkImageView colour,
                                                       VkImageView depth, uint32_t width, uint32_t height);

/// Records the start of `target`'s render pass over its whole extent, clearing colour to `clear` and depth to 1.
void begin_render_pass(VkCommandBuffer cmd, const TargetView& target, const VkClearColorValue& clear);

/// A CPU-RGBA8 picture: width * height * 4 bytes, rows top to bottom.
struct Rgba8Image {
    uint32_t width = 0;          ///< pixels
    uint32_t height = 0;         ///< pixels
    std::vector<uint8_t> pixels; ///< RGBA, row-major, top row first
};

/// Records the copy of a colour image (in TRANSFER_SRC_OPTIMAL) into the host-visible buffer `dst` and the
/// barrier that makes it readable by the host. Shared by the offscreen and swapchain readbacks.
void record_image_to_host_copy(VkCommandBuffer cmd, VkImage image, VkExtent2D extent, VkBuffer dst);

/// Access and stage of one side of a barrier.
struct BarrierSide {
    VkAccessFlags access = 0;
    VkPipelineStageFlags stage = VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT;
};

/// Records the layout change `from` -> `to` of a single-mip, single-layer colour image, making the
/// `before` accesses available to the `after` ones.
void record_colour_transition(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                              BarrierSide before, BarrierSide after);

/// The RGBA8 image of `extent` held in mapped memory at `mapped` (tightly packed rows).
[[nodiscard]] Rgba8Image image_from_mapped(const void* mapped, VkExtent2D extent);

/// A colour image and a kDepthFormat depth image of one size with their render pass (create_render_pass) and
/// framebuffer: what every target drawn offscreen owns (OffscreenTarget, LayerTarget). Move-only.
class Attachments {
public:
    /// Creates the two images (attachment usage plus `colour_usage` / `depth_usage`), a render pass ending the colour
    /// in `final_layout` (`keep_depth`: the depth stored and left readable, as create_render_pass) and the
    /// framebuffer; `width`, `height` > 0. Errors: Vulkan failures.
    [[nodiscard]] static Result<Attachments> create(const Context& ctx, uint32_t width, uint32_t height, VkFormat colour_format,
                                                    VkImageUsageFlags colour_usage, VkImageUsageFlags depth_usage,
                                                    VkImageLayout final_layout, bool keep_depth);
    Attachments() = default;
    ~Attachments() { destroy(); }
    Attachments(Attachments&& other) noexcept;
    Attachments& operator=(Attachments&& other) noexcept;
    Attachments(const Attachments&) = delete;
    Attachments& operator=(const Attachments&) = delete;

    /// The view a renderer draws into.
    [[nodiscard]] TargetView view() const;
    /// Size in pixels ({0, 0} before create).
    [[nodiscard]] VkExtent2D extent() const { return colour_.extent(); }
    /// The colour image.
    [[nodiscard]] const Image& colour() const { return colour_; }
    /// The depth image.
    [[nodiscard]] const Image& depth() const { return depth_; }
    /// Releases everything now (also done by the destructor); the device must not be using it.
    void destroy();

private:
    VkDevice device_ = VK_NULL_HANDLE;
    Image colour_;
    Image depth_;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
};

/// A headless colour (R8G8B8A8 UNORM or SRGB) + depth (D32) target with its render pass and framebuffer.
/// After each render pass the colour image is in TRANSFER_SRC_OPTIMAL, ready for read_back(). Move-only.
class OffscreenTarget {
public:
    /// Creates a `width` x `height` target (both > 0); `srgb` picks R8G8B8A8_SRGB over UNORM.
    /// The colour image starts cleared to transparent black.
    [[nodiscard]] static Result<OffscreenTarget> create(const Context& ctx, uint32_t width, uint32_t height,
                                                        bool srgb = false);
    OffscreenTarget() = default;
    OffscreenTarget(OffscreenTarget&&) noexcept = default;
    OffscreenTarget& operator=(OffscreenTarget&&) noexcept = default;
    OffscreenTarget(const OffscreenTarget&) = delete;
    OffscreenTarget& operator=(const OffscreenTarget&) = delete;

    /// The view a renderer draws into.
    [[nodiscard]] TargetView view() const { return attachments_.view(); }
    /// Size in pixels.
    [[nodiscard]] VkExtent2D extent() const { return attachments_.extent(); }
    /// The colour image (for custom copies).
    [[nodiscard]] const Image& colour() const { return attachments_.colour(); }
    /// Copies the colour image to the CPU, waiting for all earlier work on ctx's queue to finish.
    [[nodiscard]] Result<Rgba8Image> read_back(const Context& ctx) const;
    /// Releases everything now (also done by the destructor); the device must be idle.
    void destroy();

private:
    Attachments attachments_;
    Buffer readback_;
};

}  // namespace aloha::gpu
