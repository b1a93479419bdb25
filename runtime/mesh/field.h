#pragma once
// A scalar field f(x, y, z) evaluated in batches: what the implicit polygonizer samples. A field
// is one FRep kernel at a fixed t, or a combination built by the scene layer (3D textures,
// FTransform operations).
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "backends/backend.h"

namespace fscript::mesh {

// Time spent in function evaluation while meshing, summed over threads (reported by --stats):
// every batch the polygonizers and colourings evaluate is timed by an EvalTimer.
std::atomic<uint64_t>& evaluation_ns();

class EvalTimer {
 public:
  EvalTimer() : start_(std::chrono::steady_clock::now()) {}
  ~EvalTimer() {
    auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_).count();
    evaluation_ns().fetch_add(static_cast<uint64_t>(ns), std::memory_order_relaxed);
  }
  EvalTimer(const EvalTimer&) = delete;
  EvalTimer& operator=(const EvalTimer&) = delete;

 private:
  std::chrono::steady_clock::time_point start_;
};

class Field {
 public:
  virtual ~Field() = default;
  // out[i] = f(x[i], y[i], z[i]) for i < n; false on a runtime error.
  virtual bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
                    backends::RuntimeError& err) const = 0;
};

// An FRep kernel (inputs x, y, z, t; the first output) at time t.
class KernelField : public Field {
 public:
  KernelField(const backends::Kernel& k, float t) : k_(k), t_(t) {}
  bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
            backends::RuntimeError& err) const override;

 private:
  const backends::Kernel& k_;
  float t_;
};

}  // namespace fscript::mesh
