#pragma once
// Interval evaluation of a kernel: bounds on every value and output of a straight-line kernel for
// inputs in given intervals, with, for each min / max / select, which operand every point takes.
// The rule of each op comes from the op table (math_ops.def names runtime/math's iv::FN).
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "ir/ir.h"
#include "runtime/math/interval.h"

namespace fscript::ir {

// Which operand a min, max or select takes at every point of the region (Both: it depends).
enum class Choice : uint8_t { Both, Left, Right };

// An allocator whose vectors grow without initialising their new elements (resize does not zero
// what is about to be written): evaluation scratch reused across tapes of other lengths.
template <class T>
struct Uninitialised : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = Uninitialised<U>;
  };
  using std::allocator<T>::allocator;
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

struct IntervalEval {
  std::vector<math::Interval> values;   // by value id
  std::vector<Choice> choices;          // by value id; Both for every other op
  std::vector<math::Interval> outputs;  // the kernel's results, in order
};

// Many regions at once: lane k of every value belongs to region k. Laid out for SIMD (one vector
// register per field on AVX-512), so a tape's step costs about what one region's step costs.
constexpr size_t kIntervalLanes = 16;
struct IntervalLanes {
  alignas(64) float lo[kIntervalLanes];
  alignas(64) float hi[kIntervalLanes];
  alignas(64) uint32_t nan[kIntervalLanes];

  math::Interval lane(size_t k) const { return {lo[k], hi[k], nan[k]}; }
  void set(size_t k, const math::Interval& v) { lo[k] = v.lo, hi[k] = v.hi, nan[k] = v.nan; }
};

struct IntervalBatchEval {
  std::vector<IntervalLanes, Uninitialised<IntervalLanes>> values;  // by value id
  // [value id * kIntervalLanes + lane], written for the min, max and select steps only (nothing
  // reads the others').
  std::vector<Choice, Uninitialised<Choice>> choices;
  std::vector<uint32_t> outputs;      // value ids of the kernel's results
  // Simplification's backward pass for all lanes at once, by value id, a bit per lane: the value is
  // needed, and it is a decided choice standing for its side. Made by the first simplified().
  std::vector<uint16_t> needed, stands;
  bool masks = false;
  math::Interval output(size_t k, size_t lane) const { return values[outputs[k]].lane(lane); }
};

// The ops the batched evaluator runs as SIMD (ir/interval_lanes.cpp); it runs every other op's
// scalar rule lane by lane, an order of magnitude slower, but sin and cos, whose ends it takes
// from their batch twin in one call for all lanes (still many times an add: not counted here,
// where "as cheap as a few points" is what is asked).
constexpr bool simd_interval_op(Op op) {
  return op == Op::Param || op == Op::Const || op == Op::Add || op == Op::Sub || op == Op::Mul || op == Op::Neg ||
      op == Op::Min || op == Op::Max || op == Op::Sqrt;
}

// Whether `fn` is straight-line pure code (one block of value ops ending in ret): what interval
// evaluation and tape simplification take. Anything else runs dense (and stays correct).
bool interval_evaluable(const Function& fn);

// The interval rule of one value op over its operands' intervals `v` (by value id).
math::Interval interval_of(const Inst& in, const std::vector<math::Interval>& v);
// The rule of `op` on operand intervals (`square`: a Mul of one value by itself; `imm`: a Const's
// value), and which operand a min / max / select takes over the whole region.
math::Interval interval_rule(Op op, bool square, float imm, const math::Interval& a, const math::Interval& b,
                             const math::Interval& c);
Choice choice_of(Op op, const math::Interval& a, const math::Interval& b, const math::Interval& c);

// Bounds every value of `fn` for parameters in `inputs` (one per parameter). False, with nothing
// written, when `fn` is not interval_evaluable.
bool eval_intervals(const Function& fn, const std::vector<math::Interval>& inputs, IntervalEval& out);

