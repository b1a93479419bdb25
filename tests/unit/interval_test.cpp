// Interval arithmetic is sound: for random boxes, every point result (the scalar definition and
// every backend's batch code, rounding included) lies in the interval the rules give. Per op of the
// table, for the shared benchmarks and examples, and for thousands of random programs.
#include <catch2/catch.hpp>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "backends/vm/vm_backend.h"
#include "backends/vm/vm_points.h"
#include "ir/eval.h"
#include "ir/interval_eval.h"
#include "ir/interval_lanes.h"
#include "ir/tape.h"
#include "engine/render/quadtree.h"
#include "ir/text.h"
#include "runtime/support/files.h"
#include "tests/unit/backend_cases.h"
#include "tests/unit/helpers.h"
#include "tests/support/skip.h"

using namespace fscript;
using math::Interval;

namespace {

const float kInf = test::kInf;
// Ends of boxes: specials, small and large magnitudes, and the extrema of the periodic functions.
const std::vector<float> kEnds = {-kInf,       -1e30f, -1e6f,      -100.0f, -7.25f,      -3.14159274f, -2.0f,
                                  -1.5707964f, -1.0f,  -0.5f,      -1e-30f, 0.0f,        1e-30f,       0.25f,
                                  0.5f,        1.0f,   1.5707964f, 2.0f,    3.14159274f, 4.7123890f,   6.2831855f,
                                  10.0f,       88.0f,  1e6f,       1e30f,   kInf};

struct Box {
  Interval iv;
  std::vector<float> points;  // the ends, points inside, and NaN when the box allows it
};

Box random_box(std::mt19937& rng) {
  std::uniform_int_distribution<size_t> pick(0, kEnds.size() - 1);
  float a = kEnds[pick(rng)], b = kEnds[pick(rng)];
  if (rng() % 3 == 0) b = a;                                                      // a point
  if (rng() % 4 == 0 && std::isfinite(a)) b = a + static_cast<float>(rng() % 1000) * 1e-3f;  // a narrow box
  Box box;
  box.iv = {std::min(a, b), std::max(a, b), rng() % 5 == 0};
  box.points = {box.iv.lo, box.iv.hi};
  std::uniform_real_distribution<double> t(0, 1);
  double lo = std::clamp<double>(box.iv.lo, -3e38, 3e38), hi = std::clamp<double>(box.iv.hi, -3e38, 3e38);
  for (int k = 0; k < 6 && lo < hi; ++k) box.points.push_back(static_cast<float>(lo + (hi - lo) * t(rng)));
  for (float e : kEnds)  // every listed value the box holds: the extrema of sin, the zeros
    if (box.iv.lo <= e && e <= box.iv.hi) box.points.push_back(e);
  if (box.iv.lo <= 0 && 0 <= box.iv.hi) box.points.push_back(-0.0f);
  if (box.iv.nan) box.points.push_back(test::kNan);
  return box;
}

// One box per input, each of half-size `half` around a point of [-span, span] (thousandths), with
// its ends, centre and a few points inside; their intervals go to `in`.
std::vector<Box> boxes_around(std::mt19937& rng, size_t inputs, float half, int span, std::vector<Interval>& in) {
  std::vector<Box> boxes;
  in.clear();
  for (size_t a = 0; a < inputs; ++a) {
    float centre = static_cast<float>(static_cast<int>(rng() % static_cast<unsigned>(2 * span + 1)) - span) / 1000.0f;
    Box bx;
    bx.iv = {centre - half, centre + half, false};
    bx.points = {bx.iv.lo, bx.iv.hi, centre};
    for (int k = 0; k < 6; ++k) bx.points.push_back(bx.iv.lo + 2 * half * static_cast<float>(rng() % 1000) / 1000.0f);
    boxes.push_back(bx);
    in.push_back(bx.iv);
  }
  return boxes;
}

// The IR of a kernel applying `op` to its parameters.
std::unique_ptr<ir::Module> op_kernel(ir::Op op, int arity) {
  std::string text = "fn @kernel(" + std::to_string(arity) + ") -> 1 kernel {\nb0:\n", args;
  for (int a = 0; a < arity; ++a) {
    text += "  v" + std::to_string(a) + " = param " + std::to_string(a) + "\n";
    args += (a ? ", v" : " v") + std::to_string(a);
  }
  text += "  v9 = " + std::string(ir::mnemonic(op)) + args + "\n  ret v9\n}\n";
  std::string err;
  return ir::read(text, err);
}

std::vector<std::unique_ptr<backends::Kernel>> every_backend(const ir::Module& m) {
  std::vector<std::unique_ptr<backends::Kernel>> out;
  for (const auto& name : backends::available_backends()) {
    std::string err;
    out.push_back(backends::make_backend(name)->compile(m, {}, err));
    INFO(name << ": " << err);
    REQUIRE(out.back());
  }
  return out;
}

// Points x boxes: every combination of each box's points for `arity` inputs (capped), as columns,
// with the index of the case each point belongs to.
struct Batch {
  std::vector<std::vector<float>> cols;
  std::vector<size_t> owner;
};

void add_case(Batch& b, const std::vector<Box>& boxes, size_t index, std::mt19937& rng, int samples) {
  for (int s = 0; s < samples; ++s) {
    for (size_t a = 0; a < boxes.size(); ++a) {
      const auto& p = boxes[a].points;
      b.cols[a].push_back(p[s < static_cast<int>(p.size()) ? static_cast<size_t>(s) : rng() % p.size()]);
    }
    b.owner.push_back(index);
  }
}

std::vector<std::vector<float>> run_all(const std::vector<std::unique_ptr<backends::Kernel>>& kernels, Batch& b,
                                        size_t outputs) {
  std::vector<std::vector<float>> results;
  size_t n = b.owner.size();
  std::vector<const float*> in;
  for (auto& c : b.cols) in.push_back(c.data());
  for (const auto& k : kernels) {
    std::vector<std::vector<float>> out(outputs, std::vector<float>(n));
    std::vector<float*> outs;
    for (auto& o : out) outs.push_back(o.data());
    backends::RuntimeError err;
    REQUIRE(k->eval_batch(in.data(), outs.data(), n, err));
    for (auto& o : out) results.push_back(std::move(o));
  }
  return results;
}

// Output 0 of `fn` over each case's boxes by the batched evaluator (16 cases a pass), on every ISA
// variant this CPU runs: [variant][case].
std::vector<std::vector<Interval>> batch_bounds(const ir::Function& fn,
                                                const std::vector<std::vector<Interval>>& cases) {
  ir::IntervalTape tape(fn);
  using Run = decltype(&ir::isa_base::eval_lanes);
  std::vector<Run> variants = {ir::isa_base::eval_lanes};
  if (__builtin_cpu_supports("x86-64-v3")) variants.push_back(ir::isa_avx2::eval_lanes);
  if (__builtin_cpu_supports("x86-64-v4")) variants.push_back(ir::isa_avx512::eval_lanes);
  constexpr size_t L = ir::kIntervalLanes;
  std::vector<std::vector<Interval>> out;
  for (Run run : variants) {
    std::vector<Interval> got(cases.size());
    for (size_t first = 0; first < cases.size(); first += L) {
      std::vector<ir::IntervalLanes> in(tape.num_params());
      for (size_t p = 0; p < in.size(); ++p)
        for (size_t k = 0; k < L; ++k) in[p].set(k, cases[std::min(first + k, cases.size() - 1)][p]);
      std::vector<ir::IntervalLanes> values(tape.num_values());
      std::vector<ir::Choice> choices(values.size() * L);
      run(tape.steps().data(), tape.steps().size(), in.data(), in.size(), values.data(), choices.data());
      for (size_t k = 0; k < L && first + k < cases.size(); ++k) got[first + k] = values[tape.outputs()[0]].lane(k);
    }
    out.push_back(std::move(got));
  }
  return out;
}

}  // namespace

