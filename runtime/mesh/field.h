#pragma once
// A scalar field f(x, y, z) evaluated in batches: what the implicit polygonizer samples. A field
// is one FRep kernel at a fixed t, or a combination built by the scene layer (3D textures,
// FTransform operations).
#include <cstddef>
#include <vector>

#include "backends/backend.h"

namespace fscript::mesh {

class Field {
 public:
  virtual ~Field() = default;
  // out[i] = f(x[i], y[i], z[i]) for i < n; false on a runtime error.
  virtual bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
                    backend::RuntimeError& err) const = 0;
};

// An FRep kernel (inputs x, y, z, t; the first output) at time t.
class KernelField : public Field {
 public:
  KernelField(const backend::Kernel& k, float t) : k_(k), t_(t) {}
  bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
            backend::RuntimeError& err) const override;

 private:
  const backend::Kernel& k_;
  float t_;
};

}  // namespace fscript::mesh
