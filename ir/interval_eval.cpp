// Interval evaluation over one block, and the choice record that tape simplification reads.
#include "ir/interval_eval.h"

#include <algorithm>

namespace fscript::ir {
namespace {

using math::Interval;

// Which operand a min / max (a, b) or select (a = condition, b, c) takes over the whole region.
Choice choice(Op op, const Interval& a, const Interval& b, const Interval& c) {
  (void)c;
  if (op == Op::Select) {
    math::Truth t = math::truth_of(a);
    return t == math::Truth::Always ? Choice::Left : t == math::Truth::Never ? Choice::Right : Choice::Both;
  }
  if (op != Op::Min && op != Op::Max) return Choice::Both;
  // The other side must never be NaN (min/max give NaN if either is), and the sides must not
  // touch, so the side taken is the result bit for bit (no question of the sign of a zero).
  if (a.empty() || b.empty()) return Choice::Both;
  bool a_below = a.hi < b.lo, b_below = b.hi < a.lo;
  bool min = op == Op::Min;
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

namespace {

// The rule of `op` on its operands' intervals (`square`: a Mul of a value by itself).
[[gnu::always_inline]] inline Interval apply(Op op, bool square, float imm, const Interval& a, const Interval& b,
                                             const Interval& c) {
  (void)c;
  if (square) return math::iv::square(a);
  switch (op) {
#define FS_IV_1(N, FN) \
  case Op::N: return math::iv::FN(a);
#define FS_IV_2(N, FN) \
  case Op::N: return math::iv::FN(a, b);
#define FS_IV_3(N, FN) \
  case Op::N: return math::iv::FN(a, b, c);
#define FS_MATH(N, FN, A, HOW) FS_IV_##A(N, FN)
#include "ir/math_ops.def"
#undef FS_IV_1
#undef FS_IV_2
#undef FS_IV_3
    case Op::Const: return Interval::point(imm);
    // Parameters come from the region; memory, calls and control flow are not bounded here.
    case Op::Param: case Op::Phi: case Op::GLoad: case Op::GStore: case Op::ANew: case Op::ALoad:
    case Op::AStore: case Op::ALen: case Op::Call: case Op::Tick: case Op::Jump: case Op::Branch: case Op::Ret:
      return Interval::everything();
  }
  return Interval::everything();
}

const Interval kNone = Interval::everything();

}  // namespace

Interval interval_of(const Inst& in, const std::vector<Interval>& v) {
  auto arg = [&](size_t i) -> const Interval& { return i < in.args.size() ? v[in.args[i]->id] : kNone; };
  return apply(in.op, in.op == Op::Mul && in.args[0] == in.args[1], in.imm, arg(0), arg(1), arg(2));
}

IntervalTape::IntervalTape(const Function& fn) : values_(fn.next_value), params_(fn.num_params) {
  for (const Inst* in : fn.entry()->insts) {
    if (in->op == Op::Ret) {
      for (const Inst* a : in->args) outputs_.push_back(a->id);
      break;
    }
    Step s{in->op, in->op == Op::Mul && in->args[0] == in->args[1], static_cast<uint8_t>(std::min<size_t>(in->args.size(), 3)),
           in->id, 0, 0, 0, in->imm};
    uint32_t* slot[] = {&s.a, &s.b, &s.c};
    for (size_t k = 0; k < s.arity; ++k) *slot[k] = in->args[k]->id;
    if (in->op == Op::Param) s.a = static_cast<uint32_t>(in->aux);
    steps_.push_back(s);
  }
}

IntervalTape IntervalTape::simplified(const IntervalEval& ev, size_t* collapsed) const {
  // What each value stands for in the region: itself, or the side a decided choice takes.
  std::vector<uint32_t> stands(values_);
  size_t decided = 0;
  for (const Step& s : steps_) {
    uint32_t v = s.dst;
    Choice c = ev.choices[s.dst];
    if (c != Choice::Both && (s.op == Op::Min || s.op == Op::Max)) v = stands[c == Choice::Left ? s.a : s.b];
    if (c != Choice::Both && s.op == Op::Select) v = stands[c == Choice::Left ? s.b : s.c];
    decided += v != s.dst;
    stands[s.dst] = v;
  }
  if (collapsed) *collapsed = decided;
  // Live: what the outputs reach through the collapsed choices.
  std::vector<char> live(values_, 0);
  for (uint32_t o : outputs_) live[stands[o]] = 1;
  for (auto it = steps_.rbegin(); it != steps_.rend(); ++it) {
    if (!live[it->dst] || it->op == Op::Param) continue;
    const uint32_t operands[] = {it->a, it->b, it->c};
    for (size_t k = 0; k < it->arity; ++k) live[stands[operands[k]]] = 1;
  }
  // The copy, in the original order, numbered densely.
  IntervalTape out;
  out.params_ = params_;
  std::vector<uint32_t> renumber(values_, 0);
  for (const Step& s : steps_) {
    if (!live[s.dst]) continue;
    Step c = s;
    c.dst = renumber[s.dst] = out.values_++;
    if (s.op != Op::Param) {
      uint32_t* slot[] = {&c.a, &c.b, &c.c};
      for (size_t k = 0; k < s.arity; ++k) *slot[k] = renumber[stands[*slot[k]]];
    }
    out.steps_.push_back(c);
  }
  for (uint32_t o : outputs_) out.outputs_.push_back(renumber[stands[o]]);
  return out;
}

void IntervalTape::eval(const std::vector<Interval>& inputs, IntervalEval& out) const {
  out.values.resize(values_);
  out.choices.assign(values_, Choice::Both);
  Interval* v = out.values.data();
  for (const Step& s : steps_) {
    if (s.op == Op::Param) {
      v[s.dst] = s.a < inputs.size() ? inputs[s.a] : kNone;
      continue;
    }
    v[s.dst] = apply(s.op, s.square, s.imm, v[s.a], v[s.b], v[s.c]);
    if (s.op == Op::Min || s.op == Op::Max || s.op == Op::Select) out.choices[s.dst] = choice(s.op, v[s.a], v[s.b], v[s.c]);
  }
  out.outputs.clear();
  for (uint32_t o : outputs_) out.outputs.push_back(v[o]);
}

bool eval_intervals(const Function& fn, const std::vector<Interval>& inputs, IntervalEval& out) {
  if (!interval_evaluable(fn)) return false;
  IntervalTape(fn).eval(inputs, out);
  return true;
}

}  // namespace fscript::ir
