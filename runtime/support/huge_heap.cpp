// The huge heap of huge_heap.h on glibc: one arena, a reservation grown by M_TOP_PAD, and
// madvise(MADV_HUGEPAGE) on exactly the range the break moved over. What glibc's own
// glibc.malloc.hugetlb=1 tunable does, without asking users to set it before the process starts.
#include "runtime/support/huge_heap.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

#include "runtime/support/sanitizers.h"

namespace fscript::support {
namespace {

HugeHeap g_heap;

}  // namespace

#if defined(__GLIBC__) && !defined(FS_FOREIGN_MALLOC)

namespace {
bool g_prepared = false;

// The kernel gives huge pages to advised memory unless the administrator turned them off.
bool huge_pages_available() {
  const char* opt = std::getenv("FSCRIPT_HUGE_PAGES");
  if (opt && std::strcmp(opt, "0") == 0) return false;
  std::FILE* f = std::fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
  if (!f) return false;
  char line[128] = {};
  bool ok = std::fgets(line, sizeof line, f) && !std::strstr(line, "[never]");
  std::fclose(f);
  return ok;
}

// Without huge pages the faults of first touches stay, but freed batches and meshes need not give
// their pages back to be faulted in again by the next ones (glibc trims a heap's top and unmaps
// blocks over its threshold on every free, and grows the heap 128 KiB at a time).
void keep_heap(size_t bytes) {
  constexpr int kMmapThreshold = 32 << 20, kTopPad = 16 << 20;
  if (mallopt(M_MMAP_THRESHOLD, kMmapThreshold) == 1) mallopt(M_TRIM_THRESHOLD, static_cast<int>(2 * bytes - 1));
  mallopt(M_TOP_PAD, kTopPad);
}

}  // namespace

void prepare_huge_heap() {
  if (!huge_pages_available()) return;
  g_prepared = mallopt(M_ARENA_MAX, 1) == 1;
}

HugeHeap reserve_huge_heap(size_t bytes) {
  constexpr size_t kPage = 4096, kDefaultTopPad = 128 * 1024;
  constexpr int kMmapThreshold = 32 << 20;  // glibc's largest: buffers below it come from the heap
  constexpr size_t kMaxReserve = size_t{1} << 30;  // mallopt takes an int; the trim threshold is twice it
  bytes = std::min(bytes, kMaxReserve);
  if (g_heap.reserved || bytes < (size_t{4} << 20)) return g_heap;
  if (!g_prepared) {  // no huge pages: still one heap that keeps its pages, grown in large steps
    keep_heap(bytes);
    return g_heap;
  }
  if (mallopt(M_MMAP_THRESHOLD, kMmapThreshold) != 1 ||
      mallopt(M_TRIM_THRESHOLD, static_cast<int>(2 * bytes - 1)) != 1 ||
      mallopt(M_TOP_PAD, static_cast<int>(bytes)) != 1)
    return g_heap;
  // A request larger than the free top of the heap makes malloc grow it, by the request plus the pad.
  auto* before = static_cast<char*>(sbrk(0));
  void* probe = std::malloc(mallinfo2().keepcost + (size_t{64} << 10));
  asm volatile("" : : "r"(probe) : "memory");  // the compiler may drop a malloc whose block is unused
  auto* after = static_cast<char*>(sbrk(0));
  mallopt(M_TOP_PAD, static_cast<int>(kDefaultTopPad));
  if (before != reinterpret_cast<char*>(-1) && after >= before + bytes) {  // else the cap, or no break
    auto start = (reinterpret_cast<uintptr_t>(before) + kPage - 1) & ~(uintptr_t{kPage} - 1);
    auto end = reinterpret_cast<uintptr_t>(after) & ~(uintptr_t{kPage} - 1);
    if (madvise(reinterpret_cast<void*>(start), end - start, MADV_HUGEPAGE) == 0) g_heap.reserved = end - start;
  }
  std::free(probe);
  return g_heap;
}

#else

void prepare_huge_heap() {}
HugeHeap reserve_huge_heap(size_t) { return g_heap; }

#endif

HugeHeap huge_heap() { return g_heap; }

}  // namespace fscript::support