TEST_CASE("intervals: outward rounding by ulps in one step equals stepping one ulp at a time") {
  using fscript::math::detail::next_down;
  using fscript::math::detail::next_up;
  using fscript::math::detail::steps_down;
  std::mt19937 rng(7);
  std::vector<float> fs = {0.0f,
                           -0.0f,
                           std::numeric_limits<float>::denorm_min(),
                           -std::numeric_limits<float>::denorm_min(),
                           std::numeric_limits<float>::min(),
                           -std::numeric_limits<float>::min(),
                           std::numeric_limits<float>::max(),
                           -std::numeric_limits<float>::max(),
                           std::numeric_limits<float>::infinity(),
                           -std::numeric_limits<float>::infinity(),
                           1.0f,
                           -1.0f};
  for (uint32_t b = 1; b < 8; ++b)
    fs.push_back(std::bit_cast<float>(b)), fs.push_back(std::bit_cast<float>(0x80000000u | b));
  for (uint32_t b = 0x7f7ffff8u; b < 0x7f800000u; ++b)
    fs.push_back(std::bit_cast<float>(b)), fs.push_back(std::bit_cast<float>(0x80000000u | b));
  for (int i = 0; i < 100000; ++i) {
    float f = std::bit_cast<float>(static_cast<uint32_t>(rng()));
    if (f == f) fs.push_back(f);
  }
  for (float f : fs)
    for (int ulps = 0; ulps <= 6; ++ulps) {
      float down = f, up = f;
      for (int k = 0; k < ulps; ++k) down = next_down(down), up = next_up(up);
      INFO(f << " " << ulps);
      REQUIRE(std::bit_cast<uint32_t>(steps_down(f, ulps)) == std::bit_cast<uint32_t>(down));
      REQUIRE(std::bit_cast<uint32_t>(-steps_down(-f, ulps)) == std::bit_cast<uint32_t>(up));
    }
}

