// Interval evaluation over one block, and the choice record that tape simplification reads.
#include "ir/interval_eval.h"

namespace fscript::ir {
namespace {

using math::Interval;

Choice choice_of(const Inst& in, const std::vector<Interval>& v) {
  auto arg = [&](size_t i) { return v[in.args[i]->id]; };
  if (in.op == Op::Select) {
    math::Truth t = math::truth_of(arg(0));
    return t == math::Truth::Always ? Choice::Left : t == math::Truth::Never ? Choice::Right : Choice::Both;
  }
  if (in.op != Op::Min && in.op != Op::Max) return Choice::Both;
  // The other side must never be NaN (min/max give NaN if either is), and the sides must not
  // touch, so the side taken is the result bit for bit (no question of the sign of a zero).
  Interval a = arg(0), b = arg(1);
  if (a.empty() || b.empty()) return Choice::Both;
  bool a_below = a.hi < b.lo, b_below = b.hi < a.lo;
  bool min = in.op == Op::Min;
  if ((min ? a_below : b_below) && !b.nan) return Choice::Left;
  if ((min ? b_below : a_below) && !a.nan) return Choice::Right;
  return Choice::Both;
}

}  // namespace

bool interval_evaluable(const Function& fn) {
  if (fn.blocks.size() != 1) return false;
  for (const Inst* in : fn.entry()->insts) {
    if (in->op == Op::Ret) continue;
    if (!has_flag(in->op, Pure) || in->op == Op::Phi) return false;
  }
  const Inst* t = fn.entry()->terminator();
  return t && t->op == Op::Ret;
}

Interval interval_of(const Inst& in, const std::vector<Interval>& v) {
  auto arg = [&](size_t i) { return v[in.args[i]->id]; };
  if (in.op == Op::Mul && in.args[0] == in.args[1]) return math::iv::square(arg(0));
  switch (in.op) {
#define FS_IV_1(N, FN) \
  case Op::N: return math::iv::FN(arg(0));
#define FS_IV_2(N, FN) \
  case Op::N: return math::iv::FN(arg(0), arg(1));
#define FS_IV_3(N, FN) \
  case Op::N: return math::iv::FN(arg(0), arg(1), arg(2));
#define FS_MATH(N, FN, A, HOW) FS_IV_##A(N, FN)
#include "ir/math_ops.def"
#undef FS_IV_1
#undef FS_IV_2
#undef FS_IV_3
    case Op::Const: return Interval::point(in.imm);
    // Parameters come from the region; memory, calls and control flow are not bounded here.
    case Op::Param: case Op::Phi: case Op::GLoad: case Op::GStore: case Op::ANew: case Op::ALoad:
    case Op::AStore: case Op::ALen: case Op::Call: case Op::Tick: case Op::Jump: case Op::Branch: case Op::Ret:
      return Interval::everything();
  }
  return Interval::everything();
}

bool eval_intervals(const Function& fn, const std::vector<Interval>& inputs, IntervalEval& out) {
  if (!interval_evaluable(fn)) return false;
  eval_intervals_straight(fn, inputs, out);
  return true;
}

void eval_intervals_straight(const Function& fn, const std::vector<Interval>& inputs, IntervalEval& out) {
  out.values.assign(fn.next_value, Interval::everything());
  out.choices.assign(fn.next_value, Choice::Both);
  out.outputs.clear();
  for (const Inst* in : fn.entry()->insts) {
    if (in->op == Op::Ret) {
      for (const Inst* a : in->args) out.outputs.push_back(out.values[a->id]);
      break;
    }
    out.values[in->id] = in->op == Op::Param && static_cast<size_t>(in->aux) < inputs.size()
                             ? inputs[static_cast<size_t>(in->aux)]
                             : interval_of(*in, out.values);
    out.choices[in->id] = choice_of(*in, out.values);
  }
}

}  // namespace fscript::ir
