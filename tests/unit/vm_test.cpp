// The VM: batch path equals the one-point path, divergent lanes, budgets, special values per op.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <sstream>

#include "backends/regalloc.h"
#include "backends/vm/bytecode.h"
#include "ir/eval.h"
#include "ir/text.h"
#include "runtime/support/big_stack.h"
#include "tests/unit/helpers.h"

using namespace fscript;

static bool same(float a, float b) { return a == b || (std::isnan(a) && std::isnan(b)); }

TEST_CASE("vm: a batch gives the same results as one point at a time, with divergent lanes") {
  auto b = test::build(R"(
    function steps(x) { var n = 0; var v = abs(x) * 10; while (v > 1) { v = v / 2; n++; } return n; }
    function fib(n) { return n < 2 ? n : fib(n - 1) + fib(n - 2); }
    function FRep(x, y, z, t) {
      var s = steps(x);
      if (y > 0) { for (var i = 0; i < s; i++) { if (i == 3) break; z += sin(i); } } else { z = fib(floor(abs(y) * 5)); }
      return s * 100 + z;
    })");
  REQUIRE(b->ok);
  const size_t n = 1000;
  std::vector<float> xs(n), ys(n), zs(n), ts(n, 0), out(n);
  for (size_t i = 0; i < n; ++i) {
    xs[i] = std::sin(static_cast<float>(i)) * 3;
    ys[i] = std::cos(static_cast<float>(i) * 0.7f);
    zs[i] = static_cast<float>(i % 7);
  }
  const float* in[] = {xs.data(), ys.data(), zs.data(), ts.data()};
  float* outs[] = {out.data()};
  backends::RuntimeError err;
  REQUIRE(b->kernel->eval_batch(in, outs, n, err));
  int mismatches = 0;
  for (size_t i = 0; i < n; ++i) mismatches += !same(out[i], test::eval1(*b, {xs[i], ys[i], zs[i], 0}));
  CHECK(mismatches == 0);
}

TEST_CASE("vm: budgets stop runaway scripts and name the line") {
  backends::Budgets small;
  small.max_loop_iterations = 1000;
  small.max_call_depth = 20;
  auto loop = test::build("function f(x) {\n  while (x == x) {\n    x = x + 1;\n  }\n  return x;\n}", "f", true, small);
  REQUIRE(loop->ok);
  std::vector<float> in = {1}, out(1);
  backends::RuntimeError err;
  CHECK(!loop->kernel->eval(in.data(), out.data(), err));
  CHECK(err.line == 2);
  CHECK(err.message.find("loop iteration budget") != std::string::npos);
  auto rec = test::build("function f(x) {\n  return f(x + 1);\n}", "f", true, small);
  REQUIRE(rec->ok);
  CHECK(!rec->kernel->eval(in.data(), out.data(), err));
  CHECK(err.line == 2);
  CHECK(err.message.find("call depth") != std::string::npos);
}

TEST_CASE("vm: an out-of-range index names the line and never touches other memory") {
  auto b = test::build("function f(i) {\n  var a = [1, 2, 3];\n  return a[i];\n}", "f");
  REQUIRE(b->ok);
  std::vector<float> in = {1e9f}, out(1);
  backends::RuntimeError err;
  CHECK(!b->kernel->eval(in.data(), out.data(), err));
  CHECK(err.line == 3);
  CHECK(err.message.find("out of range") != std::string::npos);
}

TEST_CASE("vm: many small kernels compiled and freed") {
  for (int i = 0; i < 300; ++i) {
    auto b = test::build("function FRep(x,y,z,t){ return x * " + std::to_string(i) + " + y; }");
    REQUIRE(b->ok);
    CHECK(test::eval1(*b, {1, 2}) == static_cast<float>(i + 2));
  }
}

