#pragma once
// Transparent huge pages for the heap of a run: big meshes and pictures touch tens to hundreds of
// megabytes, and the first touch of every 4 KiB page is a fault (about 8 us on a virtual machine).
#include <cstddef>

namespace fscript::support {

struct HugeHeap {
  size_t reserved = 0;  // bytes of heap advised for huge pages; 0: not in use
};

// First thing in main, before any thread starts: every thread allocates from the one main heap, the
// region reserve_huge_heap advises (per-thread heaps would not be). Does nothing where the huge heap
// cannot be used (not glibc, a sanitizer's allocator, transparent huge pages off, or
// FSCRIPT_HUGE_PAGES=0 in the environment).
void prepare_huge_heap();

// Grows the heap by `bytes` at once (virtual memory, committed only as touched), keeps it from being
// trimmed and advises the kernel to back it with 2 MiB pages. Call it after the memory cap is set
// (limits.h), which then counts the reservation: the cap still bounds the whole run. Without huge
// pages (but with glibc's malloc) it still keeps the heap: no trimming below 2 x `bytes`, blocks
// up to 32 MiB from the heap, growth in 16 MiB steps.
HugeHeap reserve_huge_heap(size_t bytes);

// What reserve_huge_heap did in this process.
HugeHeap huge_heap();

}  // namespace fscript::support
