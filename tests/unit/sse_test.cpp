// What is the SSE backend's own: spills, a 100,000-operation function, code that assumes bounded
// inputs, 64-bit loop counts. Everything every backend must do (each op on special values, batch
// lengths, control flow, recursion, budgets) is in backends_test.cpp.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>

#include "backends/jit_support.h"
#include "backends/sse/sse_backend.h"
#include "runtime/math/isa.h"
#include "tests/unit/backend_cases.h"
#include "tests/unit/helpers.h"

using namespace fscript;
using test::kInf;
using test::kNan;
using test::kSpecial;
using test::same;

namespace {

// Runs `body` (an FRep over x, y, z) on both backends over every pair of special values (and the
// third input cycling), in one batch, and compares every output.
void agree(const std::string& body, const std::string& prelude = "") {
  std::string text = prelude + "function FRep(x, y, z, t) { " + body + " }";
  auto vm = test::build(text, "", true, {}, "vm");
  auto sse = test::build(text, "", true, {}, "sse");
  INFO(body << "\n" << test::messages(vm->diag));
  REQUIRE(vm->ok);
  REQUIRE(sse->ok);
  std::vector<float> cols[4], o1, o2;
  auto& [x, y, z, t] = cols;
  for (float a : kSpecial)
    for (float b : kSpecial)
      x.push_back(a), y.push_back(b), z.push_back(kSpecial[(x.size() * 7) % kSpecial.size()]), t.push_back(0);
  size_t n = x.size();
  backends::RuntimeError err;
  REQUIRE(test::eval_columns(*vm->kernel, cols, o1, err));
  REQUIRE(test::eval_columns(*sse->kernel, cols, o2, err));
  int bad = 0;
  for (size_t i = 0; i < n && bad < 5; ++i)
    if (!same(o1[i], o2[i])) {
      ++bad;
      FAIL_CHECK("x=" << x[i] << " y=" << y[i] << " z=" << z[i] << ": vm " << o1[i] << ", sse " << o2[i]);
    }
}

}  // namespace

TEST_CASE("sse: more live values than registers are spilled and come back right") {
  // 24 values live at once, each used again at the end.
  std::string body;
  for (int k = 0; k < 24; ++k) body += "var a" + std::to_string(k) + " = x * " + std::to_string(k + 1) + " + y;";
  body += "var s = 0;";
  for (int k = 0; k < 24; ++k) body += "s = s + a" + std::to_string(k) + " * a" + std::to_string(23 - k) + ";";
  body += "return s + sin(z) * a3;";
  agree(body);
}

TEST_CASE("sse: a function of 100,000 operations compiles and agrees with the VM") {
  std::string body = "var s = x;";
  for (int i = 0; i < 50000; ++i)
    body += i % 3 ? "s = s * 0.99991 + y * " + std::to_string(i % 7) + ".5;" : std::string("s = max(s, z) - 0.001;");
  body += "return s;";
  std::string text = "function FRep(x, y, z, t) { " + body + " }";
  auto vm = test::build(text, "", true, {}, "vm");  // one front end run; the sse kernel from its module
  REQUIRE(vm->ok);
  std::string error;
  auto sse = sse::SseBackend().compile(*vm->module, {}, error);
  REQUIRE(sse);
  size_t ops = 0;
  for (const auto& f : vm->module->functions)
    for (const auto& blk : f->blocks) ops += blk->insts.size();
  CHECK(ops >= 100000);
  for (float x : {0.5f, -3.0f, 1e6f}) {
    float in[4] = {x, 0.25f, 0.1f, 0}, a, b;
    backends::RuntimeError err;
    REQUIRE(vm->kernel->eval(in, &a, err));
    REQUIRE(sse->eval(in, &b, err));
    CHECK(same(a, b));
  }
}

