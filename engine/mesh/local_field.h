#pragma once
// Fields for one region of space: a kernel's tape simplified over the region's box (each min, max
// and select its intervals decide there becomes its side), and its gradient's tape the same way,
// both run straight from the tape. Inside the box they give the kernel's bits.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "backends/backend.h"
#include "engine/mesh/field.h"
#include "ir/interval_eval.h"

namespace fscript::mesh {

// What the local tapes of every job since the process started did (fvrml-run --stats).
struct LocalTapeStats {
  std::atomic<uint64_t> regions{0};      // regions asked for a local field
  std::atomic<uint64_t> simplified{0};   // of those, given a shorter tape
  std::atomic<uint64_t> tape_ops{0};     // summed over the simplified: their tapes' lengths
  std::atomic<uint64_t> full_ops{0};     // summed over the simplified: the whole tape's length
  std::atomic<uint64_t> gradients{0};    // gradient tapes simplified (regions whose gradient was asked)
};
LocalTapeStats& local_tape_totals();

// The gradient's flat tape (f, df/dx, df/dy, df/dz over x, y, z, t), built at the first call by
// the layer that owns the passes; nullptr where the field has none.
using GradientTape = std::function<const ir::IntervalTape*()>;

class TapeField;

class LocalTapes {
 public:
  // `full`: the kernel's tape over (x, y, z, t), alive as long as this; `t`: the time the field is
  // taken at; `gradient`: set where the kernel's field has a gradient (its fields then give one,
  // from the gradient's tape simplified for their regions in turn).
  LocalTapes(const ir::IntervalTape& full, float t, GradientTape gradient)
      : full_(full), t_(t), gradient_(std::move(gradient)) {}
  // A field equal, bit for bit, to the kernel's at every point of `box`; nullptr where the box
  // decides too little for a shorter tape to pay (under a tenth shorter).
  std::shared_ptr<const Field> at(const Box3& box) const;
  // Field::bounds_and_locals of the whole kernel's field.
  void bounds_and_locals(const Box3* boxes, size_t n, math::Interval* out, const WantsLocal& wants,
                         std::shared_ptr<const Field>* locals) const {
    batch(full_, nullptr, boxes, n, out, wants, locals);
  }

 private:
  friend class TapeField;
  // `from` simplified over `box`, or nullptr where that saves under a tenth; `counted`: a value
  // tape, in the stats.
  std::shared_ptr<const ir::IntervalTape> narrow(const ir::IntervalTape& from, const Box3& box, bool counted) const;
  // The simplified tape kept (or nullptr where it saves under a tenth of `from`), counted in the stats.
  std::shared_ptr<const ir::IntervalTape> keep(ir::IntervalTape&& t, const ir::IntervalTape& from, bool counted) const;
  // bounds_and_locals over `from`: the whole tape (parent nullptr) or a region's.
  void batch(const ir::IntervalTape& from, const std::shared_ptr<const TapeField>& parent, const Box3* boxes, size_t n,
             math::Interval* out, const WantsLocal& wants, std::shared_ptr<const Field>* locals) const;
  const ir::IntervalTape& full_;
  float t_;
  GradientTape gradient_;
};

// An FRep kernel's field that hands out its regions' tapes, as a scene shape's field does for its
// FRep (fscript render3d; the tests).
class LocalKernelField : public KernelField {
 public:
  LocalKernelField(const backends::Kernel& k, float t, const ir::IntervalTape& tape, const backends::Kernel* gradient,
                   GradientTape gradient_tape)
      : KernelField(k, t, &tape, gradient), tapes_(tape, t, std::move(gradient_tape)) {}
  std::shared_ptr<const Field> local(const Box3& b) const override { return tapes_.at(b); }
  void bounds_and_locals(const Box3* boxes, size_t n, math::Interval* out, const WantsLocal& wants,
                         std::shared_ptr<const Field>* locals) const override {
    tapes_.bounds_and_locals(boxes, n, out, wants, locals);
  }

 private:
  LocalTapes tapes_;
};

}  // namespace fscript::mesh
