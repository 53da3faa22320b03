#include "engine/gpu/frame_sync.hpp"

#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"

namespace aloha::gpu {

Status allocate_command_buffer(const Context& ctx, VkCommandBuffer* out) {
    VkCommandBufferAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    ai.commandPool = ctx.command_pool();
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    ALOHA_VK_RETURN(vkAllocateCommandBuffers(ctx.device(), &ai, out));
    return {};
}

Status create_fence(VkDevice device, bool signalled, VkFence* out) {
    VkFenceCreateInfo fi{};
    fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    fi.flags = signalled ? VkFenceCreateFlags{VK_FENCE_CREATE_SIGNALED_BIT} : VkFenceCreateFlags{0};
    ALOHA_VK_RETURN(vkCreateFence(device, &fi, nullptr, out));
    return {};
}

}  // namespace aloha::gpu
