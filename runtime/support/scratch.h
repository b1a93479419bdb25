#pragma once
// Per-thread scratch arrays of floats, reused from call to call: hot paths that need a batch's
// worth of room per call (a group's fold, a gradient's children) would otherwise allocate anew each
// time, and a large allocation is fresh pages from the kernel, with their faults, every time.
#include <cstddef>
#include <memory>
#include <vector>

namespace fscript::support {

// Holds an array of at least n floats (not zeroed) until it goes out of scope; nested holders on
// one thread (a group inside a group) each get their own.
class ScratchFloats {
 public:
  explicit ScratchFloats(size_t n) : buf_(take()) {
    if (buf_->size < n) buf_->data.reset(new float[n]), buf_->size = n;
  }
  ~ScratchFloats() { pool().push_back(std::move(buf_)); }
  ScratchFloats(const ScratchFloats&) = delete;
  ScratchFloats& operator=(const ScratchFloats&) = delete;
  float* get() const { return buf_->data.get(); }

 private:
  struct Buffer {
    std::unique_ptr<float[]> data;
    size_t size = 0;
  };
  static std::vector<std::unique_ptr<Buffer>>& pool() {
    thread_local std::vector<std::unique_ptr<Buffer>> free;
    return free;
  }
  static std::unique_ptr<Buffer> take() {
    auto& free = pool();
    if (free.empty()) return std::make_unique<Buffer>();
    auto b = std::move(free.back());
    free.pop_back();
    return b;
  }
  std::unique_ptr<Buffer> buf_;
};

}  // namespace fscript::support
