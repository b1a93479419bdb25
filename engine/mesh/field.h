#pragma once
// A scalar field f(x, y, z) evaluated in batches: what the implicit polygonizer samples. A field
// is one FRep kernel at a fixed t, or a combination built by the scene layer (3D textures,
// FTransform operations).
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "backends/backend.h"
#include "ir/interval_eval.h"
#include "runtime/math/interval.h"
#include "runtime/support/cancel.h"

namespace fscript::mesh {

// Time spent in function evaluation while meshing, summed over threads (reported by --stats):
// every batch the polygonizers, colourings and direct pictures evaluate is timed by an EvalTimer,
// while evaluation_timing() is on. Off by default: a run that reports no time reads no clock
// (two reads a batch were 6% of a direct picture, whose batches are small).
std::atomic<uint64_t>& evaluation_ns();
std::atomic<bool>& evaluation_timing();

class EvalTimer {
 public:
  EvalTimer() : on_(evaluation_timing().load(std::memory_order_relaxed)) {
    if (on_) start_ = std::chrono::steady_clock::now();
  }
  ~EvalTimer() {
    if (!on_) return;
    auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_).count();
    evaluation_ns().fetch_add(static_cast<uint64_t>(ns), std::memory_order_relaxed);
  }
  EvalTimer(const EvalTimer&) = delete;
  EvalTimer& operator=(const EvalTimer&) = delete;

 private:
  bool on_;
  std::chrono::steady_clock::time_point start_;
};

// The points x in [lo[0], hi[0]], y in [lo[1], hi[1]], z in [lo[2], hi[2]].
struct Box3 {
  float lo[3], hi[3];
};

// Per box of a batch (its index and bound): whether the caller wants the box's local field.
using WantsLocal = std::function<bool(size_t, const math::Interval&)>;

class Field {
 public:
  virtual ~Field() = default;
  // out[i] = f(x[i], y[i], z[i]) for i < n; false on a runtime error.
  virtual bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
                    backends::RuntimeError& err) const = 0;
  // Rows of a grid: out[r * count + i] = f(x[i], y[r], z[r]). The same values as eval over those
  // points; a kernel field computes what does not depend on x once per row (Kernel::eval_rows).
  virtual bool eval_rows(const float* x, size_t count, const float* y, const float* z, size_t rows, float* out,
                         backends::RuntimeError& err) const;
  // Holds eval's result, rounding included, at every point of the box (NaN flagged). A field that
  // cannot bound itself says "anything", and the polygonizer then samples the region point by point.
  virtual math::Interval bound(const Box3&) const { return math::Interval::everything(); }
  // bound() of n boxes (a region's children): a field on a tape bounds them in one batched pass.
  virtual void bounds(const Box3* boxes, size_t n, math::Interval* out) const {
    for (size_t i = 0; i < n; ++i) out[i] = bound(boxes[i]);
  }
  // Whether bound() can ever say more than "anything" (else the polygonizer does not ask).
  virtual bool can_bound() const { return false; }
  // f and its gradient at points: out[0][i] = f, out[1..3][i] = df/dx, df/dy, df/dz (infinite or
  // NaN where f is not differentiable there). Only asked when has_gradient(); the polygonizers
  // otherwise take central differences of eval.
  virtual bool has_gradient() const { return false; }
  virtual bool eval_gradient(const float* x, const float* y, const float* z, size_t n, float* const out[4],
                             backends::RuntimeError& err) const;
  // A field with this one's bits at every point of the box, cheaper there (the tape simplified for
  // the region: local_field.h); nullptr where there is none, and the polygonizer asks this one.
  virtual std::shared_ptr<const Field> local(const Box3&) const { return nullptr; }
  // bounds() of n boxes, and for each box `wants` asks for, what local() gives for it: a field on
  // a tape takes both from one interval pass (local() alone bounds its box again).
  virtual void bounds_and_locals(const Box3* boxes, size_t n, math::Interval* out, const WantsLocal& wants,
                                 std::shared_ptr<const Field>* locals) const;
  // The tapes this field runs for its values and for its gradient, where it runs one (nullptr: it
  // runs something else): the profiler charges their steps to source lines. The gradient's tape may
  // be made at this ask.
  virtual const ir::IntervalTape* value_tape() const { return nullptr; }
  virtual const ir::IntervalTape* gradient_tape() const { return nullptr; }
  // Every tape an evaluation of this field runs: its own, or a combination's parts' (an
  // FTransform's children and its operation), appended to `out`.
  virtual void part_tapes(bool gradient, std::vector<const ir::IntervalTape*>& out) const {
    if (const ir::IntervalTape* t = gradient ? gradient_tape() : value_tape()) out.push_back(t);
  }
  // The mesher knows how many points the whole function will be asked for once the octree has
  // handed out its regions' tapes (backends::Kernel::expect_points: auto then compiles or not).
  virtual void expect_points(uint64_t) const {}
};