TEST_CASE("sse: code that assumes bounded inputs, and the general code for batches outside") {
  // With |x| <= 65536 the subtraction is finite, so max needs no NaN test; x = 1e30 makes it NaN.
  std::string text = "function FRep(x, y, z, t) { return max(1, x * x - x * x) + min(y, 2 * y); }";
  auto vm = test::build(text, "", true, {}, "vm");
  auto sse = test::build(text, "", true, {}, "sse");
  REQUIRE(sse->ok);
  std::string error;
  double bound = 0;
  REQUIRE_FALSE(sse::generate(*sse->module, {}, error, nullptr, nullptr, &bound).empty());
  CHECK(bound == 65536);
  auto run = [&](std::vector<float> x) {
    std::vector<float> y(x.size(), 0.5f), z(x.size()), t(x.size()), o1(x.size()), o2(x.size());
    for (size_t i = 0; i < x.size(); ++i) y[i] = i % 3 ? -x[i] : x[i];
    const float* in[4] = {x.data(), y.data(), z.data(), t.data()};
    float* out1[1] = {o1.data()};
    float* out2[1] = {o2.data()};
    backends::RuntimeError err;
    REQUIRE(vm->kernel->eval_batch(in, out1, x.size(), err));
    REQUIRE(sse->kernel->eval_batch(in, out2, x.size(), err));
    for (size_t i = 0; i < x.size(); ++i) {
      INFO("x=" << x[i] << ": vm " << o1[i] << ", sse " << o2[i]);
      CHECK(same(o1[i], o2[i]));
    }
    return o2;
  };
  run({0.5f, -2.0f, 65536.0f, -0.0f, 3.0f, 1e4f, -65536.0f});  // all in range: the bounded code
  std::vector<float> o = run({0.5f, 1e30f, 2.0f, kInf, kNan, 70000.0f, -3.0f});  // the general code
  CHECK(std::isnan(o[1]));
  CHECK(std::isnan(o[3]));
  CHECK(o[0] == 1.5f);
  float one[4] = {1e30f, 1, 0, 0}, r = 0;
  backends::RuntimeError err;
  REQUIRE(sse->kernel->eval(one, &r, err));  // one point, out of range
  CHECK(std::isnan(r));
  // Kernels where a bound would remove nothing carry no assumption.
  auto plain = test::build("function FRep(x, y, z, t) { return min(x, y / y); }", "", true, {}, "vm");
  REQUIRE_FALSE(sse::generate(*plain->module, {}, error, nullptr, nullptr, &bound).empty());
  CHECK(bound == 0);
}

TEST_CASE("sse: loop budgets beyond int32 keep exact 64-bit counts (fs_ticks_carry)") {
  // Four int32 counters, then four int64 totals, as the generated code lays them out.
  struct alignas(16) Counters {
    int32_t c[4];
    int64_t t[4];
  } s{};
  const int64_t kT = INT32_MAX - 1;
  uint64_t budget = 5'000'000'000ull;
  for (int i = 0; i < 4; ++i) s.c[i] = static_cast<int32_t>(kT + 1);  // every lane just passed the threshold
  CHECK(backends::fs_ticks_carry(s.c, budget) == 0);
  for (int i = 0; i < 4; ++i) CHECK(s.t[i] + s.c[i] == kT + 1);  // nothing lost
  // The next trigger (counter > kT) comes when the lane passes min(budget, ticks + kT).
  int64_t until_next = kT + 1 - s.c[0];
  CHECK(until_next == kT + 1);
  s.c[0] += static_cast<int32_t>(until_next - 1);  // the lane at ticks = 2 * kT + 1
  CHECK(backends::fs_ticks_carry(s.c, budget) == 0);
  int64_t ticks = s.t[0] + s.c[0];
  CHECK(ticks == 2 * kT + 1);
  // Now less than kT remains: the counter restarts so it passes kT exactly past the budget.
  int64_t remaining = static_cast<int64_t>(budget) - ticks;
  CHECK(kT - s.c[0] == remaining);
  s.c[0] += static_cast<int32_t>(remaining);  // exactly at the budget: still fine
  CHECK(s.t[0] + s.c[0] == static_cast<int64_t>(budget));
  s.c[0] += 1;  // one past: over
  CHECK(backends::fs_ticks_carry(s.c, budget) == 1);
  // A kernel with such a budget still runs and counts ordinary loops.
  backends::Budgets big;
  big.max_loop_iterations = budget;
  auto b = test::build("function FRep(x, y, z, t) { var s = 0; for (var i = 0; i < x; i++) s += i; return s; }", "",
                       true, big, "sse");
  REQUIRE(b->ok);
  CHECK(test::eval1(*b, {100}) == 4950.0f);
}

