#include "engine/gpu/cpu_heap.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace aloha::gpu {

CpuHeapSettings keep_freed_heap() {
    CpuHeapSettings s;
    s.trim_threshold = size_t{512} << 20;
    s.mmap_threshold = size_t{32} << 20;  // glibc's HEAP_MAX_SIZE / 2 on 64-bit: larger values are refused
#if defined(__GLIBC__)
    s.applied = mallopt(M_TRIM_THRESHOLD, static_cast<int>(s.trim_threshold)) == 1 &&
                mallopt(M_MMAP_THRESHOLD, static_cast<int>(s.mmap_threshold)) == 1;
#endif
    return s;
}

}  // namespace aloha::gpu