TEST_CASE("intervals: every value op of the table holds every point result, on every backend") {
  std::mt19937 rng(20261202);
  int ops = 0;
  for (int k = 0; k < ir::kNumOps; ++k) {
    ir::Op op = static_cast<ir::Op>(k);
    if (!ir::has_flag(op, ir::Pure) || op == ir::Op::Const || op == ir::Op::Param || op == ir::Op::Phi) continue;
    ++ops;
    int arity = ir::op_info(op).arity;
    auto m = op_kernel(op, arity);
    REQUIRE(m);
    auto kernels = every_backend(*m);
    std::vector<std::vector<Box>> cases(3000);
    std::vector<std::vector<Interval>> boxes(cases.size());
    std::vector<Interval> want(cases.size());
    Batch batch{std::vector<std::vector<float>>(static_cast<size_t>(arity)), {}};
    for (size_t c = 0; c < cases.size(); ++c) {
      std::vector<Interval>& in = boxes[c];
      for (int a = 0; a < arity; ++a) cases[c].push_back(random_box(rng)), in.push_back(cases[c].back().iv);
      ir::IntervalEval ev;
      REQUIRE(ir::eval_intervals(*m->functions[0], in, ev));
      want[c] = ev.outputs[0];
      add_case(batch, cases[c], c, rng, 12);
    }
    // The scalar rules, then the batched evaluator on each ISA variant.
    std::vector<std::vector<Interval>> bounds = batch_bounds(*m->functions[0], boxes);
    bounds.insert(bounds.begin(), want);
    auto results = run_all(kernels, batch, 1);
    int bad = 0;
    for (size_t i = 0; i < batch.owner.size(); ++i) {
      float args[3] = {0, 0, 0}, scalar;
      for (int a = 0; a < arity; ++a) args[a] = batch.cols[static_cast<size_t>(a)][i];
      REQUIRE(ir::eval_pure(op, args, scalar));
      for (size_t r = 0; r < bounds.size() * (results.size() + 1); ++r) {
        size_t by = r / (results.size() + 1), of = r % (results.size() + 1);
        const Interval& w = bounds[by][batch.owner[i]];
        float got = of == results.size() ? scalar : results[of][i];
        if (w.contains(got) || bad++ > 5) continue;
        const auto& bx = cases[batch.owner[i]];
        FAIL_CHECK(ir::mnemonic(op) << (by ? " (batched intervals, variant " + std::to_string(by - 1) + ")" : "")
                                    << (of == results.size() ? " (scalar)" : " (backend " + std::to_string(of) + ")")
                                    << " at (" << args[0] << ", " << args[1] << ", " << args[2] << ") = " << got
                                    << " outside [" << w.lo << ", " << w.hi << "]" << (w.nan ? " or NaN" : "")
                                    << "; boxes [" << bx[0].iv.lo << ", " << bx[0].iv.hi << "]"
                                    << (bx.size() > 1 ? " [" + std::to_string(bx[1].iv.lo) + ", " +
                                                std::to_string(bx[1].iv.hi) + "]"
                                                      : ""));
      }
    }
  }
  CHECK(ops >= 40);
}

