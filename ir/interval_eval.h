#pragma once
// Interval evaluation of a kernel: bounds on every value and output of a straight-line kernel for
// inputs in given intervals, with, for each min / max / select, which operand every point takes.
// The rule of each op comes from the op tables (math_ops.def names runtime/math's iv::FN).
#include <cstdint>
#include <vector>

#include "ir/ir.h"
#include "runtime/math/interval.h"

namespace fscript::ir {

// Which operand a min, max or select takes at every point of the region (Both: it depends).
enum class Choice : uint8_t { Both, Left, Right };

struct IntervalEval {
  std::vector<math::Interval> values;   // by value id
  std::vector<Choice> choices;          // by value id; Both for every other op
  std::vector<math::Interval> outputs;  // the kernel's results, in order
};

// Whether `fn` is straight-line pure code (one block of value ops ending in ret): what interval
// evaluation and tape simplification take. Anything else runs dense (and stays correct).
bool interval_evaluable(const Function& fn);

// The interval rule of one value op over its operands' intervals `v` (by value id).
math::Interval interval_of(const Inst& in, const std::vector<math::Interval>& v);

// Bounds every value of `fn` for parameters in `inputs` (one per parameter). False, with nothing
// written, when `fn` is not interval_evaluable.
bool eval_intervals(const Function& fn, const std::vector<math::Interval>& inputs, IntervalEval& out);

// A straight-line kernel flattened for evaluation over many regions (a quadtree's tiles): one
// step per value op with operand slots (the value ids), so nothing is chased through pointers.
// eval_intervals is one IntervalTape evaluated once.
class IntervalTape {
 public:
  explicit IntervalTape(const Function& fn);  // fn must be interval_evaluable
  void eval(const std::vector<math::Interval>& inputs, IntervalEval& out) const;

 private:
  struct Step {
    Op op;
    bool square;  // a Mul of one value by itself
    uint32_t dst, a, b, c;
    float imm;  // Const; Param: the parameter's index
  };
  std::vector<Step> steps_;
  std::vector<uint32_t> outputs_;
  uint32_t values_ = 0;
};

}  // namespace fscript::ir