TEST_CASE("vm: a chunk whose loop runs long runs again point by point, with the same results") {
  // Lanes loop 0 to 100,000 times: past 65,536 iterations together the chunk goes lane by lane.
  auto b = test::build("function FRep(x, y, z, t) { var s = 0; for (var i = 0; i < x; i++) s = s + y; return s; }");
  REQUIRE(b->ok);
  size_t n = 600;  // two chunks, the second partial
  std::vector<float> xs(n), ys(n), zero(n, 0), out(n);
  for (size_t i = 0; i < n; ++i)
    xs[i] = static_cast<float>((i * 7919) % 100001), ys[i] = 0.5f + static_cast<float>(i % 3);
  const float* in[4] = {xs.data(), ys.data(), zero.data(), zero.data()};
  float* outs[1] = {out.data()};
  backends::RuntimeError err;
  REQUIRE(b->kernel->eval_batch(in, outs, n, err));
  int mismatches = 0;
  for (size_t i = 0; i < n; i += 37) mismatches += !same(out[i], test::eval1(*b, {xs[i], ys[i], 0, 0}));
  CHECK(mismatches == 0);
  // A runaway lane among them stops the batch with the budget's error.
  backends::Budgets small;
  small.max_loop_iterations = 200000;
  auto capped = test::build("function FRep(x, y, z, t) { var s = 0; for (var i = 0; i < x; i++) s = s + y; return s; }",
                            "", true, small);
  xs[300] = 1e9f;
  CHECK_FALSE(capped->kernel->eval_batch(in, outs, n, err));
  CHECK(err.message == "loop iteration budget exceeded: more than 200000 iterations in one evaluation");
}

// sin and cos of one value in one block share one range reduction (backends/vm/bytecode.h): the
// listing shows the pairs, and the results are the SSE backend's bits (which compute sin and cos
// on their own where unpaired) on special values, batch and one point, under a mask.
TEST_CASE("vm: paired sin and cos give the bits of sin and cos alone") {
  const char* src = R"(
    function FRep(x, y, z, t) {
      var r = 0;
      if (y > 0) { r = sin(x) * 3 + cos(x); } else { r = cos(x * 2) - sin(x * 2) + sin(x); }
      return r + cos(z) * 0.5 - sin(z);
    })";
  auto vm = test::build(src);
  auto sse = test::build(src, "", true, {}, "sse");
  REQUIRE(vm->ok);
  REQUIRE(sse->ok);
  vm::VmProgram p;
  std::string error;
  REQUIRE(vm::compile_program(*vm->module, p, error));
  std::string listing = vm::disassemble(p);
  INFO(listing);
  CHECK(listing.find("(and its cos into r") != std::string::npos);
  CHECK(listing.find("(computed with its pair, from r") != std::string::npos);
  const float special[] = {0.0f,   -0.0f,  1.0f,       -1.0f, 0.5f,       3.14159265f, -1.5707964f,
                           100.0f, 1e5f,   8388608.0f, 1e30f, -1e30f,     INFINITY,    -INFINITY,
                           NAN,    1e-40f, 7.25f,      -2.5f, 6.2831855f, 1e-7f,       16777216.0f};
  const size_t n = std::size(special) * 4;
  std::vector<float> xs(n), ys(n), zs(n), ts(n, 0), a(n), b(n);
  for (size_t i = 0; i < n; ++i) {
    xs[i] = special[i % std::size(special)];
    ys[i] = (i / std::size(special)) % 2 ? 1.0f : -1.0f;  // both branches, lanes mixed
    zs[i] = special[(i * 7 + 3) % std::size(special)];
  }
  const float* in[] = {xs.data(), ys.data(), zs.data(), ts.data()};
  float* oa[] = {a.data()};
  float* ob[] = {b.data()};
  backends::RuntimeError err;
  REQUIRE(vm->kernel->eval_batch(in, oa, n, err));
  REQUIRE(sse->kernel->eval_batch(in, ob, n, err));
  int batch = 0, one = 0;
  for (size_t i = 0; i < n; ++i) {
    batch += !same(a[i], b[i]);
    one += !same(test::eval1(*vm, {xs[i], ys[i], zs[i], 0}), b[i]);
  }
  CHECK(batch == 0);
  CHECK(one == 0);
}

