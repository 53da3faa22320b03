// keep_freed_heap (engine/gpu/cpu_heap.hpp): after it, memory freed at the top of the heap stays mapped
// (glibc's free byte count keeps it) instead of being trimmed back to the kernel, which is what made
// lavapipe page-fault its binned scene in again every frame.
#include "engine/gpu/cpu_heap.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace aloha::gpu {
namespace {

#if defined(__SANITIZE_ADDRESS__)
#define ALOHA_SANITIZER_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ALOHA_SANITIZER_ALLOCATOR 1
#endif
#endif

TEST(CpuHeap, FreedBlocksStayMapped) {
#if !defined(__GLIBC__)
    GTEST_SKIP() << "mallopt is glibc's";
#elif defined(ALOHA_SANITIZER_ALLOCATOR)
    GTEST_SKIP() << "AddressSanitizer's allocator replaces glibc's malloc: mallopt does nothing under it";
#else
    const CpuHeapSettings s = keep_freed_heap();
    ASSERT_TRUE(s.applied);
    EXPECT_EQ(s.trim_threshold, size_t{512} << 20);
    EXPECT_EQ(s.mmap_threshold, size_t{32} << 20);
    // Lavapipe's pattern: 64 KiB + 16 B blocks (below the mmap threshold, so from the heap), 48 MiB in all,
    // touched, then all freed. With glibc's default 128 KiB trim threshold the free top would be returned.
    constexpr size_t kBlock = 65552, kBlocks = 768;
    std::vector<void*> blocks(kBlocks);
    for (void*& b : blocks) {
        b = std::malloc(kBlock);
        ASSERT_NE(b, nullptr);
        std::memset(b, 1, kBlock);
    }
    for (auto it = blocks.rbegin(); it != blocks.rend(); ++it) std::free(*it);
    const struct mallinfo2 info = mallinfo2();
    // The freed blocks are still held by the arena (free bytes >= what was freed, less one block of slack).
    EXPECT_GE(info.fordblks, (kBlocks - 1) * kBlock);
#endif
}

}  // namespace
}  // namespace aloha::gpu
