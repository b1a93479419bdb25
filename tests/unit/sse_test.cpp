// The SSE backend against the VM, value for value: every operation it compiles on special and
// ordinary inputs (bit-identical, or NaN on both), batches of every length (the tail of one to
// three points), spills, many kernels compiled and freed, and clear refusals for what this stage
// does not compile yet.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>

#include "backends/jit_support.h"
#include "backends/sse/sse_backend.h"
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
  std::vector<float> x, y, z, t;
  for (float a : kSpecial)
    for (float b : kSpecial) x.push_back(a), y.push_back(b), z.push_back(kSpecial[(x.size() * 7) % kSpecial.size()]), t.push_back(0);
  size_t n = x.size();
  std::vector<float> o1(n), o2(n);
  const float* in[4] = {x.data(), y.data(), z.data(), t.data()};
  float* out1[1] = {o1.data()};
  float* out2[1] = {o2.data()};
  backend::RuntimeError err;
  REQUIRE(vm->kernel->eval_batch(in, out1, n, err));
  REQUIRE(sse->kernel->eval_batch(in, out2, n, err));
  int bad = 0;
  for (size_t i = 0; i < n && bad < 5; ++i)
    if (!same(o1[i], o2[i])) {
      ++bad;
      FAIL_CHECK("x=" << x[i] << " y=" << y[i] << " z=" << z[i] << ": vm " << o1[i] << ", sse " << o2[i]);
    }
}

}  // namespace

TEST_CASE("sse: arithmetic, min/max, comparisons and selects are bit-identical to the VM") {
  for (const char* body : test::kArithmeticBodies) agree(body);
}

TEST_CASE("sse: transcendentals and noise agree with the VM (the same runtime/math functions)") {
  for (const char* body : test::kTranscendentalBodies) agree(body);
}

TEST_CASE("sse: more live values than registers are spilled and come back right") {
  // 24 values live at once, each used again at the end.
  std::string body;
  for (int k = 0; k < 24; ++k) body += "var a" + std::to_string(k) + " = x * " + std::to_string(k + 1) + " + y;";
  body += "var s = 0;";
  for (int k = 0; k < 24; ++k) body += "s = s + a" + std::to_string(k) + " * a" + std::to_string(23 - k) + ";";
  body += "return s + sin(z) * a3;";
  agree(body);
}

TEST_CASE("sse: every batch length, the one-point call, and several outputs") {
  auto vm = test::build("x = u * 2 + w; y = sin(v) - u; z = min(u, v);", "", true, {}, "vm");
  auto sse = test::build("x = u * 2 + w; y = sin(v) - u; z = min(u, v);", "", true, {}, "sse");
  REQUIRE(vm->ok);
  REQUIRE(sse->ok);
  REQUIRE(sse->kernel->num_outputs() == 3);
  for (size_t n = 0; n <= 9; ++n) {
    std::vector<float> u(n), v(n), w(n), t(n, 0);
    for (size_t i = 0; i < n; ++i) u[i] = 0.3f * i, v[i] = 1.0f - 0.2f * i, w[i] = -0.1f * i;
    std::vector<std::vector<float>> a(3, std::vector<float>(n + 1, 42)), b = a;
    const float* in[4] = {u.data(), v.data(), w.data(), t.data()};
    float* oa[3] = {a[0].data(), a[1].data(), a[2].data()};
    float* ob[3] = {b[0].data(), b[1].data(), b[2].data()};
    backend::RuntimeError err;
    REQUIRE(vm->kernel->eval_batch(in, oa, n, err));
    REQUIRE(sse->kernel->eval_batch(in, ob, n, err));
    INFO("n = " << n);
    CHECK(a == b);  // including the untouched element after the batch
  }
  float in[4] = {0.5f, 0.25f, 2.0f, 0}, o1[3], o2[3];
  backend::RuntimeError err;
  REQUIRE(vm->kernel->eval(in, o1, err));
  REQUIRE(sse->kernel->eval(in, o2, err));
  for (int k = 0; k < 3; ++k) CHECK(same(o1[k], o2[k]));
}

TEST_CASE("sse: a partial last group runs only the points given (errors that depend on the inputs)") {
  backend::Budgets budgets = test::input_dependent_budgets();
  for (const char* text : test::kInputDependentErrors) {
    INFO(text);
    auto vm = test::build(text, "", true, budgets, "vm");
    auto sse = test::build(text, "", true, budgets, "sse");
    REQUIRE(sse->ok);
    CHECK(test::partial_group_mismatch(*vm->kernel, *sse->kernel, 9) == "");
  }
}

