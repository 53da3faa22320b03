// Heap settings for a CPU Vulkan device (lavapipe). Lavapipe's binner takes its per-frame scene memory (the
// triangles' setup data and the tiles' command lists) from malloc in 64 KiB blocks and frees them after every
// flush (end of frame, timestamp, fence). glibc then gives the freed top of the heap back to the kernel
// (MADV_DONTNEED once more than M_TRIM_THRESHOLD is free), so the next frame page-faults every block in again:
// on crowd_1k that was three quarters of the frame (docs/PERFORMANCE.md, "Whole frame on lavapipe").
#pragma once

#include <cstddef>

namespace aloha::gpu {

/// What keep_freed_heap() asked of glibc.
struct CpuHeapSettings {
    size_t trim_threshold = 0;  ///< free bytes kept at the top of a heap before it is returned to the kernel
    size_t mmap_threshold = 0;  ///< allocations from this size on are mmapped (and unmapped when freed)
    bool applied = false;       ///< false where the C library has no mallopt (not glibc)
};

/// Makes freed heap memory stay mapped (trim threshold 512 MiB; mmap threshold 32 MiB, the largest glibc
/// allows, so the draw module's per-draw vertex buffers also come from the heap). Process-wide and
/// idempotent; memory is then kept at the process's peak instead of returned between frames. Called by
/// Context::create for a CPU device unless ContextOptions::keep_freed_heap is false.
CpuHeapSettings keep_freed_heap();

}  // namespace aloha::gpu