// A straight-line kernel flattened: one step per value op with operand slots (value ids), so
// nothing is chased through pointers. It is what interval evaluation runs over many regions (a
// quadtree's tiles, an octree's bricks; eval_intervals is one IntervalTape evaluated once), what
// simplification shortens, and what the VM compiles directly (vm::compile_tape).
class IntervalTape {
 public:
  struct Step {
    Op op;
    bool square;    // a Mul of one value by itself
    uint8_t arity;  // operands used of a, b, c
    uint32_t dst, a, b, c;
    float imm;  // Const; Param: the parameter's index is `a`
  };
  // Grown uninitialised: simplification writes the new tape in place at the old one's length and
  // then cuts it, with no zeroing and no second copy.
  using Steps = std::vector<Step, Uninitialised<Step>>;

  explicit IntervalTape(const Function& fn);  // fn must be interval_evaluable
  IntervalTape() = default;                    // an empty tape, to be written by simplified()
  void eval(const std::vector<math::Interval>& inputs, IntervalEval& out) const;
  // kIntervalLanes regions in one pass (`inputs[p]`: parameter p in each lane); every lane's
  // bounds are sound, and as tight as eval's up to the last ulp (ir/interval_batch.cpp).
  void eval_batch(const std::vector<IntervalLanes>& inputs, IntervalBatchEval& out) const;

  // The tape specialised to a region (`ev`: this tape's evaluation over it): every min / max /
  // select whose side was decided becomes that side, what only the other side needed is dropped,
  // values are renumbered densely. The same bits as this tape at every point of the region; it
  // recurses. `collapsed` (when given) counts the choices that were decided.
  IntervalTape simplified(const IntervalEval& ev, size_t* collapsed = nullptr) const;
  // The same from lane `lane` of a batch evaluation (the first call does the backward pass of
  // every lane, the others reuse it).
  IntervalTape simplified(IntervalBatchEval& ev, size_t lane) const;
  // The same written into `out`, whose storage is reused (a renderer keeps one tape per level).
  void simplified(IntervalBatchEval& ev, size_t lane, IntervalTape& out) const;
  // That backward pass now (so threads may then simplify lanes of `ev` at once).
  void lane_masks(IntervalBatchEval& ev) const;

  const Steps& steps() const { return steps_; }
  const std::vector<uint32_t>& outputs() const { return outputs_; }
  // Where each step's op is in the source (line and column; 0 where none): kept by the tape made
  // from a function, and by the tapes simplified from one while a KeepSources lives (the profiler
  // maps a region's steps to lines); empty otherwise, which costs simplification nothing.
  struct Where {
    uint32_t line = 0, col = 0;
  };
  const std::vector<Where>& sources() const { return sources_; }
  uint32_t num_values() const { return values_; }  // value ids are below this
  uint32_t num_params() const { return params_; }
  size_t length() const { return steps_.size(); }  // value ops, parameters and constants included
  size_t operations() const;  // steps that compute: parameters and constants left out
  // Whether every step is a simd_interval_op (batched bounds cost about what a few points do).
  bool simd_only() const { return simd_only_; }

 private:
  IntervalTape simplified(const Choice* choices, size_t stride, size_t* collapsed) const;
  // The forward pass: the needed steps in order, renumbered, a standing choice taking its side's number.
  // `each(f)` calls f(i) for every needed step i, in order.
  template <typename Each, typename Stands>
  void emit(const Choice* choices, size_t stride, Each each, Stands stands, IntervalTape& out) const;
  template <typename Needed>
  auto every_step(Needed needed) const;
  struct LaneSteps;
  Steps steps_;
  std::vector<uint32_t> outputs_;
  std::vector<Where> sources_;  // by step; empty in simplified tapes
  uint32_t values_ = 0, params_ = 0;
  bool simd_only_ = true;
  bool dense_ = true;  // step i defines value i (simplified tapes always; a function's when numbered so)
};

// While one of these lives (in any thread), simplified tapes keep their steps' sources.
class KeepSources {
 public:
  KeepSources();
  ~KeepSources();
  KeepSources(const KeepSources&) = delete;
  KeepSources& operator=(const KeepSources&) = delete;
};
bool keeping_sources();

// The tape's values at one point (`params`, one per parameter), step by step with the reference
// semantics of constant folding (ir::eval_pure): the index of the first step whose value is NaN
// while none of its operands is, or length() when no step makes one.
size_t first_nan_step(const IntervalTape& t, const float* params);

}  // namespace fscript::ir