namespace {

// Bits, zero signs included; any NaN for a NaN (payloads are not defined).
bool same_bits(float a, float b) { return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0; }

struct OpText {
  ir::Op op;
  const char* form;  // A and B stand for the operands
};

std::string fill(std::string form, const std::string& a, const std::string& b) {
  form.replace(form.find('A'), 1, a);
  if (size_t at = form.find('B'); at != std::string::npos) form.replace(at, 1, b);
  return form;
}

// `d = first(a, b)` then `second(d, c)` or `second(c, d)` (with `squared`, d * d in d's place) for
// every first op given and every op that fuses second, the first op's operands x y, x 0.75 or
// 0.75 x and c a register or an immediate, on pairs of special values: each gives the bits of the
// reference evaluator's ops one after the other, in a batch and one point at a time; and most
// programs' listings show `marker` (fused as the caller expects).
void check_fused(const std::vector<OpText>& first, bool squared, const char* marker) {
  const OpText second[] = {{ir::Op::Add, "(A + B)"}, {ir::Op::Sub, "(A - B)"},   {ir::Op::Mul, "(A * B)"},
                           {ir::Op::Div, "(A / B)"}, {ir::Op::Max, "max(A, B)"}, {ir::Op::Abs, "abs(A)"},
                           {ir::Op::Neg, "(-A)"},    {ir::Op::Sqrt, "sqrt(A)"}};
  const float special[] = {0.0f,   -0.0f,  1.0f,     -1.0f,     0.5f, -2.5f, 3e38f,
                           -3e38f, 1e-40f, INFINITY, -INFINITY, NAN,  7.25f};
  const size_t k = std::size(special), n = k * k;  // 169 points: a padded tail too
  std::vector<float> xs(n), ys(n), zs(n), ts(n, 0), out(n);
  for (size_t i = 0; i < n; ++i) xs[i] = special[i % k], ys[i] = special[i / k], zs[i] = special[(i * 5 + 2) % k];
  int marked = 0, programs = 0;
  for (const OpText& o1 : first)
    for (const OpText& o2 : second)
      for (bool t_first : {true, false})
        for (const char* c : {"z", "-0.5"})
          for (int ab = 0; ab < 3; ++ab) {
            if (ir::op_info(o2.op).arity == 1 && (!t_first || c[0] != 'z')) continue;
            if (ir::op_info(o1.op).arity == 1 && ab > 0) continue;
            const char* av = ab == 2 ? "0.75" : "x";
            const char* bv = ab == 0 ? "y" : ab == 1 ? "0.75" : "x";
            const char* t = squared ? "(d * d)" : "d";
            std::string body = t_first ? fill(o2.form, t, c) : fill(o2.form, c, t);
            std::string text =
                "function FRep(x, y, z, t) { var d = " + fill(o1.form, av, bv) + "; return " + body + "; }";
            auto b = test::build(text);
            REQUIRE(b->ok);
            vm::VmProgram p;
            std::string error;
            REQUIRE(vm::compile_program(*b->module, p, error));
            ++programs;
            marked += vm::disassemble(p).find(marker) != std::string::npos;
            const float* in[] = {xs.data(), ys.data(), zs.data(), ts.data()};
            float* outs[] = {out.data()};
            backends::RuntimeError err;
            REQUIRE(b->kernel->eval_batch(in, outs, n, err));
            int bad = 0;
            for (size_t i = 0; i < n && bad < 3; ++i) {
              float args1[2] = {ab == 2 ? 0.75f : xs[i], ab == 0 ? ys[i] : ab == 1 ? 0.75f : xs[i]}, d, want;
              REQUIRE(ir::eval_pure(o1.op, args1, d));
              float args_sq[2] = {d, d};
              if (squared) REQUIRE(ir::eval_pure(ir::Op::Mul, args_sq, d));
              float other = c[0] == 'z' ? zs[i] : -0.5f;
              float args2[2] = {t_first ? d : other, t_first ? other : d};
              REQUIRE(ir::eval_pure(o2.op, args2, want));
              float one = test::eval1(*b, {xs[i], ys[i], zs[i], 0});
              if (same_bits(out[i], want) && same_bits(one, want)) continue;
              ++bad;
              FAIL_CHECK(text << " at x=" << xs[i] << " y=" << ys[i] << " z=" << zs[i] << ": batch " << out[i]
                              << ", one point " << one << ", want " << want);
            }
          }
  INFO(marked << " of " << programs << " programs have '" << marker << "'");
  CHECK(marked * 10 >= programs * 8);  // a few pairs the optimiser rewrites first (-(-x), x * -y)
}

}  // namespace

// Each pair of fusable ops, in both operand positions, with registers and immediates (bytecode.h).
TEST_CASE("vm: fused pairs of lane ops give the bits of the two ops") {
  check_fused({{ir::Op::Add, "(A + B)"},
               {ir::Op::Sub, "(A - B)"},
               {ir::Op::Mul, "(A * B)"},
               {ir::Op::Max, "max(A, B)"},
               {ir::Op::Abs, "abs(A)"},
               {ir::Op::Neg, "(-A)"},
               {ir::Op::Sqrt, "sqrt(A)"}},
              false, " -> ");
}

// An add or subtract squared on the way: x - c, its square, then the second op.
TEST_CASE("vm: squared fused pairs give the bits of the three ops") {
  check_fused({{ir::Op::Add, "A + B"}, {ir::Op::Sub, "A - B"}}, true, "-> square ->");
}