TEST_CASE("sse: many kernels compiled and freed") {
  for (int i = 0; i < 300; ++i) {
    auto b = test::build("function FRep(x, y, z, t) { return x * " + std::to_string(i) + " + sin(y); }", "", true, {}, "sse");
    REQUIRE(b->ok);
    CHECK(test::eval1(*b, {1, 0, 0}) == static_cast<float>(i));
  }
}

TEST_CASE("sse: branches and loops run masked, lane by lane as the VM runs them") {
  for (const char* body : {
           "if (x < 0) { return -x; } else { return x * 2; }",
           "var s = 0; for (var i = 0; i < abs(x) && i < 40; i++) s = s + i * y; return s;",
           "var i = 0; while (true) { if (i * i > abs(x) * 10) break; i++; if (i > 50) break; } return i;",
           "var s = 0; for (var i = 0; i < 8; i++) { if (i % 2 == 0) continue; s = s + i; } return s + x;",
           "var c = 0; for (var i = 0; i < 5; i++) for (var j = 0; j < 5; j++) { if (j > i + x) break; c += 1; } return c;",
           "var k = floor(clamp(x, -3, 30)); var a = 0; var b = 1; while (k > 0) { var t = a + b; a = b; b = t; k -= 1; } return a;",
           "var s = 0; do { s = s + 1; } while (s < y && s < 20); return s;",
           "if (x) return sin(y); else if (y) return cos(x); return z;"})
    agree(body);
}

TEST_CASE("sse: globals start as NaN in every evaluation and follow the lanes' paths") {
  agree("g = 0; if (x > 0) g = y; return g + 1;");
  agree("if (x > 0) h = 1; return h;");  // NaN where x <= 0: the global was never set
}

TEST_CASE("sse: the loop budget stops a runaway loop with the VM's message and line") {
  backend::Budgets small;
  small.max_loop_iterations = 1000;
  const char* text = "function FRep(x, y, z, t) {\n  var s = 0;\n  while (s < x) s = s + 1;\n  return s;\n}";
  auto b = test::build(text, "", true, small, "sse");
  REQUIRE(b->ok);
  CHECK(test::eval1(*b, {500}) == 500.0f);
  std::vector<float> xs = {1, 2, 5000, 3, 4}, zero(5, 0), out(5);
  const float* in[4] = {xs.data(), zero.data(), zero.data(), zero.data()};
  float* outs[1] = {out.data()};
  backend::RuntimeError err;
  CHECK(!b->kernel->eval_batch(in, outs, 5, err));
  CHECK(err.message == "loop iteration budget exceeded: more than 1000 iterations in one evaluation");
  CHECK(err.line == 3);
}

TEST_CASE("sse: arrays per lane, with the VM's results and errors") {
  agree("var a = new Array(4); for (var i = 0; i < 4; i++) a[i] = x * i; return a[1] + a[3] - a.length;");
  agree("var a = new Array(3); a[0] = 1; if (x > 0) a[2] = y; return a[2] + a[0];");
  // Errors: an index out of range in one lane stops the batch with the VM's message and line.
  const char* text = "function FRep(x, y, z, t) {\n  var a = new Array(3);\n  return a[x];\n}";
  auto vm = test::build(text, "", true, {}, "vm");
  auto sse = test::build(text, "", true, {}, "sse");
  REQUIRE(sse->ok);
  std::vector<float> xs = {0, 1, 2, 7, 1}, zero(5, 0), out(5);
  const float* in[4] = {xs.data(), zero.data(), zero.data(), zero.data()};
  float* outs[1] = {out.data()};
  backend::RuntimeError e1, e2;
  CHECK(!vm->kernel->eval_batch(in, outs, 5, e1));
  CHECK(!sse->kernel->eval_batch(in, outs, 5, e2));
  CHECK(e2.message == e1.message);
  CHECK(e2.message == "index 7 is out of range for array 'a' of 3 elements");
  CHECK(e2.line == 3);
  backend::Budgets small;
  small.max_array_elements = 10;
  auto big = test::build("function FRep(x, y, z, t) { var a = new Array(x); return a.length; }", "", true, small, "sse");
  REQUIRE(big->ok);
  CHECK(test::eval1(*big, {10}) == 10.0f);
  float p[4] = {11, 0, 0, 0}, o[1];
  backend::RuntimeError e3;
  CHECK(!big->kernel->eval(p, o, e3));
  CHECK(e3.message.find("sizes must be whole numbers from 0 to the budget of 10") != std::string::npos);
}

