// GPU memory objects: host-visible, persistently mapped buffers and 2D images with a view.
#pragma once

#include "engine/core/result.hpp"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>

namespace aloha::gpu {

class Context;

/// A VkBuffer with its own memory, host-visible and coherent, mapped for its whole life. Move-only.
/// (Lavapipe has one memory type; on a discrete GPU this is PCIe-visible memory, fine for per-frame data.)
class Buffer {
public:
    /// Creates a buffer of `size` bytes (> 0) with `usage`, mapped persistently.
    [[nodiscard]] static Result<Buffer> create(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage);
    Buffer() = default;
    ~Buffer() { destroy(); }
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    /// The buffer handle (VK_NULL_HANDLE when empty).
    [[nodiscard]] VkBuffer handle() const { return buffer_; }
    /// Size in bytes.
    [[nodiscard]] VkDeviceSize size() const { return size_; }
    /// Start of the mapped memory (writes are visible to the device without flushing).
    [[nodiscard]] std::byte* mapped() const { return mapped_; }
    /// Copies `bytes` to offset `offset`; requires offset + bytes.size() <= size().
    void write(std::span<const std::byte> bytes, VkDeviceSize offset = 0) const;
    /// Releases the buffer and memory now (also done by the destructor).
    void destroy();

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    std::byte* mapped_ = nullptr;
};

/// Creates a 2D optimal-tiling image of `mips` levels and binds it to device-local memory (any memory type
/// when none is device-local); on failure whatever was created is left in *image / *memory for the caller
/// to destroy.
[[nodiscard]] Status create_bound_image(const Context& ctx, uint32_t width, uint32_t height, VkFormat format, uint32_t mips,
                                        VkImageUsageFlags usage, VkImage* image, VkDeviceMemory* memory);

/// A 2D VkImage with device memory and one image view. Move-only.
class Image {
public:
    /// Creates a `width` x `height` image of `format` with `usage`; the view covers `aspect`.
    [[nodiscard]] static Result<Image> create(const Context& ctx, uint32_t width, uint32_t height, VkFormat format,
                                              VkImageUsageFlags usage, VkImageAspectFlags aspect);
    Image() = default;
    ~Image() { destroy(); }
    Image(Image&& other) noexcept;
    Image& operator=(Image&& other) noexcept;
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;

    /// The image handle.
    [[nodiscard]] VkImage handle() const { return image_; }
    /// The view over the whole image.
    [[nodiscard]] VkImageView view() const { return view_; }
    /// Pixel format.
    [[nodiscard]] VkFormat format() const { return format_; }
    /// Width and height in pixels.
    [[nodiscard]] VkExtent2D extent() const { return extent_; }
    /// Releases view, image and memory now (also done by the destructor).
    void destroy();

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkImage image_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_{0, 0};
};

}  // namespace aloha::gpu
