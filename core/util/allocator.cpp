// glibc malloc settings through mallopt.
#include "core/util/allocator.h"

#include <malloc.h>

namespace pf {

void KeepLargeBuffersForReuse() {
    mallopt(M_ARENA_MAX, 1);
    // Buffers up to mallopt's maximum come from the heap, not fresh mappings...
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    // ...and the heap is not trimmed until a gigabyte lies free at its top.
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

}  // namespace pf