TEST_CASE("intervals: decided comparisons, selects and min/max choices hold at every point") {
  using ir::Choice;
  auto m = op_kernel(ir::Op::Min, 2);
  const uint32_t v = m->functions[0]->entry()->insts[2]->id;  // the fmin
  ir::IntervalEval ev;
  REQUIRE(ir::eval_intervals(*m->functions[0], {{0, 1, false}, {2, 3, false}}, ev));
  CHECK(ev.choices[v] == Choice::Left);
  REQUIRE(ir::eval_intervals(*m->functions[0], {{0, 1, false}, {2, 3, true}}, ev));
  CHECK(ev.choices[v] == Choice::Both);  // b may be NaN: min would be NaN, not a
  REQUIRE(ir::eval_intervals(*m->functions[0], {{4, 5, true}, {2, 3, false}}, ev));
  CHECK(ev.choices[v] == Choice::Both);  // a may be NaN
  REQUIRE(ir::eval_intervals(*m->functions[0], {{4, 5, false}, {2, 3, false}}, ev));
  CHECK(ev.choices[v] == Choice::Right);
  REQUIRE(ir::eval_intervals(*m->functions[0], {{0, 2, false}, {2, 3, false}}, ev));
  CHECK(ev.choices[v] == Choice::Both);  // touching: left to the dense code
  CHECK(math::truth_of({0, 0, true}) == math::Truth::Never);
  CHECK(math::truth_of({1e-30f, 5, false}) == math::Truth::Always);
  CHECK(math::truth_of({-1, 1, false}) == math::Truth::Either);
  CHECK(math::iv::lt({0, 1, false}, {1, 2, false}).lo == 0);  // 1 < 1 is false
  CHECK(math::iv::lt({0, 1, false}, {2, 3, false}).lo == 1);
  CHECK(math::iv::lt({0, 1, true}, {2, 3, false}).lo == 0);  // NaN < 2 is false
}

TEST_CASE("intervals: benchmarks and examples bound every point of random boxes, on every backend") {
  std::mt19937 rng(7);
  std::vector<std::string> files = {"bench/snail.fs", "bench/star.fs", "examples/blobs.fs"};
  std::string shared = std::getenv("FS_SHARED_DIR") ? std::getenv("FS_SHARED_DIR") : "";
  std::string probe;
  if (shared.empty() || !support::read_file(shared + "/bench/gyroid.fs", probe, probe))
    test::skip(test::SkipKind::Missing,
               "the shared folder's benchmarks (FS_SHARED_DIR) are not there; the bundled ones ran");
  else
    for (const char* f : {"/bench/gyroid.fs", "/bench/csg8.fs", "/data/prospero.fs"}) files.push_back(shared + f);
  int evaluable = 0;
  for (const auto& f : files) {
    std::string text, err;
    std::string path = f[0] == '/' ? f : std::string(FS_SOURCE_DIR) + "/" + f;
    REQUIRE(support::read_file(path, text, err));
    auto b = test::build(text);
    INFO(f << "\n" << test::messages(b->diag));
    REQUIRE(b->ok);
    const ir::Function& fn = *b->module->functions[static_cast<size_t>(b->module->find_function("kernel"))];
    if (!ir::interval_evaluable(fn)) continue;
    ++evaluable;
    auto kernels = every_backend(*b->module);
    size_t inputs = fn.num_params, outputs = fn.num_results;
    Batch batch{std::vector<std::vector<float>>(inputs), {}};
    std::vector<std::vector<Interval>> want;
    int tight = 0, small = 0;  // boxes of half-size <= 2^-8, and those whose outputs are narrower than 0.5
    for (size_t c = 0; c < 200; ++c) {
      std::vector<Interval> in;  // boxes of every size around points of [-2, 2]
      std::vector<Box> boxes = boxes_around(rng, inputs, std::ldexp(1.0f, -static_cast<int>(c % 12)), 2000, in);
      ir::IntervalEval ev;
      REQUIRE(ir::eval_intervals(fn, in, ev));
      want.push_back(ev.outputs);
      add_case(batch, boxes, c, rng, 8);
      if (c % 12 >= 8) {
        ++small;
        bool narrow = true;
        for (const Interval& o : ev.outputs) narrow &= !o.nan && o.hi - o.lo < 0.5f;
        tight += narrow;
      }
    }
    // Not vacuous: on small boxes the bounds are close (the rules are tight, not just sound).
    INFO(f << ": " << tight << " of " << small << " small boxes bounded within 0.5");
    CHECK(tight == small);
    auto results = run_all(kernels, batch, outputs);
    int bad = 0;
    for (size_t i = 0; i < batch.owner.size(); ++i)
      for (size_t r = 0; r < results.size(); ++r) {
        const Interval& w = want[batch.owner[i]][r % outputs];
        if (!w.contains(results[r][i]) && bad++ < 5)
          FAIL_CHECK(f << ": output " << r % outputs << " = " << results[r][i] << " outside [" << w.lo << ", " << w.hi
                       << "]");
      }
  }
  CHECK(evaluable >= 3);
}