// Whether the run is cancelled (support/cancel.h), said in `err`: the kernels' fields ask before
// each batch, so a cancel stops a frame within one batch, not at its end.
inline bool stop_if_cancelled(backends::RuntimeError& err) {
  if (!support::run_cancelled()) return false;
  err.message = support::kCancelledMessage;
  return true;
}

// Points per evaluation call where the caller picks the batches (grid planes, parametric grids,
// per-vertex colours and displacements): a cancelled run stops within one.
constexpr size_t kEvalBatch = 8192;

// k.eval_batch over n points (in[i], out[o] are k's columns) in batches of kEvalBatch, asking
// before each whether the run is cancelled; stops at the first failing batch.
bool eval_in_batches(const backends::Kernel& k, const float* const* in, float* const* out, size_t n,
                     backends::RuntimeError& err);

// `tape` (a kernel of x, y, z, t) over n boxes at time t in batches of ir::kIntervalLanes: out[i]
// its first output over boxes[i]; `each` (when given) sees every box's batch evaluation and lane.
void tape_bounds(const ir::IntervalTape& tape, float t, const Box3* boxes, size_t n, math::Interval* out,
                 const std::function<void(size_t, ir::IntervalBatchEval&, size_t)>& each = {});

// The result of `tape` (a kernel of x, y, z, t and perhaps more inputs, given in `extra`) over a box.
math::Interval kernel_bound(const ir::IntervalTape& tape, const Box3& b, const std::vector<math::Interval>& extra);

// An FRep kernel (inputs x, y, z, t; the first output) at time t; `intervals`, when the kernel has
// them (ir::interval_evaluable), bounds it, and `gradient`, when it has one (ir::gradient_module:
// outputs f, df/dx, df/dy, df/dz), gives its gradient.
class KernelField : public Field {
 public:
  KernelField(const backends::Kernel& k, float t, const ir::IntervalTape* intervals = nullptr,
              const backends::Kernel* gradient = nullptr)
      : k_(k), t_(t), intervals_(intervals), gradient_(gradient) {}
  bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
            backends::RuntimeError& err) const override;
  bool eval_rows(const float* x, size_t count, const float* y, const float* z, size_t rows, float* out,
                 backends::RuntimeError& err) const override;
  math::Interval bound(const Box3& b) const override;
  void bounds(const Box3* boxes, size_t n, math::Interval* out) const override;
  bool can_bound() const override { return intervals_ != nullptr; }
  bool has_gradient() const override { return gradient_ != nullptr; }
  bool eval_gradient(const float* x, const float* y, const float* z, size_t n, float* const out[4],
                     backends::RuntimeError& err) const override;
  const ir::IntervalTape* value_tape() const override { return intervals_; }

 private:
  const backends::Kernel& k_;
  float t_;
  const ir::IntervalTape* intervals_;
  const backends::Kernel* gradient_;
};

}  // namespace fscript::mesh
