// The huge heap (runtime/support/huge_heap.h): where the machine allows it, the memory malloc hands
// out afterwards is in the reserved range and the kernel has it marked for huge pages; elsewhere
// (a sanitizer's allocator, huge pages off) nothing changes.
#include <catch2/catch.hpp>
#include <cstdint>
#include <cstdlib>
#include <fstream>
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
