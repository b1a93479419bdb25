// Interval evaluation over one block, and the choice record that tape simplification reads.
#include "ir/interval_eval.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "ir/eval.h"

namespace fscript::ir {

using math::Interval;

// Which operand a min / max (a, b) or select (a = condition, b, c) takes over the whole region.
Choice choice_of(Op op, const Interval& a, const Interval& b, const Interval& c) {
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
    case Op::Param:
    case Op::Phi:
    case Op::GLoad:
    case Op::GStore:
    case Op::ANew:
    case Op::ALoad:
    case Op::AStore:
    case Op::ALen:
    case Op::Call:
    case Op::Tick:
    case Op::Jump:
    case Op::Branch:
    case Op::Ret: return Interval::everything();
  }
  return Interval::everything();
}

const Interval kNone = Interval::everything();

}  // namespace

Interval interval_rule(Op op, bool square, float imm, const Interval& a, const Interval& b, const Interval& c) {
  return apply(op, square, imm, a, b, c);
}

Interval interval_of(const Inst& in, const std::vector<Interval>& v) {
  auto arg = [&](size_t i) -> const Interval& { return i < in.args.size() ? v[in.args[i]->id] : kNone; };
  return apply(in.op, in.op == Op::Mul && in.args[0] == in.args[1], in.imm, arg(0), arg(1), arg(2));
}

IntervalTape::IntervalTape(const Function& fn) : values_(fn.next_value), params_(fn.num_params) {
  steps_.reserve(fn.entry()->insts.size());
  sources_.reserve(fn.entry()->insts.size());
  for (const Inst* in : fn.entry()->insts) {
    if (in->op == Op::Ret) {
      for (const Inst* a : in->args) outputs_.push_back(a->id);
      break;
    }
    Step s{in->op,
           in->op == Op::Mul && in->args[0] == in->args[1],
           static_cast<uint8_t>(std::min<size_t>(in->args.size(), 3)),
           in->id,
           0,
           0,
           0,
           in->imm};
    uint32_t* slot[] = {&s.a, &s.b, &s.c};
    for (size_t k = 0; k < s.arity; ++k) *slot[k] = in->args[k]->id;
    if (in->op == Op::Param) s.a = static_cast<uint32_t>(in->aux);
    steps_.push_back(s);
    sources_.push_back({in->line, in->col});
    simd_only_ = simd_only_ && simd_interval_op(in->op);
    dense_ = dense_ && in->id == steps_.size() - 1;
  }
}

size_t first_nan_step(const IntervalTape& t, const float* params) {
  std::vector<float> v(t.num_values(), 0.0f);
  const auto& steps = t.steps();
  for (size_t i = 0; i < steps.size(); ++i) {
    const IntervalTape::Step& s = steps[i];
    float a[3] = {v[s.a], v[s.b], v[s.c]}, out = 0;
    bool operand_nan = false;
    for (size_t k = 0; k < s.arity; ++k) operand_nan |= std::isnan(a[k]);
    if (s.op == Op::Const) out = s.imm;
    else if (s.op == Op::Param) out = params[s.a];
    else if (!eval_pure(s.op, a, out)) return steps.size();
    v[s.dst] = out;
    if (std::isnan(out) && !operand_nan) return i;
  }
  return steps.size();
}

IntervalTape IntervalTape::simplified(const IntervalEval& ev, size_t* collapsed) const {
  return simplified(ev.choices.data(), 1, collapsed);
}

namespace {

bool chooses(Op op) { return op == Op::Min || op == Op::Max || op == Op::Select; }

// The operand a decided min / max / select takes.
uint32_t side_of(const IntervalTape::Step& s, Choice c) {
  return s.op == Op::Select ? (c == Choice::Left ? s.b : s.c) : (c == Choice::Left ? s.a : s.b);
}

}  // namespace

// The steps whose value `needed` says is needed, in order (for emit's forward pass).
template <typename Needed>
auto IntervalTape::every_step(Needed needed) const {
  return [this, needed](auto&& f) {
    for (size_t i = 0; i < steps_.size(); ++i)
      if (needed(steps_[i].dst)) f(i);
  };
}