TEST_CASE("vm: straight-line code is reordered so that a value sits next to the reader it fuses with") {
  // Written the way sources write distances: the subtractions first, the squares after.
  auto b = test::build(R"(function FRep(x, y, z, t) {
    var dx = x - 0.25; var dy = y + 0.5; var dz = z - t;
    return sqrt(dx * dx + dy * dy + dz * dz) - 0.3;
  })");
  REQUIRE(b->ok);
  vm::VmProgram p;
  std::string error;
  REQUIRE(vm::compile_program(*b->module, p, error));
  std::string listing = vm::disassemble(p);
  INFO(listing);
  size_t squares = 0;
  for (size_t at = listing.find("-> square ->"); at != std::string::npos; at = listing.find("-> square ->", at + 1))
    ++squares;
  CHECK(squares == 2);  // dy^2 into the first sum, dz^2 into the second; dx^2 is the sum's other operand
  CHECK(listing.find("= sqrt r1 -> fsub _ #0.3") != std::string::npos);
  const float xs[] = {0.0f, -0.0f, 1.0f, 0.25f, 3e38f, NAN, -2.0f, 1e-40f, 0.5f};
  for (float x : xs)
    for (float y : xs) {
      float z = y * 0.5f - x, t = x;
      float dx = x - 0.25f, dy = y + 0.5f, dz = z - t;
      float want = std::sqrt(dx * dx + dy * dy + dz * dz) - 0.3f;
      CHECK(same_bits(test::eval1(*b, {x, y, z, t}), want));
    }
}

namespace {

// The straight-line kernel's value by the IR itself, op by op through the reference evaluator:
// independent of the VM's order, registers and fusion.
float reference_value(const ir::Function& fn, const float* in) {
  std::vector<float> v(fn.next_value, 0.0f);
  for (const ir::Inst* i : fn.entry()->insts) {
    if (i->op == ir::Op::Ret) return v[i->args[0]->id];
    if (i->op == ir::Op::Param) v[i->id] = in[i->aux];
    else if (i->op == ir::Op::Const) v[i->id] = i->imm;
    else {
      float a[3] = {};
      for (size_t k = 0; k < i->args.size() && k < 3; ++k) a[k] = v[i->args[k]->id];
      REQUIRE(ir::eval_pure(i->op, a, v[i->id]));
    }
  }
  FAIL("no return");
  return 0;
}

}  // namespace

