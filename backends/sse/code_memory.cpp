// W^X code pages through mmap / mprotect / munmap.
#include "backends/sse/code_memory.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <algorithm>
#include <cstring>

namespace fscript::sse {

std::unique_ptr<CodeMemory> CodeMemory::create(const std::vector<uint8_t>& code, std::string& error) {
  size_t page = static_cast<size_t>(sysconf(_SC_PAGESIZE));
  size_t mapped = (std::max<size_t>(code.size(), 1) + page - 1) / page * page;
  void* p = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) {
    error = std::string("cannot map memory for machine code: ") + std::strerror(errno);
    return nullptr;
  }
  std::memcpy(p, code.data(), code.size());
  if (mprotect(p, mapped, PROT_READ | PROT_EXEC) != 0) {
    error = std::string("cannot make machine code executable: ") + std::strerror(errno);
    munmap(p, mapped);
    return nullptr;
  }
  return std::unique_ptr<CodeMemory>(new CodeMemory(static_cast<uint8_t*>(p), mapped, code.size()));
}

CodeMemory::~CodeMemory() { munmap(start_, mapped_); }

}  // namespace fscript::sse