// The same where step i defines value i (dense_): the lane's bit of the `needed` masks read
// sixteen at a time, so the steps a region drops (most of them) cost next to nothing.
struct IntervalTape::LaneSteps {
  const uint16_t* need;
  uint16_t bit;
  size_t count;
  template <typename F>
  void operator()(F&& f) const {
#if defined(__SSE2__)
    const __m128i b = _mm_set1_epi16(static_cast<short>(bit)), zero = _mm_setzero_si128();
    for (size_t base = 0; base < count; base += 16) {
      __m128i lo = _mm_loadu_si128(reinterpret_cast<const __m128i*>(need + base));
      __m128i hi = _mm_loadu_si128(reinterpret_cast<const __m128i*>(need + base + 8));
      lo = _mm_cmpeq_epi16(_mm_and_si128(lo, b), zero);
      hi = _mm_cmpeq_epi16(_mm_and_si128(hi, b), zero);
      auto mask = static_cast<uint32_t>(~_mm_movemask_epi8(_mm_packs_epi16(lo, hi)) & 0xFFFF);
      if (base + 16 > count) mask &= (1u << (count - base)) - 1;
      for (; mask; mask &= mask - 1) f(base + static_cast<size_t>(__builtin_ctz(mask)));
    }
#else
    for (size_t i = 0; i < count; ++i)
      if (need[i] & bit) f(i);
#endif
  }
};

// simd_interval_op by op, for the forward pass.
constexpr auto kSimdOp = [] {
  std::array<bool, kNumOps> t{};
  for (int op = 0; op < kNumOps; ++op) t[static_cast<size_t>(op)] = simd_interval_op(static_cast<Op>(op));
  return t;
}();

template <typename Each, typename Stands>
void IntervalTape::emit(const Choice* choices, size_t stride, Each each, Stands stands, IntervalTape& out) const {
  thread_local std::vector<uint32_t> renumber;
  renumber.resize(values_);
  out.params_ = params_;
  out.steps_.resize(steps_.size());  // written in place, then cut to its length
  Step* next = out.steps_.data();
  uint32_t n = 0;
  bool simd = true;
  each([&](size_t i) {
    const Step& s = steps_[i];
    if (stands(s.dst)) {
      renumber[s.dst] = renumber[side_of(s, choices[size_t(s.dst) * stride])];
      return;
    }
    Step c = s;
    c.dst = renumber[s.dst] = n++;
    if (s.op != Op::Param) {  // operand slots past the arity hold 0: renumbered harmlessly, never read
      c.a = renumber[s.a];
      c.b = renumber[s.b];
      c.c = renumber[s.c];
    }
    simd = simd && kSimdOp[static_cast<size_t>(s.op)];
    *next++ = c;
  });
  out.steps_.resize(static_cast<size_t>(next - out.steps_.data()));
  out.simd_only_ = simd;
  out.dense_ = true;
  out.values_ = n;
  out.sources_.clear();
  if (!sources_.empty() && keeping_sources()) {
    out.sources_.reserve(out.steps_.size());
    each([&](size_t i) {
      if (!stands(steps_[i].dst)) out.sources_.push_back(sources_[i]);
    });
  }
  out.outputs_.clear();
  for (uint32_t o : outputs_) out.outputs_.push_back(renumber[o]);
}

namespace {
std::atomic<int> source_keepers{0};
}  // namespace

bool keeping_sources() { return source_keepers.load(std::memory_order_relaxed) > 0; }
KeepSources::KeepSources() { source_keepers.fetch_add(1); }
KeepSources::~KeepSources() { source_keepers.fetch_sub(1); }

IntervalTape IntervalTape::simplified(const Choice* choices, size_t stride, size_t* collapsed) const {
  thread_local std::vector<uint8_t> live;  // bit 0: needed; bit 1: a decided choice, standing for its side
  live.assign(values_, 0);
  // Backward: what the outputs reach, a decided min / max / select passing through to its side.
  for (uint32_t o : outputs_) live[o] = 1;
  size_t decided = 0;
  for (auto it = steps_.rbegin(); it != steps_.rend(); ++it) {
    const Step& s = *it;
    if (!live[s.dst]) continue;
    Choice c = chooses(s.op) ? choices[size_t(s.dst) * stride] : Choice::Both;
    if (c != Choice::Both) {
      live[s.dst] = 3;
      live[side_of(s, c)] |= 1;
      ++decided;
      continue;
    }
    if (s.op == Op::Param) continue;
    live[s.a] |= s.arity > 0;
    live[s.b] |= s.arity > 1;
    live[s.c] |= s.arity > 2;
  }
  if (collapsed) *collapsed = decided;
  const uint8_t* l = live.data();
  IntervalTape out;
  emit(
      choices, stride, every_step([l](uint32_t v) { return l[v] != 0; }), [l](uint32_t v) { return (l[v] & 2) != 0; },
      out);
  return out;
}

