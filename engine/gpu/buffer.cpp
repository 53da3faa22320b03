#include "engine/gpu/buffer.hpp"

#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"

#include <cassert>
#include <cstring>
#include <utility>

namespace aloha::gpu {

Result<Buffer> Buffer::create(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage) {
    if (size == 0) return gpu_error("Buffer::create: size must be > 0");
    Buffer b;
    b.device_ = ctx.device();
    b.size_ = size;
    VkBufferCreateInfo bci{};
    bci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    bci.size = size;
    bci.usage = usage;
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ALOHA_VK_RETURN(vkCreateBuffer(b.device_, &bci, nullptr, &b.buffer_));
    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(b.device_, b.buffer_, &req);
    Result<uint32_t> type = ctx.find_memory_type(
        req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    if (!type) return type.error();
    VkMemoryAllocateInfo mai{};
    mai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = type.value();
    ALOHA_VK_RETURN(vkAllocateMemory(b.device_, &mai, nullptr, &b.memory_));
    ALOHA_VK_RETURN(vkBindBufferMemory(b.device_, b.buffer_, b.memory_, 0));
    void* p = nullptr;
    ALOHA_VK_RETURN(vkMapMemory(b.device_, b.memory_, 0, VK_WHOLE_SIZE, 0, &p));
    b.mapped_ = static_cast<std::byte*>(p);
    return b;
}

Buffer::Buffer(Buffer&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      size_(std::exchange(other.size_, 0)),
      mapped_(std::exchange(other.mapped_, nullptr)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        destroy();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(other.size_, 0);
        mapped_ = std::exchange(other.mapped_, nullptr);
    }
    return *this;
}

void Buffer::write(std::span<const std::byte> bytes, VkDeviceSize offset) const {
    assert(offset + bytes.size() <= size_);
    if (!bytes.empty()) std::memcpy(mapped_ + offset, bytes.data(), bytes.size());
}

void Buffer::destroy() {
    if (device_ == VK_NULL_HANDLE) return;
    if (memory_ != VK_NULL_HANDLE && mapped_ != nullptr) vkUnmapMemory(device_, memory_);
    if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(device_, buffer_, nullptr);
    if (memory_ != VK_NULL_HANDLE) vkFreeMemory(device_, memory_, nullptr);
    device_ = VK_NULL_HANDLE;
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    size_ = 0;
}

Status create_bound_image(const Context& ctx, uint32_t width, uint32_t height, VkFormat format, uint32_t mips,
                          VkImageUsageFlags usage, VkImage* image, VkDeviceMemory* memory) {
    const VkDevice device = ctx.device();
    VkImageCreateInfo ici{};
    ici.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = format;
    ici.extent = {width, height, 1};
    ici.mipLevels = mips;
    ici.arrayLayers = 1;
    ici.samples = VK_SAMPLE_COUNT_1_BIT;
    ici.tiling = VK_IMAGE_TILING_OPTIMAL;
    ici.usage = usage;
    ici.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    ALOHA_VK_RETURN(vkCreateImage(device, &ici, nullptr, image));
    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(device, *image, &req);
    Result<uint32_t> type = ctx.find_memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (!type) type = ctx.find_memory_type(req.memoryTypeBits, 0);
    if (!type) return type.error();
    VkMemoryAllocateInfo mai{};
    mai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = type.value();
    ALOHA_VK_RETURN(vkAllocateMemory(device, &mai, nullptr, memory));
    ALOHA_VK_RETURN(vkBindImageMemory(device, *image, *memory, 0));
    return {};
}

Result<Image> Image::create(const Context& ctx, uint32_t width, uint32_t height, VkFormat format,
                            VkImageUsageFlags usage, VkImageAspectFlags aspect) {
    if (width == 0 || height == 0) return gpu_error("Image::create: width and height must be > 0");
    Image im;
    im.device_ = ctx.device();
    im.format_ = format;
    im.extent_ = {width, height};
    if (Status st = create_bound_image(ctx, width, height, format, 1, usage, &im.image_, &im.memory_); !st) return st.error();
    VkImageViewCreateInfo vci{};
    vci.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vci.image = im.image_;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = format;
    vci.subresourceRange = {aspect, 0, 1, 0, 1};
    ALOHA_VK_RETURN(vkCreateImageView(im.device_, &vci, nullptr, &im.view_));
    return im;
}

Image::Image(Image&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      image_(std::exchange(other.image_, VK_NULL_HANDLE)),
      view_(std::exchange(other.view_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      format_(other.format_),
      extent_(other.extent_) {}

Image& Image::operator=(Image&& other) noexcept {
    if (this != &other) {
        destroy();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        image_ = std::exchange(other.image_, VK_NULL_HANDLE);
        view_ = std::exchange(other.view_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        format_ = other.format_;
        extent_ = other.extent_;
    }
    return *this;
}

void Image::destroy() {
    if (device_ == VK_NULL_HANDLE) return;
    if (view_ != VK_NULL_HANDLE) vkDestroyImageView(device_, view_, nullptr);
    if (image_ != VK_NULL_HANDLE) vkDestroyImage(device_, image_, nullptr);
    if (memory_ != VK_NULL_HANDLE) vkFreeMemory(device_, memory_, nullptr);
    device_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    view_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
}

}  // namespace aloha::gpu
