// The huge heap (runtime/support/huge_heap.h): where the machine allows it, the memory malloc hands
// out afterwards is in the reserved range and the kernel has it marked for huge pages; with huge
// pages off (ctest runs it again with FSCRIPT_HUGE_PAGES=0) the heap is still kept; under a
// sanitizer's allocator nothing changes.
#include <catch2/catch.hpp>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <malloc.h>
#include <unistd.h>
#include <sstream>
#include <string>

#include "runtime/support/huge_heap.h"
#include "runtime/support/sanitizers.h"

using namespace fscript;

namespace {

bool sanitized() { return support::kForeignMalloc; }

bool huge_pages_on() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(f, line) && line.find("[never]") == std::string::npos;
}

// The VmFlags of the mapping that holds `p`, from /proc/self/smaps.
std::string flags_of(const void* p) {
  std::ifstream f("/proc/self/smaps");
  auto at = reinterpret_cast<uintptr_t>(p);
  bool mine = false;
  for (std::string line; std::getline(f, line);) {
    uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') mine = lo <= at && at < hi;
    else if (mine && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

}  // namespace

TEST_CASE("huge heap: later allocations land in the range advised for huge pages") {
  support::prepare_huge_heap();
  support::HugeHeap h = support::reserve_huge_heap(size_t{64} << 20);
  if (sanitized() || !huge_pages_on() || std::getenv("FSCRIPT_HUGE_PAGES")) {
    CHECK(h.reserved == 0);
    return;
  }
  REQUIRE(h.reserved >= (size_t{64} << 20));
  CHECK(support::huge_heap().reserved == h.reserved);
  // Up to 32 MiB comes from the heap now, not from a mapping of its own (its first bytes may still
  // be in the free top the heap had before the reservation).
  auto* buffer = static_cast<char*>(std::malloc(size_t{8} << 20));
  REQUIRE(buffer);
  CHECK(flags_of(buffer + (size_t{4} << 20)).find(" hg") != std::string::npos);
  CHECK(flags_of(buffer + (size_t{8} << 20) - 1).find(" hg") != std::string::npos);
  std::free(buffer);
  // Once is enough: a second call changes nothing.
  CHECK(support::reserve_huge_heap(size_t{128} << 20).reserved == h.reserved);
}

TEST_CASE("huge heap: without huge pages the heap is still kept: large blocks from it, not trimmed") {
  support::prepare_huge_heap();
  support::HugeHeap h = support::reserve_huge_heap(size_t{64} << 20);
  if (sanitized() || h.reserved > 0) return;  // the huge heap keeps it too (the case above)
  // 8 MiB would be a mapping of its own under glibc's first threshold (128 KiB), given back to the
  // kernel when freed and faulted in again by the next one.
  const size_t mapped = mallinfo2().hblkhd;
  auto* buffer = static_cast<char*>(std::malloc(size_t{8} << 20));
  REQUIRE(buffer);
  buffer[0] = buffer[(size_t{8} << 20) - 1] = 1;
  CHECK(mallinfo2().hblkhd == mapped);
  void* top = sbrk(0);
  std::free(buffer);
  CHECK(sbrk(0) == top);  // not trimmed
}
