// VM executor. One dispatch per instruction per chunk of lanes; the lane loops are plain C++
// that the compiler vectorises (this file is built with -O3). Lanes diverge at branches: each
// block runs for the lanes waiting at it, lowest block first, with masked register writes, so
// every lane computes exactly what a scalar run of the program would.
#include "backends/vm/vm_exec.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "backends/jit_support.h"
#include "backends/lane_arrays.h"
#include "backends/runtime_errors.h"
#include "runtime/math/batch_isa.h"
#include "runtime/math/math.h"
#include "runtime/support/cancel.h"

#ifndef FS_ISA
#error "vm_exec.cpp is compiled once per ISA with FS_ISA set (see backends/CMakeLists.txt)"
#endif

namespace fscript::vm::FS_ISA {
namespace {

using backends::Budgets;
using backends::RuntimeError;
using ir::Op;
namespace errors = backends::errors;
using Mask = uint32_t;  // all ones: the lane is present

// Per-lane budgets used so far in one evaluation (arrays live in the chunk's LaneArrays).
struct LaneEnv {
  uint64_t ticks = 0;
  uint32_t depth = 0;
  void reset() {
    ticks = 0;
    depth = 0;
  }
};

// A function activation over `lanes` lanes.
struct Frame {
  const VmFunction* f;
  float* regs;       // register r of lane i is regs[r * stride + i]
  uint32_t lanes;    // lanes present in this frame (the chunk's points, or 1)
  uint32_t stride;   // K for the batch frame, 1 for a one-lane call frame
  LaneEnv** env;     // env[i]: lane i's state
  float* gmem;       // global g of lane i is gmem[g * gstride + i]
  uint32_t gstride;
  uint32_t lane0;    // the chunk lane of this frame's lane 0 (its arrays' lane)
};

// Batch frames keep every register as kChunkLanes lanes, 64-byte aligned; the lane loops below run
// the chunk's lanes rounded up to whole vectors (vector_lanes), so the vector code needs no
// peeling or remainder.
constexpr uint32_t K = kChunkLanes;
// Loop iterations a chunk's lanes may make together before the chunk runs again point by point
// (a lane-by-lane iteration costs about 7 times a packed one, so only loops this long pay it).
constexpr uint64_t kLaneByLaneAfter = uint64_t{1} << 16;
static_assert(K % 16 == 0, "whole AVX-512 vectors per register");

// The lanes a batch frame's loops run: the chunk's, rounded up to whole AVX-512 vectors. A
// mesher's batches are often a few hundred points (a block's crossings), and running all K lanes
// of the registers for them was up to twice the work (the lanes past the chunk compute garbage that
// is never read, as before).
inline uint32_t vector_lanes(uint32_t lanes) { return std::min<uint32_t>(K, (lanes + 15) / 16 * 16); }

// The lanes a frame's loops and masks cover: one in a one-lane frame, else its lanes in whole vectors.
inline uint32_t present_lanes(uint32_t stride, uint32_t lanes) { return stride == 1 ? 1 : vector_lanes(lanes); }

inline float* reg(float* R, uint32_t r) { return static_cast<float*>(__builtin_assume_aligned(R + size_t(r) * K, 64)); }

template <class F>
inline void binary(const VInst& v, float* R, const Mask* m, bool full, uint32_t n, F f) {
  if (n % 16 != 0) __builtin_unreachable();
  float* __restrict d = reg(R, v.dst);
  const float* __restrict a = (v.kinds & 1) ? nullptr : reg(R, v.a);
  const float* __restrict b = (v.kinds & 2) ? nullptr : reg(R, v.b);
  const float ia = v.imm_a, ib = v.imm_b;
  switch (v.kinds) {
    case 0:
      if (full)
        for (uint32_t i = 0; i < n; ++i) d[i] = f(a[i], b[i]);
      else
        for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? f(a[i], b[i]) : d[i];
      break;
    case 1:
      if (full)
        for (uint32_t i = 0; i < n; ++i) d[i] = f(ia, b[i]);
      else
        for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? f(ia, b[i]) : d[i];
      break;
    case 2:
      if (full)
        for (uint32_t i = 0; i < n; ++i) d[i] = f(a[i], ib);
      else
        for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? f(a[i], ib) : d[i];
      break;
    default:
      for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? f(ia, ib) : d[i];
      break;
  }
}

template <class F>
inline void unary(const VInst& v, float* R, const Mask* m, bool full, uint32_t n, F f) {
  if (n % 16 != 0) __builtin_unreachable();
  float* __restrict d = reg(R, v.dst);
  const float* __restrict a = reg(R, v.a);
  if (full)
    for (uint32_t i = 0; i < n; ++i) d[i] = f(a[i]);
  else
    for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? f(a[i]) : d[i];
}

template <class F>
inline void ternary(const VInst& v, float* R, const Mask* m, bool full, uint32_t n, F f) {
  if (n % 16 != 0) __builtin_unreachable();
  float* __restrict d = reg(R, v.dst);
  const float* a = reg(R, v.a);
  const float* b = reg(R, v.b);
  const float* c = reg(R, v.c);
  if (full)
    for (uint32_t i = 0; i < n; ++i) d[i] = f(a[i], b[i], c[i]);
  else
    for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? f(a[i], b[i], c[i]) : d[i];
}

// A transcendental with a SIMD batch twin: compute every lane, keep the present ones.
inline void batched(const VInst& v, float* R, const Mask* m, bool full, uint32_t n,
                    void (*fn)(const float*, float*, size_t)) {
  float* d = reg(R, v.dst);
  const float* a = reg(R, v.a);
  if (full) {
    fn(a, d, n);
    return;
  }
  alignas(64) float tmp[K];
  fn(a, tmp, n);
  for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? tmp[i] : d[i];
}

// sin and cos: as batched, or one of a pair (bytecode.h): the first computes both, the second
// copies its result from the pair's register. Both run under the block's one mask.
inline void trig(const VInst& v, float* R, const Mask* m, bool full, uint32_t n,
                 void (*fn)(const float*, float*, size_t)) {
  if (v.c == kNoReg) return batched(v, R, m, full, n, fn);
  float* d = reg(R, v.dst);
  float* o = reg(R, v.c);
  if (v.aux == kTrigSecond) {
    if (full) std::copy_n(o, n, d);
    else
      for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? o[i] : d[i];
    return;
  }
  alignas(64) float tmp[K];
  float* mine = full ? d : tmp;  // the other's lanes need no mask: only the second reads them
  bool sin = v.op == Op::Sin;
  fscript::math::FS_ISA::sincos_batch(reg(R, v.a), sin ? mine : o, sin ? o : mine, n);
  if (!full)
    for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? tmp[i] : d[i];
}

// The same for a binary one; an immediate operand is broadcast into a scratch lane vector.
inline void batched2(const VInst& v, float* R, const Mask* m, bool full, uint32_t n,
                     void (*fn)(const float*, const float*, float*, size_t)) {
  alignas(64) float ia[K], ib[K], tmp[K];
  const float* a = (v.kinds & 1) ? ia : reg(R, v.a);
  const float* b = (v.kinds & 2) ? ib : reg(R, v.b);
  if (v.kinds & 1) std::fill_n(ia, K, v.imm_a);
  if (v.kinds & 2) std::fill_n(ib, K, v.imm_b);
  float* d = reg(R, v.dst);
  fn(a, b, full ? d : tmp, n);
  if (!full)
    for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? tmp[i] : d[i];
}

// The same for a ternary one (its operands are always registers).
inline void batched3(const VInst& v, float* R, const Mask* m, bool full, uint32_t n,
                     void (*fn)(const float*, const float*, const float*, float*, size_t)) {
  alignas(64) float tmp[K];
  float* d = reg(R, v.dst);
  fn(reg(R, v.a), reg(R, v.b), reg(R, v.c), full ? d : tmp, n);
  if (!full)
    for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? tmp[i] : d[i];
}

#include "backends/vm/vm_fused.inc"

// How each row of ir/math_ops.def runs, by its kind and arity: on the batch path (FS_VM_*) and on
// the one-point path (FS_ONE_*), where transcendentals go through the same batch functions (n = 1)
// so a point gives the same bits either way.
#define FS_VM_Lane1(N, FN) \
  case Op::N: unary(v, R, m, full, n, [](float a) { return M::FN(a); }); return true;
#define FS_VM_Lane2(N, FN) \
  case Op::N: binary(v, R, m, full, n, [](float a, float b) { return M::FN(a, b); }); return true;
#define FS_VM_Lane3(N, FN) \
  case Op::N: ternary(v, R, m, full, n, [](float a, float b, float c) { return M::FN(a, b, c); }); return true;
#define FS_VM_Batch1(N, FN) \
  case Op::N: batched(v, R, m, full, n, M::FS_ISA::FN##_batch); return true;
#define FS_VM_Batch2(N, FN) \
  case Op::N: batched2(v, R, m, full, n, M::FS_ISA::FN##_batch); return true;
#define FS_VM_Batch3(N, FN) \
  case Op::N: batched3(v, R, m, full, n, M::FS_ISA::FN##_batch); return true;
#define FS_VM_Trig1(N, FN) \
  case Op::N: trig(v, R, m, full, n, M::FS_ISA::FN##_batch); return true;
#define FS_ONE_Lane1(N, FN) \
  case Op::N: *d = M::FN(a); return true;
#define FS_ONE_Lane2(N, FN) \
  case Op::N: *d = M::FN(a, b); return true;
#define FS_ONE_Lane3(N, FN) \
  case Op::N: *d = M::FN(a, b, R[v.c]); return true;
#define FS_ONE_Batch1(N, FN) \
  case Op::N: I::FN##_batch(&a, d, 1); return true;
#define FS_ONE_Batch2(N, FN) \
  case Op::N: I::FN##_batch(&a, &b, d, 1); return true;
#define FS_ONE_Batch3(N, FN)         \
  case Op::N: {                      \
    const float c = R[v.c];          \
    I::FN##_batch(&a, &b, &c, d, 1); \
    return true;                     \
  }
#define FS_ONE_Trig1(N, FN)                                                                    \
  case Op::N:                                                                                  \
    if (v.c == kNoReg) I::FN##_batch(&a, d, 1);                                                \
    else if (v.aux == kTrigSecond) *d = R[v.c];                                                \
    else I::sincos_batch(&a, v.op == Op::Sin ? d : &R[v.c], v.op == Op::Sin ? &R[v.c] : d, 1); \
    return true;

// A 64-byte aligned, growable scratch buffer (one per thread).
struct AlignedFloats {
  float* p = nullptr;
  size_t n = 0;
  ~AlignedFloats() { std::free(p); }
  float* get(size_t want) {
    if (want > n) {
      std::free(p);
      n = (want + 15) / 16 * 16;
      p = static_cast<float*>(std::aligned_alloc(64, n * sizeof(float)));
      std::fill_n(p, n, 0.0f);
    }
    return p;
  }
};

class Executor {
 public:
  Executor(const VmProgram& p, const Budgets& b, size_t row_length)
      : p_(p), budgets_(b), row_length_(row_length), arrays_(thread_arrays()) {
    if (!p.needs_lane_state) return;
    // Array slots: the module's global arrays, then each function's own (as the JITs number them).
    std::vector<std::string> names = p.global_array_names;
    for (const VmFunction& f : p.functions) {
      slot_base_.push_back(static_cast<uint32_t>(names.size()));
      names.insert(names.end(), f.array_names.begin(), f.array_names.end());
    }
    arrays_.init(kChunkLanes, b.max_array_elements, names);
  }

  bool run_chunk(const float* const* in, float* const* out, size_t base, uint32_t L, RuntimeError& err);
  bool out_of_stack() const { return out_of_stack_; }
  // The chunk stopped because a loop ran long (kLaneByLaneAfter iterations of its lanes together).
  bool long_loop() const { return long_loop_; }

 private:
  bool run(Frame& fr, std::vector<Mask>& start_mask, float* const* out, size_t base, float* result, RuntimeError& err);
  bool exec(Frame& fr, const VInst& v, const Mask* m, bool full, RuntimeError& err);
  bool exec_one(Frame& fr, const VInst& v, RuntimeError& err);
  bool lane_op(Frame& fr, const VInst& v, uint32_t i, RuntimeError& err);
  bool call(Frame& fr, const VInst& v, uint32_t i, RuntimeError& err);
  bool array_op(Frame& fr, const VInst& v, uint32_t i, RuntimeError& err);
  void edge_moves(Frame& fr, const Edge& e, const Mask* m);
  bool out_of_stack_ = false;
  bool long_loop_ = false;
  uint64_t chunk_ticks_ = 0;  // loop iterations the chunk's lanes made together (batch frames only)
  static void init_frame(Frame& fr) {
    const VmFunction& f = *fr.f;
    uint32_t n = present_lanes(fr.stride, fr.lanes);
    for (auto [r, v] : f.consts) std::fill_n(fr.regs + size_t(r) * fr.stride, n, v);
  }
  // Parameter p's lanes for points [base, base + L): the points' own values, or with row parameters
  // the run of x values below them and one value per row from them on.
  void load_param(uint32_t p, const float* in, size_t base, uint32_t L, float* lanes) const {
    if (!p_.row_params_from) {
      std::memcpy(lanes, in + base, L * sizeof(float));
      return;
    }
    size_t row = base / row_length_, at = base % row_length_;
    for (uint32_t l = 0; l < L;) {
      uint32_t run = static_cast<uint32_t>(std::min<size_t>(L - l, row_length_ - at));
      if (p < p_.row_params_from) std::memcpy(lanes + l, in + at, run * sizeof(float));
      else std::fill_n(lanes + l, run, in[row]);
      l += run, at = 0, ++row;
    }
  }
  uint32_t slot_of(const Frame& fr, const VInst& v) const {
    return v.array_global ? v.aux : slot_base_[static_cast<size_t>(fr.f - p_.functions.data())] + v.aux;
  }

  const VmProgram& p_;
  const Budgets& budgets_;
  size_t row_length_;                 // points per row, for a kernel with row parameters
  std::vector<uint32_t> slot_base_;  // per function: its first array slot
  backends::LaneArrays& arrays_;      // the thread's, so storage is reused from batch to batch

  static backends::LaneArrays& thread_arrays() {
    thread_local backends::LaneArrays arrays;
    return arrays;
  }
};

bool Executor::run_chunk(const float* const* in, float* const* out, size_t base, uint32_t L, RuntimeError& err) {
  chunk_ticks_ = 0;
  long_loop_ = false;
  thread_local std::vector<LaneEnv> envs;
  thread_local std::vector<LaneEnv*> env_ptrs;
  thread_local std::vector<float> gmem;
  thread_local AlignedFloats regs;
  thread_local std::vector<Mask> start;
  const VmFunction& k = p_.functions[p_.kernel];
  if (p_.needs_lane_state) {
    envs.resize(K);
    env_ptrs.resize(K);
    for (uint32_t i = 0; i < L; ++i) {
      envs[i].reset();
      env_ptrs[i] = &envs[i];
    }
    arrays_.reset();
    gmem.assign(size_t(p_.num_globals) * L, __builtin_nanf(""));
  }
  // One point (eval) runs as a one-lane frame with scalar code; a batch uses full K-lane registers.
  uint32_t S = L == 1 ? 1 : K;
  Frame fr{&k, regs.get(size_t(std::max<uint32_t>(k.num_regs, 1)) * S), L, S, env_ptrs.data(), gmem.data(), L, 0};
  init_frame(fr);
  // The lanes past the last point repeat it: what an earlier chunk left there (any value: huge
  // ones sent sin and cos to libm's slow reduction) would cost more than a real point.
  for (uint32_t p = 0; p < k.num_params; ++p)
    if (k.param_regs[p] != kNoReg) {
      float* lanes = fr.regs + size_t(k.param_regs[p]) * S;
      load_param(p, in[p], base, L, lanes);
      std::fill(lanes + L, lanes + present_lanes(S, L), lanes[L - 1]);
    }
  start.assign(present_lanes(S, L), 0);
  std::fill_n(start.begin(), L, ~Mask{0});
  if (k.blocks.size() == 1) {  // straight-line kernel: one pass over the code, all lanes present
    const VBlock& vb = k.blocks[0];
    for (uint32_t i = vb.begin; i < vb.end; ++i)
      if (!(S == 1 ? exec_one(fr, k.code[i], err) : exec(fr, k.code[i], start.data(), true, err))) return false;
    for (size_t o = 0; o < vb.results.size(); ++o)
      std::memcpy(out[o] + base, fr.regs + size_t(vb.results[o]) * S, L * sizeof(float));
    return true;
  }
  return run(fr, start, out, base, nullptr, err);
}

void Executor::edge_moves(Frame& fr, const Edge& e, const Mask* m) {
  if (e.moves.empty()) return;
  uint32_t S = fr.stride, n = present_lanes(S, fr.lanes);
  thread_local std::vector<float> tmp;
  tmp.resize(e.moves.size() * n);
  for (size_t k = 0; k < e.moves.size(); ++k)
    std::memcpy(tmp.data() + k * n, fr.regs + size_t(e.moves[k].src) * S, n * sizeof(float));
  for (size_t k = 0; k < e.moves.size(); ++k) {
    float* d = fr.regs + size_t(e.moves[k].dst) * S;
    const float* s = tmp.data() + k * n;
    for (uint32_t i = 0; i < n; ++i) d[i] = m[i] ? s[i] : d[i];
  }
}

// Runs the frame's function until every present lane returns. Kernel frames write `out`;
// a one-lane call frame writes `*result`.
bool Executor::run(Frame& fr, std::vector<Mask>& start_mask, float* const* out, size_t base, float* result,
                   RuntimeError& err) {
  const VmFunction& f = *fr.f;
  uint32_t S = fr.stride;
  // Masks cover the chunk's lanes rounded up to whole vectors, as the ops run them (slots past the
  // chunk stay 0): a short batch in a K-lane frame costs its own lanes, not K.
  uint32_t L = present_lanes(S, fr.lanes);
  size_t nb = f.blocks.size();
  std::vector<Mask> pending(nb * L, 0);
  std::vector<uint32_t> count(nb, 0);
  std::copy_n(start_mask.begin(), L, pending.begin());
  count[0] = static_cast<uint32_t>(std::count(start_mask.begin(), start_mask.begin() + L, ~Mask{0}));
  std::vector<Mask> m(L), mt(L), mf(L);
  auto send = [&](const Edge& e, const Mask* mask, uint32_t n) {
    if (n == 0) return;
    edge_moves(fr, e, mask);
    Mask* dst = pending.data() + size_t(e.block) * L;
    for (uint32_t i = 0; i < L; ++i) dst[i] |= mask[i];
    count[e.block] += n;
  };
  for (size_t b = 0; b < nb;) {
    if (count[b] == 0) {
      ++b;
      continue;
    }
    std::copy_n(pending.begin() + static_cast<long>(b * L), L, m.begin());
    std::fill_n(pending.begin() + static_cast<long>(b * L), L, 0);
    bool full = count[b] == fr.lanes;
    uint32_t present = count[b];
    count[b] = 0;
    const VBlock& vb = f.blocks[b];
    if (fr.stride == 1) {
      for (uint32_t k = vb.begin; k < vb.end; ++k)
        if (!exec_one(fr, f.code[k], err)) return false;
    } else {
      for (uint32_t k = vb.begin; k < vb.end; ++k)
        if (!exec(fr, f.code[k], m.data(), full, err)) return false;
    }
    size_t next = b + 1;
    switch (vb.term) {
      case Op::Jump:
        send(vb.edges[0], m.data(), present);
        next = std::min<size_t>(next, vb.edges[0].block);
        break;
      case Op::Branch: {
        const float* c = fr.regs + size_t(vb.cond) * S;
        uint32_t nt = 0;
        for (uint32_t i = 0; i < L; ++i) {
          bool t = math::truthy(c[i]);
          mt[i] = m[i] & (t ? ~Mask{0} : 0);
          mf[i] = m[i] & (t ? 0 : ~Mask{0});
          nt += mt[i] ? 1 : 0;
        }
        send(vb.edges[0], mt.data(), nt);
        send(vb.edges[1], mf.data(), present - nt);
        next = std::min<size_t>({next, vb.edges[0].block, vb.edges[1].block});
        break;
      }
      case Op::Ret:
        for (uint32_t i = 0; i < fr.lanes; ++i) {
          if (!m[i]) continue;
          for (size_t o = 0; o < vb.results.size(); ++o) {
            float v = fr.regs[size_t(vb.results[o]) * S + i];
            if (result) *result = v;
            else out[o][base + i] = v;
          }
        }
        break;
      default: break;
    }
    b = next;
  }
  return true;
}

bool Executor::exec(Frame& fr, const VInst& v, const Mask* m, bool full, RuntimeError& err) {
  float* R = fr.regs;
  uint32_t L = fr.lanes;
  const uint32_t n = vector_lanes(L);
  namespace M = fscript::math;
  if (v.fused) return run_fused(v, R, K, n), true;  // straight-line functions: every lane present
  switch (v.op) {
#define FS_MATH(N, FN, A, HOW) FS_VM_##HOW##A(N, FN)
#include "ir/math_ops.def"
    case Op::GLoad:
    case Op::GStore:
    case Op::ANew:
    case Op::ALoad:
    case Op::AStore:
    case Op::ALen:
    case Op::Call:
    case Op::Tick:
      if (v.op == Op::Tick && ++chunk_ticks_ > kLaneByLaneAfter) return long_loop_ = true, false;
      for (uint32_t i = 0; i < L; ++i)
        if (m[i] && !lane_op(fr, v, i, err)) return false;
      return true;
    case Op::Param: return true;  // filled when the frame starts
    case Op::Const:
    case Op::Phi:
    case Op::Jump:
    case Op::Branch:
    case Op::Ret: return true;  // never emitted as instructions
  }
  return true;
}

// One lane (the one-point path and recursive calls): plain scalar code, no masks. Transcendentals
// go through the same batch functions (n = 1), so a point gives the same bits either way.
bool Executor::exec_one(Frame& fr, const VInst& v, RuntimeError& err) {
  float* R = fr.regs;
  namespace M = fscript::math;
  namespace I = fscript::math::FS_ISA;
  const float a = (v.kinds & 1) ? v.imm_a : (v.a != kNoReg ? R[v.a] : 0.0f);
  const float b = (v.kinds & 2) ? v.imm_b : (v.b != kNoReg ? R[v.b] : 0.0f);
  float* d = v.dst != kNoReg ? &R[v.dst] : nullptr;
  if (v.fused) return run_fused(v, R, 1, 1), true;
  switch (v.op) {
#define FS_MATH(N, FN, A, HOW) FS_ONE_##HOW##A(N, FN)
#include "ir/math_ops.def"
    case Op::GLoad:
    case Op::GStore:
    case Op::ANew:
    case Op::ALoad:
    case Op::AStore:
    case Op::ALen:
    case Op::Call:
    case Op::Tick: return lane_op(fr, v, 0, err);
    case Op::Param:
    case Op::Const:
    case Op::Phi:
    case Op::Jump:
    case Op::Branch:
    case Op::Ret: return true;
  }
  return true;
}

bool Executor::lane_op(Frame& fr, const VInst& v, uint32_t i, RuntimeError& err) {
  float* R = fr.regs;
  uint32_t S = fr.stride;
  auto reg = [&](uint32_t r) -> float& { return R[size_t(r) * S + i]; };
  LaneEnv& env = *fr.env[i];
  switch (v.op) {
    case Op::GLoad: reg(v.dst) = fr.gmem[size_t(v.aux) * fr.gstride + i]; return true;
    case Op::GStore: fr.gmem[size_t(v.aux) * fr.gstride + i] = reg(v.a); return true;
    case Op::Tick:
      if (++env.ticks > budgets_.max_loop_iterations) {
        err = {errors::loop_budget(budgets_.max_loop_iterations), v.line, v.col};
        return false;
      }
      if ((env.ticks & 1023) == 0 && support::run_cancelled()) {  // every 1,024: a call per lane costs
        err = {errors::cancelled(), v.line, v.col};
        return false;
      }
      return true;
    case Op::Call: return call(fr, v, i, err);
    default: break;
  }
  return array_op(fr, v, i, err);
}

bool Executor::array_op(Frame& fr, const VInst& v, uint32_t i, RuntimeError& err) {
  float* R = fr.regs;
  auto reg = [&](uint32_t r) -> float& { return R[size_t(r) * fr.stride + i]; };
  uint32_t slot = slot_of(fr, v), lane = fr.lane0 + i;
  bool ok;
  if (v.op == Op::ANew) {
    ok = arrays_.create(slot, lane, reg(v.a));
  } else if (v.op == Op::ALen) {
    ok = arrays_.length(slot, lane, reg(v.dst));
  } else {  // ALoad, AStore
    float* e = arrays_.element(slot, lane, reg(v.a));
    ok = e != nullptr;
    if (ok && v.op == Op::ALoad) reg(v.dst) = *e;
    if (ok && v.op == Op::AStore) *e = reg(v.b);
  }
  if (!ok) err = {arrays_.message, v.line, v.col};
  return ok;
}

// A user call for lane i runs the callee alone (one lane): recursion never diverges a batch.
// Only calls of recursive functions count against the depth budget (others are bounded by the
// program text, and the optimiser inlines them).
bool Executor::call(Frame& fr, const VInst& v, uint32_t i, RuntimeError& err) {
  LaneEnv& env = *fr.env[i];
  const VmFunction& callee = p_.functions[v.c];
  if (callee.recursive && env.depth + 1 > budgets_.max_call_depth) {
    err = {errors::call_depth(budgets_.max_call_depth), v.line, v.col};
    return false;
  }
  if (callee.recursive && support::run_cancelled()) {  // recursion can take as long as a loop
    err = {errors::cancelled(), v.line, v.col};
    return false;
  }
  if (callee.recursive && reinterpret_cast<uintptr_t>(__builtin_frame_address(0)) < backends::stack_limit()) {
    out_of_stack_ = true;
    err = {errors::recursion_stack(budgets_.max_call_depth), v.line, v.col};
    return false;
  }
  std::vector<float> regs(std::max<uint32_t>(callee.num_regs, 1));
  Frame sub{&callee, regs.data(), 1, 1, fr.env + i, fr.gmem + i, fr.gstride, fr.lane0 + i};
  init_frame(sub);
  const auto& args = fr.f->lists[v.aux];
  for (size_t k = 0; k < args.size(); ++k)
    if (callee.param_regs[k] != kNoReg) regs[callee.param_regs[k]] = fr.regs[size_t(args[k]) * fr.stride + i];
  uint32_t step = callee.recursive ? 1 : 0;
  env.depth += step;
  std::vector<Mask> one(1, ~Mask{0});
  float result = __builtin_nanf("");
  // The callee's own arrays start unmade in every activation; the caller's come back after.
  uint32_t first = slot_base_.empty() ? 0 : slot_base_[v.c];
  std::vector<int64_t> saved(size_t{callee.num_arrays} * 2);
  arrays_.enter(first, callee.num_arrays, sub.lane0, saved.data());
  bool ok = run(sub, one, nullptr, 0, &result, err);
  arrays_.leave(first, callee.num_arrays, sub.lane0, saved.data());
  env.depth -= step;
  fr.regs[size_t(v.dst) * fr.stride + i] = result;
  return ok;
}

}  // namespace

bool run_batch(const VmProgram& p, const Budgets& budgets, const float* const* inputs, float* const* outputs, size_t n,
               size_t row_length, RuntimeError& err, bool& out_of_stack) {
  Executor ex(p, budgets, row_length);
  size_t chunk = p.functions[p.kernel].blocks.size() == 1 ? kChunkLanes : kBranchyChunkLanes;
  for (size_t base = 0; base < n; base += chunk) {
    uint32_t L = static_cast<uint32_t>(std::min<size_t>(chunk, n - base));
    if (ex.run_chunk(inputs, outputs, base, L, err)) continue;
    // A loop that runs long costs every lane of the chunk each iteration, and a runaway one would
    // take a chunk's points times its budget to fail: run the chunk again one point at a time (the
    // evaluation is a function of the inputs), so a runaway point stops after its own budget.
    if (!ex.long_loop()) return out_of_stack = ex.out_of_stack(), false;
    for (uint32_t i = 0; i < L; ++i)
      if (!ex.run_chunk(inputs, outputs, base + i, 1, err)) return out_of_stack = ex.out_of_stack(), false;
  }
  return true;
}

}  // namespace fscript::vm::FS_ISA