// Random straight-line programs (shared values, squares of differences, chains) reordered and
// fused by the VM compiler give the IR's own values bit for bit: the fusion order never reads a
// value before it is computed, and no fused form changes a result.
TEST_CASE("vm: random straight-line programs give the IR's values after reordering and fusion") {
  std::mt19937 rng(20261205);
  auto pick = [&](size_t n) { return static_cast<size_t>(rng() % n); };
  const char* consts[] = {"0.5", "-0.25", "2", "0", "-0", "3e38", "1e-40", "0.3"};
  const float special[] = {0.0f,   -0.0f,  1.0f,     -1.0f,     0.5f, -2.5f, 3e38f,
                           -3e38f, 1e-40f, INFINITY, -INFINITY, NAN,  7.25f};
  const size_t n = 97;
  std::vector<float> cols[4];
  for (size_t c = 0; c < 4; ++c)
    for (size_t i = 0; i < n; ++i)
      cols[c].push_back(i < 40 ? special[(i * (2 * c + 1) + c) % std::size(special)]
                               : std::ldexp(float(int(rng() % 2001) - 1000) / 1000.0f, int(rng() % 9) - 4));
  int squared = 0, fused = 0;
  for (int prog = 0; prog < 150; ++prog) {
    std::vector<std::string> vars = {"x", "y", "z", "t"};
    std::string text = "function FRep(x, y, z, t) {\n";
    int stmts = 4 + static_cast<int>(pick(30));
    for (int s = 0; s < stmts; ++s) {
      auto v = [&] { return vars[vars.size() - 1 - pick(std::min<size_t>(vars.size(), 6))]; };  // mostly recent ones
      std::string a = v(), b = pick(3) ? v() : consts[pick(std::size(consts))], e;
      switch (pick(11)) {
        case 0: e = a + " + " + b; break;
        case 1: e = a + " - " + b; break;
        case 2: e = a + " * " + b; break;
        case 3: e = a + " / " + b; break;
        case 4: e = "max(" + a + ", " + b + ")"; break;
        case 5: e = "min(" + a + ", " + b + ")"; break;
        case 6: e = "abs(" + a + ")"; break;
        case 7: e = "sqrt(" + a + ")"; break;
        case 8: e = "-" + a; break;
        case 9: e = "(" + a + " - " + b + ") * (" + a + " - " + b + ")"; break;
        default: e = "(" + a + " + " + b + ") * (" + a + " + " + b + ") + " + v(); break;
      }
      std::string name = "v" + std::to_string(s);
      text += "  var " + name + " = " + e + ";\n";
      vars.push_back(name);
    }
    text += "  return " + vars.back() + (pick(2) ? " + " + vars[vars.size() / 2] : "") + ";\n}\n";
    auto b = test::build(text);
    REQUIRE(b->ok);
    const ir::Function& fn = b->module->kernel_function();
    REQUIRE(fn.blocks.size() == 1);
    vm::VmProgram p;
    std::string error;
    REQUIRE(vm::compile_program(*b->module, p, error));
    std::string listing = vm::disassemble(p);
    squared += listing.find("-> square ->") != std::string::npos;
    fused += listing.find(" -> ") != std::string::npos;
    std::vector<float> out(n);
    const float* in[] = {cols[0].data(), cols[1].data(), cols[2].data(), cols[3].data()};
    float* outs[] = {out.data()};
    backends::RuntimeError err;
    REQUIRE(b->kernel->eval_batch(in, outs, n, err));
    int bad = 0;
    for (size_t i = 0; i < n && bad < 2; ++i) {
      float point[4] = {cols[0][i], cols[1][i], cols[2][i], cols[3][i]};
      float want = reference_value(fn, point), one = test::eval1(*b, {point[0], point[1], point[2], point[3]});
      if (same_bits(out[i], want) && same_bits(one, want)) continue;
      ++bad;
      FAIL_CHECK(text << listing << "at point " << i << ": batch " << out[i] << ", one point " << one << ", want "
                      << want);
    }
  }
  INFO(squared << " programs with squared pairs, " << fused << " with fused pairs, of 150");
  CHECK(squared >= 50);
  CHECK(fused >= 120);
}

namespace {

// The definition of liveness, as a backward dataflow to a fixed point over every block and value:
// the reference backends::compute_intervals, which walks up from each use instead, must match.
std::vector<backends::Interval> intervals_by_dataflow(const ir::Function& fn, const backends::LinearOrder& lo) {
  size_t nb = lo.blocks.size(), nv = fn.next_value;
  std::map<const ir::Block*, size_t> index;
  for (size_t k = 0; k < nb; ++k) index[lo.blocks[k]] = k;
  std::vector<std::vector<bool>> live_in(nb, std::vector<bool>(nv, false));
  auto live_out = [&](size_t k) {
    std::vector<bool> out(nv, false);
    for (ir::Block* s : lo.blocks[k]->succs()) {
      for (size_t v = 0; v < nv; ++v) out[v] = out[v] || live_in[index.at(s)][v];
      for (const ir::Inst* p : s->insts)
        for (size_t a = 0; p->op == ir::Op::Phi && a < p->args.size(); ++a)
          if (p->targets[a] == lo.blocks[k]) out[p->args[a]->id] = true;
    }
    return out;
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t k = nb; k-- > 0;) {
      std::vector<bool> live = live_out(k);
      for (auto it = lo.blocks[k]->insts.rbegin(); it != lo.blocks[k]->insts.rend(); ++it) {
        if ((*it)->defines_value()) live[(*it)->id] = false;
        for (const ir::Inst* a : (*it)->args)
          if ((*it)->op != ir::Op::Phi) live[a->id] = true;
      }
      changed = changed || live != live_in[k];
      live_in[k] = live;
    }
  }
  std::vector<backends::Interval> want(nv);
  for (size_t k = 0; k < nb; ++k) {
    uint32_t at = lo.block_start[k];
    for (const ir::Inst* i : lo.blocks[k]->insts) {
      if (i->defines_value()) want[i->id] = {at, at};
      ++at;
    }
  }
  auto stretch = [&](size_t v, uint32_t at) { want[v].end = std::max(want[v].end, at); };
  for (size_t k = 0; k < nb; ++k) {
    std::vector<bool> out = live_out(k);
    for (size_t v = 0; v < nv; ++v) {
      if (out[v]) stretch(v, lo.block_end[k]);
      if (live_in[k][v]) stretch(v, lo.block_start[k]);
    }
    uint32_t at = lo.block_start[k];
    for (const ir::Inst* i : lo.blocks[k]->insts) {
      for (const ir::Inst* a : i->args)
        if (i->op != ir::Op::Phi) stretch(a->id, at);
      ++at;
    }
  }
  return want;
}

}  // namespace