// The backward pass of every lane at once, a bit per lane.
void IntervalTape::lane_masks(IntervalBatchEval& ev) const {
  ev.needed.assign(values_ + kIntervalLanes, 0);  // padded: LaneSteps reads 16 at a time
  ev.stands.assign(values_, 0);
  uint16_t* need = ev.needed.data();
  for (uint32_t o : outputs_) need[o] = 0xFFFF;
  for (auto it = steps_.rbegin(); it != steps_.rend(); ++it) {
    const Step& s = *it;
    uint16_t m = need[s.dst];
    if (!m || s.op == Op::Param) continue;
    uint16_t left = 0, right = 0;
    if (chooses(s.op)) {
      const Choice* c = ev.choices.data() + size_t(s.dst) * kIntervalLanes;
#if defined(__SSE2__)  // the lanes' choices compared at once (the loop below is not vectorised)
      static_assert(kIntervalLanes == 16 && sizeof(Choice) == 1, "one SSE register of choices");
      const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(c));
      left = static_cast<uint16_t>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_set1_epi8(char(Choice::Left)))));
      right = static_cast<uint16_t>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_set1_epi8(char(Choice::Right)))));
#else
      for (size_t k = 0; k < kIntervalLanes; ++k) {
        left |= static_cast<uint16_t>((c[k] == Choice::Left) << k);
        right |= static_cast<uint16_t>((c[k] == Choice::Right) << k);
      }
#endif
      left &= m, right &= m;
      ev.stands[s.dst] = left | right;
    }
    uint16_t both = m & ~(left | right);
    if (s.op == Op::Select) {
      need[s.a] |= both;
      need[s.b] |= both | left;
      need[s.c] |= both | right;
      continue;
    }
    uint16_t to_a = both | (chooses(s.op) ? left : 0), to_b = both | (chooses(s.op) ? right : 0);
    if (s.arity > 0) need[s.a] |= to_a;
    if (s.arity > 1) need[s.b] |= to_b;
    if (s.arity > 2) need[s.c] |= both;
  }
  ev.masks = true;
}

IntervalTape IntervalTape::simplified(IntervalBatchEval& ev, size_t lane) const {
  IntervalTape out;
  simplified(ev, lane, out);
  return out;
}

void IntervalTape::simplified(IntervalBatchEval& ev, size_t lane, IntervalTape& out) const {
  if (!ev.masks) lane_masks(ev);
  uint16_t bit = static_cast<uint16_t>(1u << lane);
  const uint16_t *need = ev.needed.data(), *stand = ev.stands.data();
  auto stands = [stand, bit](uint32_t v) { return (stand[v] & bit) != 0; };
  if (dense_) return emit(ev.choices.data() + lane, kIntervalLanes, LaneSteps{need, bit, steps_.size()}, stands, out);
  emit(ev.choices.data() + lane, kIntervalLanes, every_step([need, bit](uint32_t v) { return (need[v] & bit) != 0; }),
       stands, out);
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
    if (s.op == Op::Min || s.op == Op::Max || s.op == Op::Select)
      out.choices[s.dst] = choice_of(s.op, v[s.a], v[s.b], v[s.c]);
  }
  out.outputs.clear();
  for (uint32_t o : outputs_) out.outputs.push_back(v[o]);
}

size_t IntervalTape::operations() const {
  return static_cast<size_t>(std::count_if(steps_.begin(), steps_.end(),
                                           [](const Step& s) { return s.op != Op::Param && s.op != Op::Const; }));
}

bool eval_intervals(const Function& fn, const std::vector<Interval>& inputs, IntervalEval& out) {
  if (!interval_evaluable(fn)) return false;
  IntervalTape(fn).eval(inputs, out);
  return true;
}

}  // namespace fscript::ir