namespace {

// A random expression over x, y, z with every kind of operation the language has: every built-in
// of frontend/fscript/builtins.def by its arity, so a new one is in these programs at once.
std::string random_expr(std::mt19937& rng, int depth) {
  static const char* leaves[] = {"x", "y", "z", "0.5", "2", "-3", "0", "1e3"};
  static const std::array<std::vector<std::string>, 4> calls = [] {
    std::array<std::vector<std::string>, 4> by_arity;
#define FS_BUILTIN(N, A, OP, SIG, DOC) by_arity[A].push_back(N);
#include "frontend/fscript/builtins.def"
    by_arity[1].push_back("-");
    return by_arity;
  }();
  static const char* binary[] = {"+", "-", "*", "/", "%", "<", "<=", ">", ">=", "==", "!=", "&&", "||"};
  if (depth == 0 || rng() % 5 == 0) return leaves[rng() % 8];
  std::string a = random_expr(rng, depth - 1), b = random_expr(rng, depth - 1);
  auto call = [&](int arity) { return calls[arity][rng() % calls[arity].size()]; };
  switch (rng() % 6) {
    case 0: return call(1) + "(" + a + ")";
    case 1:
    case 2: return "(" + a + " " + binary[rng() % 13] + " " + b + ")";
    case 3: return call(2) + "(" + a + ", " + b + ")";
    case 4: return "(" + a + " < " + b + " ? " + random_expr(rng, depth - 1) + " : " + b + ")";
    default: {
      std::string f = call(3);
      return f + "(" + a + (f == "clamp" ? ", -1, " + b + ")" : ", " + b + ", z)");
    }
  }
}

}  // namespace