TEST_CASE("vm: live intervals from walking up each use equal the dataflow fixed point") {
  std::vector<std::string> texts;
  for (const auto& e : std::filesystem::recursive_directory_iterator(FS_GOLDEN_DIR)) {
    if (e.path().extension() != ".fs") continue;
    std::ifstream in(e.path());
    std::stringstream ss;
    ss << in.rdbuf();
    texts.push_back(ss.str());
  }
  // Loops inside loops with early exits: values live around back edges and across many blocks.
  texts.push_back(
      "function FRep(x, y, z, t) {\n  var s = 0, q = x * 2;\n"
      "  for (var i = 0; i < 5; i++) {\n    var w = s + q;\n    for (var j = 0; j < i; j++) {\n"
      "      if (w > y) break;\n      if (j == 2) continue;\n      w = w + z * j;\n    }\n"
      "    s = s + w;\n    if (s > 100) return s - q;\n  }\n  return s + q;\n}\n");
  // Random nests of ifs, loops, breaks, continues and early returns over a few variables.
  std::mt19937 rng(20261205);
  auto pick = [&](unsigned n) { return static_cast<unsigned>(rng() % n); };
  const char* vars[] = {"a", "b", "c", "x", "y"};
  std::function<std::string(int, int)> statements = [&](int depth, int loops) {
    std::string out;
    for (unsigned s = 0, n = 1 + pick(4); s < n; ++s) {
      std::string v = vars[pick(5)], w = vars[pick(5)], cond = v + (pick(2) ? " < " : " > ") + w;
      switch (depth < 4 ? pick(6) : 0) {
        case 0: out += v + " = " + w + (pick(2) ? " * 0.5 + " : " - ") + vars[pick(5)] + ";\n"; break;
        case 1: out += "if (" + cond + ") {\n" + statements(depth + 1, loops) + "}\n"; break;
        case 2:
          out += "if (" + cond + ") {\n" + statements(depth + 1, loops) + "} else {\n" + statements(depth + 1, loops) +
              "}\n";
          break;
        case 3: {
          std::string i = "i" + std::to_string(depth) + "_" + std::to_string(s);
          out += "for (var " + i + " = 0; " + i + " < " + std::to_string(1 + pick(4)) + "; " + i + "++) {\n" +
              statements(depth + 1, loops + 1) + "}\n";
          break;
        }
        case 4: out += loops ? "if (" + cond + ") " + std::string(pick(2) ? "break" : "continue") + ";\n" : ""; break;
        default: out += "if (" + cond + ") return " + v + " + " + w + ";\n"; break;
      }
    }
    return out;
  };
  for (int n = 0; n < 150; ++n)
    texts.push_back("function FRep(x, y, z, t) {\nvar a = z, b = t, c = 1;\n" + statements(0, 0) +
                    "return a + b + c;\n}\n");
  size_t functions = 0, blocks = 0, mismatches = 0;
  // The golden cases include the deepest nesting the parser allows: too deep for the main thread's
  // stack under AddressSanitizer, as in the CLI and the golden runner.
  support::run_with_big_stack([&] {
    for (bool optimize : {true, false})
      for (const std::string& text : texts) {
        auto b = test::build(text, "", optimize);
        if (!b->ok) continue;  // the golden cases of diagnostics
        for (const auto& fn : b->module->functions) {
          backends::LinearOrder lo = backends::compute_intervals(*fn);
          std::vector<backends::Interval> want = intervals_by_dataflow(*fn, lo);
          ++functions, blocks += lo.blocks.size();
          for (size_t v = 0; v < want.size(); ++v)
            if (lo.has_value[v] && (lo.interval[v].start != want[v].start || lo.interval[v].end != want[v].end)) {
              ++mismatches;
              INFO("v" << v << " of " << fn->name << ": [" << lo.interval[v].start << ", " << lo.interval[v].end
                       << "] vs [" << want[v].start << ", " << want[v].end << "]\n"
                       << text);
              CHECK(false);
            }
        }
      }
  });
  CHECK(mismatches == 0);
  CHECK(functions > 400);  // 503 and 11,605 blocks today
  CHECK(blocks > 10000);
}
