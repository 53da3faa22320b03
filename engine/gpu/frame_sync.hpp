// The per-frame-in-flight pieces every renderer allocates: a primary command buffer from the context's
// pool and a fence.
#pragma once

#include "engine/core/result.hpp"

#include <vulkan/vulkan.h>

namespace aloha::gpu {

class Context;

/// Allocates one primary command buffer from ctx's command pool into *out (freed with the pool).
[[nodiscard]] Status allocate_command_buffer(const Context& ctx, VkCommandBuffer* out);

/// Creates a fence into *out, already signalled when `signalled` (a slot not yet in flight).
[[nodiscard]] Status create_fence(VkDevice device, bool signalled, VkFence* out);

}  // namespace aloha::gpu