TEST_CASE("sse: sin and cos of one value share their reduction, bit for bit with the VM") {
  // Pairs in either order, with inf/NaN/huge lanes (the batch functions out of line, both of a pair).
  agree("return sin(x) * cos(x) + cos(y) * sin(y) + sin(z * 2) - cos(z * 2);");
  // A pair's second result defined early stays live across many values (spilled and reloaded).
  std::string body = "var c = cos(x);";
  for (int k = 0; k < 20; ++k) body += "var a" + std::to_string(k) + " = sin(y * " + std::to_string(k + 1) + ") + x;";
  body += "var s = sin(x);";
  for (int k = 0; k < 20; ++k) body += "s = s + a" + std::to_string(k) + " * cos(y * " + std::to_string(k + 1) + ");";
  agree(body + "return s * c;");
  // Only within a block: a cos under a condition is not made with the sin before it.
  agree("var s = sin(x); var n = 0; for (var i = 0; i < min(y, 3); i++) { n = n + cos(x); } return s + n;");
  agree("var s = sin(x); if (y > 0) { s = s + cos(x); } return s + cos(x);");

  // One reduction per value: the gyroid's six calls on three values convert to double three times.
  std::string text = "function FRep(x, y, z, t) { return sin(x) * cos(y) + sin(y) * cos(z) + sin(z) * cos(x); }";
  auto vm = test::build(text, "", true, {}, "vm");
  REQUIRE(vm->ok);
  std::string error, listing;
  REQUIRE(!sse::generate(*vm->module, {}, error, &listing).empty());
  size_t conversions = 0;
  for (size_t at = listing.find("cvtps2pd"); at != std::string::npos; at = listing.find("cvtps2pd", at + 1))
    ++conversions;
  CHECK(conversions == 3 * 2);  // two per reduction: four lanes in two pairs of doubles
  // The one-point path (four lanes of one point) gives the batch's bits.
  auto sse = test::build(text, "", true, {}, "sse");
  REQUIRE(sse->ok);
  for (float v : kSpecial) {
    float in[4] = {v, 0.5f * v, -v, 0}, a, b;
    backends::RuntimeError err;
    REQUIRE(vm->kernel->eval(in, &a, err));
    REQUIRE(sse->kernel->eval(in, &b, err));
    CHECK(same(a, b));
  }
}

// Kernel::eval runs code made for four equal lanes (inputs and outputs as plain arrays, the
// argument reduction of sin/cos for one pair of lanes): every point, special values included,
// gives the VM's bits, through the general code for points outside the bounded code's range.
TEST_CASE("sse: the one-point code agrees with the VM, and reduces sin/cos for one pair of lanes") {
  std::string text =
      "function FRep(x, y, z, t) { return sin(x) * cos(x) + sin(y * 3) + cos(z) + (t > 0 ? tan(t) : 1); }";
  auto vm = test::build(text);
  REQUIRE(vm->ok);
  std::string error, batch_asm, point_asm;
  auto k = sse::SseBackend().compile(*vm->module, {}, error);
  REQUIRE(k);
  for (float a : kSpecial)
    for (float b : kSpecial) {
      float in[4] = {a, b, a * 0.5f - b, b - 1}, r0 = 0, r1 = 0;
      backends::RuntimeError e0, e1;
      INFO("x = " << a << ", y = " << b);
      REQUIRE(vm->kernel->eval(in, &r0, e0));
      REQUIRE(k->eval(in, &r1, e1));
      CHECK(same(r0, r1));
    }
  double bound = 0;
  REQUIRE(!sse::generate(*vm->module, {}, error, &batch_asm, nullptr, &bound).empty());
  REQUIRE(!sse::generate(*vm->module, {}, error, &point_asm, nullptr, &bound, true).empty());
  auto count = [](const std::string& s, const std::string& w) {
    size_t n = 0;
    for (size_t p = s.find(w); p != std::string::npos; p = s.find(w, p + 1)) ++n;
    return n;
  };
  CHECK(count(batch_asm, "cvtps2pd") == 2 * count(point_asm, "cvtps2pd"));
  CHECK(count(point_asm, "cvtps2pd") >= 3);
}

