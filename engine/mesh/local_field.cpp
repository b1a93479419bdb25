// Local fields (local_field.h): a region's simplified tapes run with no compile. A region inside a
// region simplifies its parent's tapes, so the deeper the octree, the shorter and cheaper the step.
#include "engine/mesh/local_field.h"

#include <algorithm>
#include <mutex>

#include "backends/vm/vm_backend.h"
#include "backends/vm/vm_points.h"

namespace fscript::mesh {

LocalTapeStats& local_tape_totals() {
  static LocalTapeStats s;
  return s;
}

// The kernel's field inside one region, on the region's tape; its gradient's tape is simplified
// from the parent region's at the first gradient asked (a region shared by threads: once).
class TapeField : public Field, public std::enable_shared_from_this<TapeField> {
 public:
  TapeField(std::shared_ptr<const ir::IntervalTape> tape, const Box3& box, std::shared_ptr<const TapeField> parent,
            const LocalTapes& owner)
      : tape_(std::move(tape)), box_(box), parent_(std::move(parent)), owner_(owner) {}

  bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
            backends::RuntimeError& err) const override {
    if (stop_if_cancelled(err)) return false;
    if (n > kDirect) {  // a block's samples: the tape compiled, its registers reused (in cache)
      std::call_once(compile_once_, [this] { compiled_ = vm::compile_tape(*tape_, backends::Budgets{}); });
      thread_local std::vector<float> ts;
      ts.assign(n, owner_.t_);
      const float* in[4] = {x, y, z, ts.data()};
      float* outs[1] = {out};
      return compiled_->eval_batch(in, outs, n, err);
    }
    float* outs[1] = {out};
    run(*tape_, x, y, z, n, outs, 1);
    return true;
  }
  math::Interval bound(const Box3& b) const override {
    return kernel_bound(*tape_, b, {math::Interval::point(owner_.t_)});
  }
  bool can_bound() const override { return true; }
  void bounds(const Box3* boxes, size_t n, math::Interval* out) const override {
    tape_bounds(*tape_, owner_.t_, boxes, n, out);
  }
  void bounds_and_locals(const Box3* boxes, size_t n, math::Interval* out, const WantsLocal& wants,
                         std::shared_ptr<const Field>* locals) const override {
    owner_.batch(*tape_, shared_from_this(), boxes, n, out, wants, locals);
  }
  bool has_gradient() const override { return static_cast<bool>(owner_.gradient_); }
  bool eval_gradient(const float* x, const float* y, const float* z, size_t n, float* const out[4],
                     backends::RuntimeError& err) const override {
    if (stop_if_cancelled(err)) return false;
    const ir::IntervalTape* g = gradient_tape();
    if (!g) {
      err.message = "internal error: a region's field has no gradient tape";
      return false;
    }
    run(*g, x, y, z, n, out, 4);
    return true;
  }
  std::shared_ptr<const Field> local(const Box3& b) const override {
    std::shared_ptr<const ir::IntervalTape> t = owner_.narrow(*tape_, b, true);
    if (!t) return nullptr;
    return std::make_shared<TapeField>(std::move(t), b, shared_from_this(), owner_);
  }
  const ir::IntervalTape* value_tape() const override { return tape_.get(); }
  // The gradient's tape for this region: the parent's (or the whole gradient) simplified for the box.
  const ir::IntervalTape* gradient_tape() const override {
    std::call_once(gradient_once_, [this] {
      const ir::IntervalTape* from = parent_ ? parent_->gradient_tape() : owner_.gradient_();
      if (!from) return;
      local_tape_totals().gradients.fetch_add(1, std::memory_order_relaxed);
      gradient_ = owner_.narrow(*from, box_, false);
      gradient_from_ = gradient_ ? gradient_.get() : from;
      if (gradient_) parent_.reset();  // its tapes are not needed here any more (a mesh keeps thousands)
    });
    return gradient_from_;
  }

 private:
  // Outputs [0, count) of `t` at n points, kPointLanes at a time.
  void run(const ir::IntervalTape& t, const float* x, const float* y, const float* z, size_t n, float* const* out,
           size_t count) const {
    float ts[vm::kPointLanes];
    std::fill_n(ts, vm::kPointLanes, owner_.t_);
    float* o[4];
    for (size_t i = 0; i < n; i += vm::kPointLanes) {
      const float* in[4] = {x + i, y + i, z + i, ts};
      for (size_t k = 0; k < count; ++k) o[k] = out[k] + i;
      vm::eval_tape_points(t, in, 4, std::min(vm::kPointLanes, n - i), o, count);
    }
  }

  std::shared_ptr<const ir::IntervalTape> tape_;
  Box3 box_;
  mutable std::shared_ptr<const TapeField> parent_;  // until the gradient's tape is made
  const LocalTapes& owner_;
  // Batches up to this many points run straight from the tape; larger ones on its compiled code.
  static constexpr size_t kDirect = 1024;
  mutable std::once_flag compile_once_;
  mutable std::unique_ptr<backends::Kernel> compiled_;
  mutable std::once_flag gradient_once_;
  mutable std::shared_ptr<const ir::IntervalTape> gradient_;  // null: the parent's serves
  mutable const ir::IntervalTape* gradient_from_ = nullptr;
};

std::shared_ptr<const Field> LocalTapes::at(const Box3& box) const {
  std::shared_ptr<const ir::IntervalTape> t = narrow(full_, box, true);
  if (!t) return nullptr;
  return std::make_shared<TapeField>(std::move(t), box, nullptr, *this);
}

std::shared_ptr<const ir::IntervalTape> LocalTapes::narrow(const ir::IntervalTape& from, const Box3& box,
                                                           bool counted) const {
  LocalTapeStats& st = local_tape_totals();
  if (counted) st.regions.fetch_add(1, std::memory_order_relaxed);
  thread_local std::vector<math::Interval> in;
  thread_local ir::IntervalEval ev;
  in.clear();
  for (int a = 0; a < 3; ++a) in.push_back({box.lo[a], box.hi[a], false});
  in.push_back(math::Interval::point(t_));
  from.eval(in, ev);
  return keep(from.simplified(ev), from, counted);
}

std::shared_ptr<const ir::IntervalTape> LocalTapes::keep(ir::IntervalTape&& t, const ir::IntervalTape& from,
                                                         bool counted) const {
  LocalTapeStats& st = local_tape_totals();
  if (t.length() * 10 > from.length() * 9) return nullptr;
  auto tape = std::make_shared<const ir::IntervalTape>(std::move(t));
  if (counted) {
    st.simplified.fetch_add(1, std::memory_order_relaxed);
    st.tape_ops.fetch_add(tape->length(), std::memory_order_relaxed);
    st.full_ops.fetch_add(full_.length(), std::memory_order_relaxed);
  }
  return tape;
}

void LocalTapes::batch(const ir::IntervalTape& from, const std::shared_ptr<const TapeField>& parent, const Box3* boxes,
                       size_t n, math::Interval* out, const WantsLocal& wants,
                       std::shared_ptr<const Field>* locals) const {
  tape_bounds(from, t_, boxes, n, out, [&](size_t i, ir::IntervalBatchEval& ev, size_t lane) {
    locals[i] = nullptr;
    if (!wants(i, out[i])) return;
    local_tape_totals().regions.fetch_add(1, std::memory_order_relaxed);
    if (std::shared_ptr<const ir::IntervalTape> t = keep(from.simplified(ev, lane), from, true))
      locals[i] = std::make_shared<TapeField>(std::move(t), boxes[i], parent, *this);
  });
}

}  // namespace fscript::mesh