TEST_CASE("intervals: thousands of random programs bound every point of random boxes") {
  std::mt19937 rng(42);
  int programs = 0, evaluable = 0, checked = 0;
  for (int p = 0; p < 1500; ++p) {
    std::string expr = random_expr(rng, 4);
    auto b = test::build("function FRep(x, y, z, t) { return " + expr + "; }");
    if (!b->ok) continue;  // e.g. a constant division the analysis refuses
    ++programs;
    const ir::Function& fn = *b->module->functions[static_cast<size_t>(b->module->find_function("kernel"))];
    if (!ir::interval_evaluable(fn)) continue;
    ++evaluable;
    // The VM and the sse backend for every program; llvm (slow to compile) for every tenth.
    std::vector<std::unique_ptr<backends::Kernel>> kernels;
    for (const std::string name : {"vm", "sse", "llvm"}) {
      if (name == "llvm" && (p % 10 != 0 || !backends::make_backend("llvm"))) continue;
      std::string err;
      kernels.push_back(backends::make_backend(name)->compile(*b->module, {}, err));
      REQUIRE(kernels.back());
    }
    Batch batch{std::vector<std::vector<float>>(fn.num_params), {}};
    std::vector<Interval> want;
    std::vector<std::vector<Interval>> cases;
    for (size_t c = 0; c < 4; ++c) {
      std::vector<Box> boxes;
      std::vector<Interval> in;
      for (size_t a = 0; a < fn.num_params; ++a) boxes.push_back(random_box(rng)), in.push_back(boxes.back().iv);
      ir::IntervalEval ev;
      REQUIRE(ir::eval_intervals(fn, in, ev));
      want.push_back(ev.outputs[0]);
      cases.push_back(in);
      add_case(batch, boxes, c, rng, 10);
    }
    std::vector<std::vector<Interval>> bounds = batch_bounds(fn, cases);  // then the scalar rules
    bounds.push_back(want);
    auto results = run_all(kernels, batch, 1);
    for (size_t i = 0; i < batch.owner.size(); ++i)
      for (size_t r = 0; r < results.size() * bounds.size(); ++r) {
        ++checked;
        const Interval& w = bounds[r / results.size()][batch.owner[i]];
        if (w.contains(results[r % results.size()][i])) continue;
        FAIL_CHECK("return " << expr << ";\n at (" << batch.cols[0][i] << ", " << batch.cols[1][i] << ", "
                             << batch.cols[2][i] << ") = " << results[r % results.size()][i] << " outside [" << w.lo
                             << ", " << w.hi << "]" << (w.nan ? " or NaN" : "")
                             << (r / results.size() + 1 < bounds.size() ? " (batched intervals)" : ""));
        break;
      }
  }
  INFO(programs << " programs, " << evaluable << " straight-line, " << checked << " point results");
  CHECK(evaluable > 1000);
  CHECK(checked > 100000);
}

namespace {

// The kernel function of a module built by test::build.
const ir::Function& kernel_of(const ir::Module& m) {
  return *m.functions[static_cast<size_t>(m.find_function("kernel"))];
}

// "" when `simple` gives `full`'s bits at every point of `boxes` (on `backend`), else the first difference.
std::string same_outputs(std::unique_ptr<backends::Kernel> a, std::unique_ptr<backends::Kernel> b, size_t outs,
                         const std::vector<Box>& boxes, std::mt19937& rng);

std::string same_bits(const ir::Module& full, const ir::Module& simple, const std::vector<Box>& boxes,
                      const std::string& backend, std::mt19937& rng) {
  std::string err;
  auto a = backends::make_backend(backend)->compile(full, {}, err);
  auto b = backends::make_backend(backend)->compile(simple, {}, err);
  if (!a || !b) return "compile: " + err;
  return same_outputs(std::move(a), std::move(b), kernel_of(full).num_results, boxes, rng);
}

// The full kernel on the VM against the tape compiled by the VM without IR (vm::compile_tape), and
// against the tape run with no compile at all (vm::eval_tape_points, output 0).
std::string same_bits_on_tape(const ir::Module& full, const ir::IntervalTape& tape, const std::vector<Box>& boxes,
                              std::mt19937& rng) {
  std::string err;
  auto a = backends::make_backend("vm")->compile(full, {}, err);
  if (!a) return "compile: " + err;
  Batch batch{std::vector<std::vector<float>>(boxes.size()), {}};
  add_case(batch, boxes, 0, rng, 24);
  size_t n = std::min(batch.owner.size(), vm::kPointLanes);
  std::vector<const float*> in;
  for (auto& c : batch.cols) in.push_back(c.data());
  std::vector<float> want(batch.owner.size()), got(n);
  std::vector<float*> outs(kernel_of(full).num_results, want.data());
  std::vector<std::vector<float>> spare(outs.size(), std::vector<float>(want.size()));
  for (size_t k = 1; k < outs.size(); ++k) outs[k] = spare[k].data();
  backends::RuntimeError rerr;
  if (!a->eval_batch(in.data(), outs.data(), batch.owner.size(), rerr)) return "vm: " + rerr.message;
  // Whole batches and partial ones (the runner computes only the vectors a batch fills).
  for (size_t count : {n, n / 3, std::min<size_t>(n, 17), std::min<size_t>(n, 1)}) {
    std::fill(got.begin(), got.end(), NAN);
    vm::eval_tape_points(tape, in.data(), in.size(), count, got.data());
    for (size_t i = 0; i < count; ++i)
      if (!test::same(want[i], got[i]))
        return "eval_tape_points of " + std::to_string(count) + " at point " + std::to_string(i) + ": " +
            std::to_string(got[i]) + " vs " + std::to_string(want[i]);
  }
  auto b = backends::make_backend("vm")->compile(full, {}, err);
  return same_outputs(std::move(b), vm::compile_tape(tape, {}), kernel_of(full).num_results, boxes, rng);
}

std::string same_outputs(std::unique_ptr<backends::Kernel> a, std::unique_ptr<backends::Kernel> b, size_t outs,
                         const std::vector<Box>& boxes, std::mt19937& rng) {
  Batch batch{std::vector<std::vector<float>>(boxes.size()), {}};
  add_case(batch, boxes, 0, rng, 24);
  std::vector<std::unique_ptr<backends::Kernel>> ks;
  ks.push_back(std::move(a));
  ks.push_back(std::move(b));
  auto r = run_all(ks, batch, outs);
  for (size_t o = 0; o < outs; ++o)
    for (size_t i = 0; i < batch.owner.size(); ++i)
      if (!test::same(r[o][i], r[outs + o][i]))
        return "output " + std::to_string(o) + " at point " + std::to_string(i) + ": " + std::to_string(r[o][i]) +
            " vs " + std::to_string(r[outs + o][i]);
  return "";
}

}  // namespace