// A straight-line kernel runs eight lanes in ymm registers where the CPU has AVX2 (four with
// FSCRIPT_ISA=base, and wherever a loop, an array, a global or a user function call is in it):
// every such op on special values, spills of 32-byte slots, and batches of every length around
// whole groups of eight give the VM's bits.
TEST_CASE("sse: straight-line kernels run eight lanes and agree with the VM") {
  bool avx = math::active_isa() != math::Isa::Base;
  auto lanes_of = [](const std::string& body) {
    auto vm = test::build("function FRep(x, y, z, t) { " + body + " }", "", true, {}, "vm");
    REQUIRE(vm->ok);
    std::string error;
    auto k = sse::SseBackend().compile(*vm->module, {}, error);
    REQUIRE(k);
    return dynamic_cast<const sse::SseKernel&>(*k).lanes();
  };
  const char* wide[] = {
      "return (x + y) * z - x / y;",
      "return -x + abs(y) * sqrt(abs(z));",
      "return floor(x) + ceil(y) * 2 + round(z) - sign(x - y);",
      "return min(x, y) + max(y, z) - clamp(x, y, z) + min(x, 1) + max(2, y);",
      "return (x < y) + (x <= z) * 2 + (y > z) * 4 + (x >= y) * 8 + (x == z) * 16 + (y != z) * 32;",
      "return !x + (y && z) + (x || 0) + (x ? y : z);",
  };
  for (const char* body : wide) {
    CHECK(lanes_of(body) == (avx ? 8u : 4u));
    agree(body);
  }
  // 24 values live at once: spilled to 32-byte slots and read back from them.
  std::string spills;
  for (int k = 0; k < 24; ++k) spills += "var a" + std::to_string(k) + " = x * " + std::to_string(k + 1) + " + y;";
  spills += "var s = 0;";
  for (int k = 0; k < 24; ++k) spills += "s = s + a" + std::to_string(k) + " * a" + std::to_string(23 - k) + ";";
  spills += "return s - z;";
  CHECK(lanes_of(spills) == (avx ? 8u : 4u));
  agree(spills);
  // Runtime calls (four doubles per ymm register in the inline sin/cos, eight lanes to the batch
  // functions) run wide too, out-of-range lanes through the out-of-line path.
  for (const char* body :
       {"return sin(x) * cos(x) + cos(y) * sin(y) + sin(z * 2) - cos(z * 2);", "return pow(x, y) + exp(z);",
        "return x % y + atan2(y, z);", "return sin(x) + tan(y) * cos(z * 1e10);"}) {
    CHECK(lanes_of(body) == (avx ? 8u : 4u));
    agree(body);
  }
  for (const char* body : {"var s = 0; for (var i = 0; i < 3; i++) { s = s + x; } return s;",
                           "var a = new Array(2); a[1] = sin(x); return a[1];"})
    CHECK(lanes_of(body) == 4u);

  // Batches of 1 to 19 points: the tail of a batch is a padded group of eight.
  std::string text = "function FRep(x, y, z, t) { return max(sqrt(x * x + y * y) - 0.5, z * t); }";
  auto vm = test::build(text, "", true, {}, "vm");
  auto sse = test::build(text, "", true, {}, "sse");
  REQUIRE(vm->ok);
  REQUIRE(sse->ok);
  for (size_t n = 1; n < 20; ++n) {
    std::vector<float> cols[4], o1, o2;
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 4; ++c) cols[c].push_back(kSpecial[(i * 5 + static_cast<size_t>(c) * 3) % kSpecial.size()]);
    backends::RuntimeError err;
    REQUIRE(test::eval_columns(*vm->kernel, cols, o1, err));
    REQUIRE(test::eval_columns(*sse->kernel, cols, o2, err));
    REQUIRE(o2.size() == n);
    for (size_t i = 0; i < n; ++i) {
      INFO("n = " << n << ", point " << i);
      CHECK(same(o1[i], o2[i]));
    }
  }
}
