#pragma once
// Executable memory that is never writable and executable at once: pages are mapped read-write,
// the code is copied in, then they become read-execute (W^X); they are unmapped with their owner.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace fscript::sse {

class CodeMemory {
 public:
  // nullptr with a message when the system refuses the mapping or the protection change.
  static std::unique_ptr<CodeMemory> create(const std::vector<uint8_t>& code, std::string& error);
  ~CodeMemory();
  CodeMemory(const CodeMemory&) = delete;
  CodeMemory& operator=(const CodeMemory&) = delete;

  const uint8_t* start() const { return start_; }
  size_t size() const { return size_; }

 private:
  CodeMemory(uint8_t* start, size_t mapped, size_t size) : start_(start), mapped_(mapped), size_(size) {}
  uint8_t* start_;
  size_t mapped_, size_;
};

}  // namespace fscript::sse