TEST_CASE("tape simplification: the same bits inside the region, recursively, and shorter tapes") {
  std::mt19937 rng(99);
  std::vector<std::string> texts = {
      "function FRep(x, y, z, t) { return min(x * x + y * y - 1, max(abs(x) - 0.5, abs(y) - 0.5)); }",
      "function FRep(x, y, z, t) { return x < 0 ? sin(y) : cos(y) + max(z, x); }"};
  for (int p = 0; p < 400; ++p) texts.push_back("function FRep(x, y, z, t) { return " + random_expr(rng, 5) + "; }");
  std::string shared = std::getenv("FS_SHARED_DIR") ? std::getenv("FS_SHARED_DIR") : "", prospero;
  bool have_prospero = !shared.empty() && support::read_file(shared + "/data/prospero.fs", prospero, prospero);
  if (have_prospero) texts.push_back(prospero);
  int collapsed = 0, checked = 0, lane_collapsed = 0;
  for (const auto& text : texts) {
    auto b = test::build(text);
    if (!b->ok || !ir::interval_evaluable(kernel_of(*b->module))) continue;
    const ir::Function& fn = kernel_of(*b->module);
    for (int c = 0; c < 3; ++c) {
      std::vector<Interval> in;  // a small box, so choices get decided
      std::vector<Box> boxes = boxes_around(rng, fn.num_params, 1.0f / 64, 1000, in);
      ir::IntervalEval ev;
      REQUIRE(ir::eval_intervals(fn, in, ev));
      ir::IntervalTape full(fn);
      size_t decided = 0;
      ir::IntervalTape t = full.simplified(ev, &decided);
      REQUIRE(t.length() <= ir::tape_length(fn));
      collapsed += decided > 0;
      INFO(text.substr(0, 300));
      auto module = ir::tape_module(t);
      for (const char* be : {"vm", "sse"}) CHECK(same_bits(*b->module, *module, boxes, be, rng) == "");
      CHECK(same_bits_on_tape(*b->module, t, boxes, rng) == "");  // the VM straight from the tape
      // A quarter of the region simplifies the simplified tape again, still with the same bits.
      for (auto& bx : boxes) {
        bx.iv.hi = bx.iv.lo + (bx.iv.hi - bx.iv.lo) / 4;
        bx.points = {bx.iv.lo, bx.iv.hi, (bx.iv.lo + bx.iv.hi) / 2};
      }
      std::vector<Interval> quarter;
      for (const auto& bx : boxes) quarter.push_back(bx.iv);
      t.eval(quarter, ev);
      ir::IntervalTape t2 = t.simplified(ev);
      REQUIRE(t2.length() <= t.length());
      CHECK(same_bits(*b->module, *ir::tape_module(t2), boxes, "vm", rng) == "");
      CHECK(same_bits_on_tape(*b->module, t2, boxes, rng) == "");
      ++checked;
    }
    // Batched: 16 small boxes in the lanes of one evaluation, each lane's tape simplified from the
    // shared backward pass; every lane's tape gives the full kernel's bits in its own box.
    std::vector<std::vector<Box>> lane_boxes;
    std::vector<ir::IntervalLanes> lanes(fn.num_params);
    for (size_t k = 0; k < ir::kIntervalLanes; ++k) {
      std::vector<Interval> in;
      lane_boxes.push_back(boxes_around(rng, fn.num_params, 1.0f / 64, 1000, in));
      for (size_t a = 0; a < fn.num_params; ++a) lanes[a].set(k, in[a]);
    }
    ir::IntervalTape full(fn);
    ir::IntervalBatchEval bev;
    full.eval_batch(lanes, bev);
    for (size_t k = 0; k < ir::kIntervalLanes; k += 5) {
      ir::IntervalTape t = full.simplified(bev, k);
      INFO(text.substr(0, 300) << "\nlane " << k);
      CHECK(same_bits_on_tape(*b->module, t, lane_boxes[k], rng) == "");
      lane_collapsed += t.length() < full.length();
    }
    if (&text == &texts.back() && have_prospero) {  // prospero: a small region keeps a small part
      std::vector<Interval> region(fn.num_params, Interval{0, 0, false});
      region[0] = {0.5f, 0.52f, false};
      region[1] = {0.5f, 0.52f, false};
      ir::IntervalEval ev;
      REQUIRE(ir::eval_intervals(fn, region, ev));
      ir::IntervalTape t = ir::IntervalTape(fn).simplified(ev);
      INFO("prospero: " << t.length() << " of " << ir::tape_length(fn) << " operations in a 0.02 square");
      CHECK(t.length() * 10 < ir::tape_length(fn));
    }
  }
  CHECK(checked > 300);
  CHECK(collapsed > 100);
  CHECK(lane_collapsed > 100);
}