TEST_CASE("sse: recursive functions run packed under the caller's lanes, with the VM's budgets") {
  for (const char* body : test::kRecursiveBodies)
    agree(std::string(test::kRecursiveSetup) + body, test::kRecursivePrelude);
}

TEST_CASE("sse: the call depth budget, not the caller's stack, decides how deep recursion goes") {
  std::string text = "function down(n) { if (n <= 0) return 0; return 1 + down(n - 1); }\n"
                     "function FRep(x, y, z, t) { return down(x); }";
  backend::Budgets budgets;
  budgets.max_call_depth = 50;
  auto vm = test::build(text, "", true, budgets, "vm");
  auto sse = test::build(text, "", true, budgets, "sse");
  REQUIRE(sse->ok);
  CHECK(test::eval1(*vm, {49}) == 49.0f);
  CHECK(test::eval1(*sse, {49}) == 49.0f);
  float in[4] = {51, 0, 0, 0}, out = 0;
  backend::RuntimeError e1, e2;
  CHECK_FALSE(vm->kernel->eval(in, &out, e1));
  CHECK_FALSE(sse->kernel->eval(in, &out, e2));
  CHECK(e2.message == e1.message);
  CHECK(e2.line == e1.line);
  // 99,000 nested calls within a budget of 100,000: the budget decides, not the caller's stack.
  budgets.max_call_depth = backend::kCallDepthCeiling;
  auto deep = test::build(text, "", true, budgets, "sse");
  REQUIRE(deep->ok);
  CHECK(test::deep_recursion_mismatch(*deep->kernel) == "");
  // One more than the budget: the budget's error, on every stack.
  budgets.max_call_depth = 1000;
  auto capped = test::build(text, "", true, budgets, "sse");
  for (size_t stack : {size_t{1} << 20, size_t{1} << 30}) {
    backend::RuntimeError e4;
    bool ok = true;
    test::on_thread_with_stack(stack, [&] {
      float p[4] = {1001, 0, 0, 0}, r = 0;
      ok = capped->kernel->eval(p, &r, e4);
    });
    CHECK_FALSE(ok);
    CHECK(e4.message == "call depth budget exceeded: more than 1000 nested calls");
  }
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
    backend::RuntimeError err;
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
    backend::RuntimeError err;
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
  backend::RuntimeError err;
  REQUIRE(sse->kernel->eval(one, &r, err));  // one point, out of range
  CHECK(std::isnan(r));
  // Kernels where a bound would remove nothing carry no assumption.
  auto plain = test::build("function FRep(x, y, z, t) { return min(x, 1 / y); }", "", true, {}, "vm");
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
  CHECK(backend::fs_ticks_carry(s.c, budget) == 0);
  for (int i = 0; i < 4; ++i) CHECK(s.t[i] + s.c[i] == kT + 1);  // nothing lost
  // The next trigger (counter > kT) comes when the lane passes min(budget, ticks + kT).
  int64_t until_next = kT + 1 - s.c[0];
  CHECK(until_next == kT + 1);
  s.c[0] += static_cast<int32_t>(until_next - 1);  // the lane at ticks = 2 * kT + 1
  CHECK(backend::fs_ticks_carry(s.c, budget) == 0);
  int64_t ticks = s.t[0] + s.c[0];
  CHECK(ticks == 2 * kT + 1);
  // Now less than kT remains: the counter restarts so it passes kT exactly past the budget.
  int64_t remaining = static_cast<int64_t>(budget) - ticks;
  CHECK(kT - s.c[0] == remaining);
  s.c[0] += static_cast<int32_t>(remaining);  // exactly at the budget: still fine
  CHECK(s.t[0] + s.c[0] == static_cast<int64_t>(budget));
  s.c[0] += 1;  // one past: over
  CHECK(backend::fs_ticks_carry(s.c, budget) == 1);
  // A kernel with such a budget still runs and counts ordinary loops.
  backend::Budgets big;
  big.max_loop_iterations = budget;
  auto b = test::build("function FRep(x, y, z, t) { var s = 0; for (var i = 0; i < x; i++) s += i; return s; }", "",
                       true, big, "sse");
  REQUIRE(b->ok);
  CHECK(test::eval1(*b, {100}) == 4950.0f);
}
