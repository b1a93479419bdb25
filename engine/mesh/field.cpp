// Fields and kernels evaluated in batches: the kernel field the polygonizers sample, its interval
// bound, and the batching that lets a cancelled run (support/cancel.h) stop within one batch.
#include "engine/mesh/field.h"

#include <algorithm>

namespace fscript::mesh {

std::atomic<uint64_t>& evaluation_ns() {
  static std::atomic<uint64_t> total{0};
  return total;
}

std::atomic<bool>& evaluation_timing() {
  static std::atomic<bool> on{false};
  return on;
}

math::Interval kernel_bound(const ir::IntervalTape& tape, const Box3& b, const std::vector<math::Interval>& extra) {
  thread_local std::vector<math::Interval> in;
  thread_local ir::IntervalEval ev;
  in.clear();
  for (int a = 0; a < 3; ++a) in.push_back({b.lo[a], b.hi[a], false});
  in.insert(in.end(), extra.begin(), extra.end());
  tape.eval(in, ev);
  return ev.outputs.empty() ? math::Interval::everything() : ev.outputs[0];
}

void tape_bounds(const ir::IntervalTape& tape, float t, const Box3* boxes, size_t n, math::Interval* out,
                 const std::function<void(size_t, ir::IntervalBatchEval&, size_t)>& each) {
  thread_local std::vector<ir::IntervalLanes> in(4);
  thread_local ir::IntervalBatchEval ev;
  for (size_t first = 0; first < n; first += ir::kIntervalLanes) {
    const size_t m = std::min(ir::kIntervalLanes, n - first);
    for (size_t k = 0; k < ir::kIntervalLanes; ++k) {
      const Box3& b = boxes[first + std::min(k, m - 1)];  // lanes past the last repeat it
      for (int a = 0; a < 3; ++a) in[static_cast<size_t>(a)].set(k, {b.lo[a], b.hi[a], false});
      in[3].set(k, math::Interval::point(t));
    }
    tape.eval_batch(in, ev);
    for (size_t k = 0; k < m; ++k) out[first + k] = ev.output(0, k);
    if (each)
      for (size_t k = 0; k < m; ++k) each(first + k, ev, k);
  }
}

void Field::bounds_and_locals(const Box3* boxes, size_t n, math::Interval* out, const WantsLocal& wants,
                              std::shared_ptr<const Field>* locals) const {
  bounds(boxes, n, out);
  for (size_t i = 0; i < n; ++i) locals[i] = wants(i, out[i]) ? local(boxes[i]) : nullptr;
}

void KernelField::bounds(const Box3* boxes, size_t n, math::Interval* out) const {
  if (!intervals_) return Field::bounds(boxes, n, out);
  tape_bounds(*intervals_, t_, boxes, n, out);
}

math::Interval KernelField::bound(const Box3& b) const {
  if (!intervals_) return math::Interval::everything();
  return kernel_bound(*intervals_, b, {math::Interval::point(t_)});
}

bool KernelField::eval(const float* x, const float* y, const float* z, size_t n, float* out,
                       backends::RuntimeError& err) const {
  if (stop_if_cancelled(err)) return false;
  // Reused per thread: the polygonizer calls this for every plane and block.
  thread_local std::vector<float> ts, extra;
  ts.assign(n, t_);
  extra.resize(k_.num_outputs() > 1 ? n * (k_.num_outputs() - 1) : 0);
  const float* in[4] = {x, y, z, ts.data()};
  std::vector<float*> outs(k_.num_outputs());
  outs[0] = out;
  for (size_t o = 1; o < outs.size(); ++o) outs[o] = extra.data() + (o - 1) * n;
  return k_.eval_batch(in, outs.data(), n, err);
}

bool Field::eval_gradient(const float*, const float*, const float*, size_t, float* const[4],
                          backends::RuntimeError& err) const {
  err.message = "internal error: this field has no gradient";
  return false;
}

bool KernelField::eval_gradient(const float* x, const float* y, const float* z, size_t n, float* const out[4],
                                backends::RuntimeError& err) const {
  if (stop_if_cancelled(err)) return false;
  thread_local std::vector<float> ts;
  ts.assign(n, t_);
  const float* in[4] = {x, y, z, ts.data()};
  return gradient_->eval_batch(in, out, n, err);
}

bool Field::eval_rows(const float* x, size_t count, const float* y, const float* z, size_t rows, float* out,
                      backends::RuntimeError& err) const {
  thread_local std::vector<float> xs, ys, zs;
  size_t n = count * rows;
  xs.resize(n), ys.resize(n), zs.resize(n);
  for (size_t r = 0; r < rows; ++r)
    for (size_t i = 0; i < count; ++i) xs[r * count + i] = x[i], ys[r * count + i] = y[r], zs[r * count + i] = z[r];
  return eval(xs.data(), ys.data(), zs.data(), n, out, err);
}

bool KernelField::eval_rows(const float* x, size_t count, const float* y, const float* z, size_t rows, float* out,
                            backends::RuntimeError& err) const {
  if (stop_if_cancelled(err)) return false;
  thread_local std::vector<float> ts, extra;
  ts.assign(rows, t_);
  size_t n = count * rows;
  extra.resize(k_.num_outputs() > 1 ? n * (k_.num_outputs() - 1) : 0);
  const float* rest[3] = {y, z, ts.data()};
  std::vector<float*> outs(k_.num_outputs());
  outs[0] = out;
  for (size_t o = 1; o < outs.size(); ++o) outs[o] = extra.data() + (o - 1) * n;
  return k_.eval_rows(x, count, rest, rows, outs.data(), err);
}

bool eval_in_batches(const backends::Kernel& k, const float* const* in, float* const* out, size_t n,
                     backends::RuntimeError& err) {
  std::vector<const float*> ins(k.num_inputs());
  std::vector<float*> outs(k.num_outputs());
  for (size_t b = 0; b < n; b += kEvalBatch) {
    if (stop_if_cancelled(err)) return false;
    for (size_t i = 0; i < ins.size(); ++i) ins[i] = in[i] + b;
    for (size_t o = 0; o < outs.size(); ++o) outs[o] = out[o] + b;
    if (!k.eval_batch(ins.data(), outs.data(), std::min(kEvalBatch, n - b), err)) return false;
  }
  return true;
}

}  // namespace fscript::mesh