TEST_CASE("quadtree rendering: the same pixels as the dense path, for random programs, sizes and threads") {
  std::mt19937 rng(5);
  std::vector<std::string> texts = {"function FRep(x, y, z, t) { return 0.8 - sqrt(x * x + y * y); }",
                                    "function FRep(x, y, z, t) { return min(0.5 - abs(x), 0.3 - abs(y)); }",
                                    "function FRep(x, y, z, t) { return sin(10 * x) * cos(10 * y) - 0.2; }"};
  for (int p = 0; p < 120; ++p) texts.push_back("function FRep(x, y, z, t) { return " + random_expr(rng, 4) + "; }");
  int pruned = 0;
  size_t saved = 0;
  for (size_t k = 0; k < texts.size(); ++k) {
    const char* be = k % 3 == 2 ? "sse" : "vm";
    auto b = test::build(texts[k], "", true, {}, be);
    if (!b->ok) continue;
    uint32_t big = k % 8 == 0 ? 500 : 0;  // some of several top tiles a side: threads take each other's
    render::PlaneGrid g{static_cast<uint32_t>(97 + big + rng() % 300),
                        static_cast<uint32_t>(61 + big + rng() % 300),
                        -1.3f,
                        1.1f,
                        -0.9f,
                        1.4f};
    render::InsideOptions o;
    o.threads = 1 + static_cast<unsigned>(k % 3);
    if (k % 2 && ir::interval_evaluable(b->module->kernel_function()))  // the tape built ahead, as render2d does
      o.tape = std::make_shared<const ir::IntervalTape>(b->module->kernel_function());
    // A picture's vector reused: every pixel is written, whatever was there.
    std::vector<uint8_t> a(size_t(g.w) * g.h, 77), d;
    render::QuadtreeStats sa, sd;
    backends::RuntimeError err;
    REQUIRE(render::render_inside(*b->module, *b->kernel, g, o, a, sa, err));
    o.prune = false;
    REQUIRE(render::render_inside(*b->module, *b->kernel, g, o, d, sd, err));
    INFO(texts[k] << " at " << g.w << "x" << g.h << " on " << be);
    CHECK(a == d);
    CHECK_FALSE(sd.pruned);
    pruned += sa.pruned;
    saved += size_t(g.w) * g.h - sa.points;
  }
  CHECK(pruned > 100);
  CHECK(saved > 0);
}
