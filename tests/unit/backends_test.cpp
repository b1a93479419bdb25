// Every backend the build has, by construction: the list comes from backends::available_backends()
// (the llvm backend at each vector width), so a new backend is tested here the day it is
// registered. Every pure operation of the op table on special values against the reference
// evaluator, and the shared program bodies against the VM, bit for bit.
#include <catch2/catch.hpp>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <thread>

#include "backends/row_split_kernel.h"
#include "backends/runtime_errors.h"
#include "backends/sse/sse_backend.h"
#include "backends/tiered/tiered.h"
#include "ir/eval.h"
#include "ir/text.h"
#include "tests/unit/backend_cases.h"
#include "runtime/support/cancel.h"
#include "tests/unit/helpers.h"
#include "backends/llvm_module.h"
#ifdef __EMSCRIPTEN__
#include "backends/wasm/wasm_backend.h"
#include "backends/wasm/wasm_compile.h"
#endif

using namespace fscript;
using test::same;

namespace {

struct Variant {
  std::string name;  // "vm", "sse", "llvm/8"...
  std::function<std::unique_ptr<backends::Kernel>(const ir::Module&, const backends::Budgets&, std::string&)> compile;
};

// One entry per backend this binary has; a backend with its own shapes (llvm's widths) has one each.
std::vector<Variant> variants() {
  std::vector<Variant> out;
  for (const std::string& name : backends::available_backends()) {
    if (name == "llvm") {
#ifdef FS_HAVE_LLVM
      for (uint32_t w : {4u, 8u, 16u})
        out.push_back(
            {"llvm/" + std::to_string(w), [w](const ir::Module& m, const backends::Budgets& b, std::string& e) {
               const backends::LlvmModule* lm = backends::llvm_module(&e);
               return lm ? lm->backend(w)->compile(m, b, e) : nullptr;
             }});
#endif
      continue;
    }
    out.push_back({name, [name](const ir::Module& m, const backends::Budgets& b, std::string& e) {
                     return backends::make_backend(name)->compile(m, b, e);
                   }});
  }
  // The auto backend, made to switch from the VM to native code after 5 points: in the middle of
  // the first batch (so one batch runs on both tiers).
  out.push_back({"auto", [](const ir::Module& m, const backends::Budgets& b, std::string& e) {
                   setenv("FSCRIPT_AUTO_SWITCH_AFTER", "5", 1);
                   auto k = backends::make_backend("auto")->compile(m, b, e);
                   unsetenv("FSCRIPT_AUTO_SWITCH_AFTER");
                   return k;
                 }});
  return out;
}

std::unique_ptr<backends::Kernel> compile_on(const Variant& v, const ir::Module& m, const backends::Budgets& b = {}) {
  std::string error;
  auto k = v.compile(m, b, error);
  INFO(v.name << ": " << error);
  REQUIRE(k);
  return k;
}

// Every combination of `vals` for `arity` inputs, as columns, plus one ordinary point so the batch
// length is no multiple of any width (padded tails run too).
std::vector<std::vector<float>> combinations(const std::vector<float>& vals, int arity) {
  size_t combos = 1;
  for (int a = 0; a < arity; ++a) combos *= vals.size();
  std::vector<std::vector<float>> cols(static_cast<size_t>(std::max(arity, 1)), std::vector<float>(combos + 1, 0.25f));
  for (size_t c = 0; c < combos; ++c)
    for (size_t a = 0, r = c; a < static_cast<size_t>(arity); ++a, r /= vals.size()) cols[a][c] = vals[r % vals.size()];
  return cols;
}

std::vector<float> run(const backends::Kernel& k, const std::vector<std::vector<float>>& cols) {
  size_t n = cols[0].size();
  std::vector<const float*> in;
  for (const auto& c : cols) in.push_back(c.data());
  std::vector<float> out(n);
  float* outs[] = {out.data()};
  backends::RuntimeError err;
  INFO(err.message);
  REQUIRE(k.eval_batch(in.data(), outs, n, err));
  return out;
}

// `body` (an FRep over x, y, z) on every backend against the VM over every pair of special values.
void agree_with_vm(const std::string& body, const std::string& prelude = "") {
  std::string text = prelude + "function FRep(x, y, z, t) { " + body + " }";
  auto vm = test::build(text, "", true, {}, "vm");
  INFO(body << "\n" << test::messages(vm->diag));
  REQUIRE(vm->ok);
  auto cols = combinations(test::kSpecial, 2);
  cols.push_back(cols[0]);
  cols.push_back(std::vector<float>(cols[0].size(), 0.0f));
  for (size_t i = 0; i < cols[2].size(); ++i) cols[2][i] = test::kSpecial[(i * 7) % test::kSpecial.size()];
  std::vector<float> want = run(*vm->kernel, cols);
  for (const Variant& v : variants()) {
    std::vector<float> got = run(*compile_on(v, *vm->module), cols);
    int bad = 0;
    for (size_t i = 0; i < want.size() && bad < 5; ++i)
      if (!same(want[i], got[i])) {
        ++bad;
        FAIL_CHECK(v.name << " x=" << cols[0][i] << " y=" << cols[1][i] << " z=" << cols[2][i] << ": vm " << want[i]
                          << ", " << v.name << " " << got[i]);
      }
  }
}

}  // namespace

TEST_CASE("backends: the list covers every backend this binary has") {
  std::vector<std::string> names;
  for (const Variant& v : variants()) names.push_back(v.name.substr(0, v.name.find('/')));
  for (const std::string& b : backends::available_backends())
    CHECK(std::find(names.begin(), names.end(), b) != names.end());
#ifdef FS_HAVE_LLVM
  CHECK(std::find(names.begin(), names.end(), "llvm") != names.end());
#endif
#ifdef FS_HAVE_SSE
  CHECK(std::find(names.begin(), names.end(), "sse") != names.end());
#endif
#ifdef __EMSCRIPTEN__
  CHECK(std::find(names.begin(), names.end(), "wasm") != names.end());
#endif
}

TEST_CASE("backends: every pure op of the op table matches ir::eval_pure on special values, on every backend") {
  const float inf = test::kInf, nan = test::kNan;
  const std::vector<float> vals = {0.0f,
                                   -0.0f,
                                   1.0f,
                                   -1.0f,
                                   0.5f,
                                   -2.5f,
                                   inf,
                                   -inf,
                                   nan,
                                   1e-38f,
                                   1e-45f,
                                   3e38f,
                                   static_cast<float>(M_PI / 2),
                                   static_cast<float>(2 * M_PI),
                                   100.0f,
                                   -100.0f};
  int swept = 0;
  for (int k = 0; k < ir::kNumOps; ++k) {
    ir::Op op = static_cast<ir::Op>(k);
    if (!ir::has_flag(op, ir::Pure) || op == ir::Op::Const || op == ir::Op::Param) continue;
    ++swept;
    int arity = ir::op_info(op).arity;
    std::string text = "fn @kernel(" + std::to_string(std::max(arity, 1)) + ") -> 1 kernel {\nb0:\n", args;
    for (int a = 0; a < std::max(arity, 1); ++a)
      text += "  v" + std::to_string(a) + " = param " + std::to_string(a) + "\n";
    for (int a = 0; a < arity; ++a) args += (a ? ", v" : " v") + std::to_string(a);
    text += "  v9 = " + std::string(ir::mnemonic(op)) + args + "\n  ret v9\n}\n";
    std::string err;
    auto m = ir::read(text, err);
    INFO(ir::mnemonic(op) << ": " << err);
    REQUIRE(m);
    auto cols = combinations(vals, arity);
    bool runtime_call = ir::has_flag(op, ir::CallsRuntime);
    for (const Variant& v : variants()) {
      std::vector<float> out = run(*compile_on(v, *m), cols);
      int bad = 0;
      for (size_t c = 0; c < out.size(); ++c) {
        float a[3] = {0, 0, 0}, want;
        for (int i = 0; i < arity; ++i) a[i] = cols[static_cast<size_t>(i)][c];
        REQUIRE(ir::eval_pure(op, a, want));
        // Bit for bit, except that a zero's sign and a runtime function's last few ulps are the
        // math library's (the batch twins are within 4 ulp of the scalar definition).
        bool ok = same(out[c], want) || (out[c] == 0 && want == 0);
        if (!ok && runtime_call && std::isfinite(want) && std::isfinite(out[c]))
          ok = std::fabs(out[c] - want) <= 4 * std::fabs(std::nextafter(want, inf) - want);
        if (!ok && bad++ < 3)
          FAIL_CHECK(v.name << " " << ir::mnemonic(op) << "(" << a[0] << ", " << a[1] << ", " << a[2]
                            << ") = " << out[c] << ", want " << want);
      }
    }
  }
  CHECK(swept >= 40);  // the loop saw the table (40 pure value ops today)
}

TEST_CASE("backends: arithmetic, min/max, comparisons and selects are bit-identical to the VM") {
  for (const char* body : test::kArithmeticBodies) agree_with_vm(body);
}

TEST_CASE("backends: transcendentals and noise agree with the VM (the same runtime/math functions)") {
  for (const char* body : test::kTranscendentalBodies) agree_with_vm(body);
}

TEST_CASE("backends: branches, loops, globals and arrays run masked, lane by lane as the VM runs them") {
  for (const char* body : test::kControlFlowBodies) agree_with_vm(body);
  agree_with_vm("g = x; if (y > 0) g = g + 1; return g * 2;", "var g = 0;\n");
}

TEST_CASE("backends: recursive functions run under the caller's lanes, with the VM's results") {
  for (const char* body : test::kRecursiveBodies)
    agree_with_vm(std::string(test::kRecursiveSetup) + body, test::kRecursivePrelude);
}

TEST_CASE("backends: a partial last group runs only the points given (errors that depend on the inputs)") {
  backends::Budgets budgets = test::input_dependent_budgets();
  for (const char* text : test::kInputDependentErrors) {
    INFO(text);
    auto vm = test::build(text, "", true, budgets, "vm");
    REQUIRE(vm->ok);
    for (const Variant& v : variants()) {
      INFO(v.name);
      CHECK(test::partial_group_mismatch(*vm->kernel, *compile_on(v, *vm->module, budgets), 17) == "");
    }
  }
}

// Found by the backend_diff fuzz target: the VM said "index -nan", the SSE backend "index nan".
TEST_CASE("backends: a NaN in a runtime error is 'nan' on every backend, whatever its sign") {
  CHECK(backends::errors::array_index("a", -NAN, 0) == "index nan is out of range for array 'a' of 0 elements");
  CHECK(backends::errors::array_index("a", NAN, 3) == "index nan is out of range for array 'a' of 3 elements");
  auto vm = test::build("function FRep(x, y, z, t) { var a = new Array(0); return a[-log(x - 1)]; }");
  REQUIRE(vm->ok);
  for (const Variant& v : variants()) {
    INFO(v.name);
    auto k = compile_on(v, *vm->module);
    std::vector<float> in(k->num_inputs(), 0.0f), out(k->num_outputs());
    backends::RuntimeError err;
    CHECK_FALSE(k->eval(in.data(), out.data(), err));
    CHECK(err.message == "index nan is out of range for array 'a' of 0 elements");
  }
}

TEST_CASE("backends: many kernels compiled and freed") {
  for (const Variant& v : variants()) {
    for (int i = 0; i < 100; ++i) {
      auto b = test::build("function FRep(x, y, z, t) { return x * " + std::to_string(i) + " + sin(y); }");
      REQUIRE(b->ok);
      auto k = compile_on(v, *b->module);
      float in[4] = {1, 0, 0, 0}, out = 0;
      backends::RuntimeError err;
      REQUIRE(k->eval(in, &out, err));
      CHECK(out == static_cast<float>(i));
    }
  }
}

TEST_CASE("backends: every batch length, the one-point call, and several outputs") {
  auto vm = test::build("x = u * 2 + w; y = sin(v) - u; z = min(u, v);");
  REQUIRE(vm->ok);
  for (const Variant& v : variants()) {
    auto k = compile_on(v, *vm->module);
    REQUIRE(k->num_outputs() == 3);
    for (size_t n = 0; n <= 17; ++n) {
      std::vector<float> u(n), vv(n), w(n), t(n, 0);
      for (size_t i = 0; i < n; ++i) u[i] = 0.3f * i, vv[i] = 1.0f - 0.2f * i, w[i] = -0.1f * i;
      std::vector<std::vector<float>> a(3, std::vector<float>(n + 1, 42)), b = a;
      const float* in[4] = {u.data(), vv.data(), w.data(), t.data()};
      float* oa[3] = {a[0].data(), a[1].data(), a[2].data()};
      float* ob[3] = {b[0].data(), b[1].data(), b[2].data()};
      backends::RuntimeError err;
      REQUIRE(vm->kernel->eval_batch(in, oa, n, err));
      REQUIRE(k->eval_batch(in, ob, n, err));
      INFO(v.name << " n = " << n);
      CHECK(a == b);  // including the untouched element after the batch
    }
    float in[4] = {0.5f, 0.25f, 2.0f, 0}, o1[3], o2[3];
    backends::RuntimeError err;
    REQUIRE(vm->kernel->eval(in, o1, err));
    REQUIRE(k->eval(in, o2, err));
    for (int j = 0; j < 3; ++j) CHECK(same(o1[j], o2[j]));
  }
}

// Kernel::eval is code of its own on the JIT backends (llvm: one lane, sse: four equal lanes, both
// reading the point's arrays): recursion, arrays, loops and a loop-budget trap as on the VM.
TEST_CASE("backends: the one-point call runs recursion, arrays, loops and budgets as the VM does") {
  for (const char* body : test::kRecursiveBodies) {
    auto vm = test::build(std::string(test::kRecursivePrelude) + "function FRep(x, y, z, t) { " +
                          test::kRecursiveSetup + body + " }");
    REQUIRE(vm->ok);
    for (const Variant& v : variants()) {
      auto k = compile_on(v, *vm->module);
      for (float x : test::kSpecial) {
        float in[4] = {x, 3.0f, 0.5f, 0}, r0 = 0, r1 = 0;
        backends::RuntimeError e0, e1;
        INFO(v.name << ": " << body << " x = " << x);
        REQUIRE(vm->kernel->eval(in, &r0, e0));
        REQUIRE(k->eval(in, &r1, e1));
        CHECK(same(r1, r0));
      }
    }
  }
  backends::Budgets budgets;
  budgets.max_loop_iterations = 100;
  auto vm = test::build("function FRep(x, y, z, t) {\n  var s = 0;\n  while (s < x) s = s + 1;\n  return s;\n}", "",
                        true, budgets);
  REQUIRE(vm->ok);
  float small[4] = {50, 0, 0, 0}, big[4] = {1000, 0, 0, 0}, r = 0;
  backends::RuntimeError e0;
  REQUIRE_FALSE(vm->kernel->eval(big, &r, e0));
  for (const Variant& v : variants()) {
    INFO(v.name);
    auto k = compile_on(v, *vm->module, budgets);
    backends::RuntimeError e1;
    REQUIRE(k->eval(small, &r, e1));
    CHECK(r == 50.0f);
    REQUIRE_FALSE(k->eval(big, &r, e1));
    CHECK(e1.message == e0.message);
    CHECK(e1.line == e0.line);
  }
}

TEST_CASE("backends: globals start as NaN in every evaluation and follow the lanes' paths") {
  agree_with_vm("g = 0; if (x > 0) g = y; return g + 1;");
  agree_with_vm("if (x > 0) h = 1; return h;");  // NaN where x <= 0: the global was never set
}

// The first error of a batch, on `k`, as "message @ line:col" ("" when the batch ran).
static std::string batch_error(const backends::Kernel& k, std::vector<float> xs) {
  std::vector<float> zero(xs.size(), 0), out(xs.size());
  const float* in[4] = {xs.data(), zero.data(), zero.data(), zero.data()};
  float* outs[1] = {out.data()};
  backends::RuntimeError err;
  if (k.eval_batch(in, outs, xs.size(), err)) return "";
  return err.message + " @ " + std::to_string(err.line) + ":" + std::to_string(err.col);
}

TEST_CASE("backends: the loop and array budgets stop a lane with the VM's message, line and column") {
  backends::Budgets small;
  small.max_loop_iterations = 1000;
  small.max_array_elements = 10;
  const char* loop = "function FRep(x, y, z, t) {\n  var s = 0;\n  while (s < x) s = s + 1;\n  return s;\n}";
  const char* index = "function FRep(x, y, z, t) {\n  var a = new Array(3);\n  return a[x];\n}";
  const char* size = "function FRep(x, y, z, t) {\n  var a = new Array(x);\n  return a.length;\n}";
  const char* forever = "function FRep(x, y, z, t) { var s = 0; while (true) s++; return s; }";
  auto vl = test::build(loop, "", true, small), vi = test::build(index, "", true, small),
       vs = test::build(size, "", true, small), vf = test::build(forever, "", true, small);
  REQUIRE((vl->ok && vi->ok && vs->ok && vf->ok));
  CHECK(batch_error(*vl->kernel, {1, 2, 5000, 3, 4}) ==
        "loop iteration budget exceeded: more than 1000 iterations in one evaluation @ 3:3");
  CHECK(batch_error(*vi->kernel, {0, 1, 2, 7, 1}) == "index 7 is out of range for array 'a' of 3 elements @ 3:10");
  CHECK(batch_error(*vs->kernel, {10, 11}).find("sizes must be whole numbers from 0 to the budget of 10") !=
        std::string::npos);
  for (const Variant& v : variants()) {
    INFO(v.name);
    CHECK(batch_error(*compile_on(v, *vl->module, small), {1, 2, 500, 3}) == "");
    CHECK(batch_error(*compile_on(v, *vl->module, small), {1, 2, 5000, 3, 4}) ==
          batch_error(*vl->kernel, {1, 2, 5000, 3, 4}));
    CHECK(batch_error(*compile_on(v, *vi->module, small), {0, 1, 2, 7, 1}) ==
          batch_error(*vi->kernel, {0, 1, 2, 7, 1}));
    CHECK(batch_error(*compile_on(v, *vs->module, small), {10}) == "");
    CHECK(batch_error(*compile_on(v, *vs->module, small), {10, 11}) == batch_error(*vs->kernel, {10, 11}));
    CHECK(batch_error(*compile_on(v, *vf->module, small), {0}) == batch_error(*vf->kernel, {0}));
  }
}

TEST_CASE("backends: the call depth budget, not the caller's stack, decides how deep recursion goes") {
  std::string text =
      "function down(n) { if (n <= 0) return 0; return 1 + down(n - 1); }\n"
      "function FRep(x, y, z, t) { return down(x); }";
  backends::Budgets budgets;
  budgets.max_call_depth = 50;
  auto vm = test::build(text, "", true, budgets);
  REQUIRE(vm->ok);
  std::string over = batch_error(*vm->kernel, {51});
  CHECK(over.find("call depth budget exceeded") == 0);
  backends::Budgets ceiling, capped;
  ceiling.max_call_depth = backends::kCallDepthCeiling;
  capped.max_call_depth = 1000;
  for (const Variant& v : variants()) {
    INFO(v.name);
    auto k = compile_on(v, *vm->module, budgets);
    CHECK(batch_error(*k, {49, 3}) == "");
    CHECK(batch_error(*k, {3, 51}) == over);
#ifndef __EMSCRIPTEN__  // (the browser build's ceiling is its stack's 1,000 and it has no threads)
    // 99,000 nested calls within a budget of 100,000, on stacks of 1 MiB to 1 GiB.
    CHECK(test::deep_recursion_mismatch(*compile_on(v, *vm->module, ceiling)) == "");
#endif
    // One more than the budget: the budget's error, on every stack.
    auto k1000 = compile_on(v, *vm->module, capped);
#ifdef __EMSCRIPTEN__
    CHECK(batch_error(*k1000, {1001}).find("call depth budget exceeded: more than 1000 nested calls") == 0);
#else
    for (size_t stack : {size_t{1} << 20, size_t{1} << 30}) {
      std::string got;
      test::on_thread_with_stack(stack, [&] { got = batch_error(*k1000, {1001}); });
      CHECK(got.find("call depth budget exceeded: more than 1000 nested calls") == 0);
    }
#endif
  }
}

TEST_CASE("backends: auto runs the VM first and native code after the switch, with the VM's bits") {
  auto vm =
      test::build("function FRep(x, y, z, t) { return sin(x * 3) * cos(y * 2) + z * z - 0.5; }", "", true, {}, "vm");
  REQUIRE(vm->ok);
  std::vector<std::vector<float>> cols(4, std::vector<float>(1000));
  for (size_t i = 0; i < 1000; ++i)
    cols[0][i] = 0.01f * i, cols[1][i] = 1 - 0.002f * i, cols[2][i] = 0.5f, cols[3][i] = 0;
  backends::TierStats before = backends::tier_stats();
  setenv("FSCRIPT_AUTO_SWITCH_AFTER", "300", 1);
  std::string error;
  auto k = backends::make_backend("auto")->compile(*vm->module, {}, error);
  unsetenv("FSCRIPT_AUTO_SWITCH_AFTER");
  REQUIRE(k);
  // The compile (started at once) has had time to finish: the switch still waits for the 300th
  // point (a fast compile once took the job from its first point and failed the CLI's check).
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  std::vector<float> want = run(*vm->kernel, cols), got = run(*k, cols);
  for (size_t i = 0; i < want.size(); ++i) CHECK(same(want[i], got[i]));
  backends::TierStats after = backends::tier_stats();
  CHECK(after.vm_points - before.vm_points == 300);  // one batch of 1,000: 300 on the VM, then native
  CHECK(after.native_points - before.native_points == 700);
  CHECK(after.switched == before.switched + 1);
  CHECK(after.first_switch_ms >= 0);
#ifdef __EMSCRIPTEN__
  return;  // (the browser build compiles on the caller's thread and keeps no cache of kernels)
#endif
  // The same module again: its native code is alive in the cache, so it runs native at once.
  auto again = backends::make_backend("auto")->compile(*vm->module, {}, error);
  REQUIRE(again);
  std::vector<float> again_got = run(*again, cols);
  for (size_t i = 0; i < want.size(); ++i) CHECK(same(want[i], again_got[i]));
  backends::TierStats cached = backends::tier_stats();
  CHECK(cached.vm_points == after.vm_points);
  CHECK(cached.cached == after.cached + (backends::available_backends().back() == "llvm" ? 1 : 0));
  // Another module, without the forced switch: a small job stays on the VM and starts no compile.
  auto other =
      test::build("function FRep(x, y, z, t) { return sin(x * 3) * cos(y * 2) + z * z - 0.25; }", "", true, {}, "vm");
  REQUIRE(other->ok);
  auto small = backends::make_backend("auto")->compile(*other->module, {}, error);
  REQUIRE(small);
  run(*small, cols);
  CHECK(backends::tier_stats().compiles == cached.compiles);
  // A caller that announces a big job gets the compile at once.
  small->expect_points(uint64_t{1} << 34);
  CHECK(backends::tier_stats().compiles == cached.compiles + 1);
}

// Grid rows (Kernel::eval_rows) through the row split give the bits the same points give as a
// batch, on every backend, with special values in the row inputs and along the rows.
TEST_CASE("backends: grid rows through the row split agree with the points, bit for bit") {
  const std::vector<std::string> bodies = {
      "var k = 12.566370614359172; return sin(x * k + t) * cos(y * k) + sin(y * k) * cos(z * k) + sin(z * k) * cos(x * "
      "k);",
      "return x * exp(y) * log(z * z + 1) - sqrt(abs(y)) * atan2(z, y) + min(x, pow(y, 2));",
      "return sin(y) * cos(z) * exp(t) + tanh(y - z);",  // nothing depends on x
      // Lane arithmetic only: sse runs it on eight lanes, row values broadcast (vbroadcastss).
      "var r = sqrt(y * y + z * z + 1) * (abs(z) + 2) - min(y, t) / 3 + ceil(y * z) * (y < z);"
      "return max(sqrt(x * x + r) - 0.5, min(abs(x) - r, x * y - z)) + floor(x * 3) * (x < r);",
  };
  // Special values among the rows and along them, or ordinary ones only (what a backend's fast
  // code guesses of its inputs then holds for whole batches: the wasm emitter's bound).
  for (bool special : {true, false}) {
    std::vector<float> xs;
    if (special)
      for (float v : test::kSpecial) xs.push_back(v);
    while (xs.size() < 61) xs.push_back(-1.0f + 0.037f * static_cast<float>(xs.size()));
    const size_t rows = 23, count = xs.size();
    std::vector<std::vector<float>> rest(3, std::vector<float>(rows));
    for (size_t r = 0; r < rows; ++r) {
      rest[0][r] = special ? test::kSpecial[(r * 5) % test::kSpecial.size()] : 0.3f - 0.11f * static_cast<float>(r);
      rest[1][r] = -0.9f + 0.08f * static_cast<float>(r);
      rest[2][r] = r % 3 ? 0.25f : 0.0f;
    }
  // The same points as one batch, for the reference (the VM without the split).
    std::vector<std::vector<float>> cols(4, std::vector<float>(rows * count));
    for (size_t r = 0; r < rows; ++r)
      for (size_t i = 0; i < count; ++i) {
        cols[0][r * count + i] = xs[i];
        for (size_t k = 0; k < 3; ++k) cols[1 + k][r * count + i] = rest[k][r];
      }
    for (const std::string& body : bodies) {
      auto vm = test::build("function FRep(x, y, z, t) { " + body + " }", "", true, {}, "vm");
      REQUIRE(vm->ok);
      std::vector<float> want = run(*vm->kernel, cols);
    // The forced switch first: once llvm has compiled the body, auto finds it in the cache.
      std::vector<std::string> names = {"auto, switched after 300 points"};
      for (const std::string& name : backends::available_backends()) names.push_back(name);
      names.push_back("auto");
      for (const std::string& label : names) {
        INFO(label << ": " << body);
        std::string name = label.substr(0, label.find(','));
        if (name != label) setenv("FSCRIPT_AUTO_SWITCH_AFTER", "300", 1);  // in the middle of the rows
        std::string error;
        auto k = backends::with_row_split(backends::make_backend(name)->compile(*vm->module, {}, error), name,
                                          *vm->module, {});
        REQUIRE(k);
        uint64_t rows_before = backends::row_stats().rows;
        std::vector<float> got(rows * count);
        float* outs[] = {got.data()};
        const float* in_rest[] = {rest[0].data(), rest[1].data(), rest[2].data()};
        backends::RuntimeError err;
        backends::TierStats tiers = backends::tier_stats();
        REQUIRE(k->eval_rows(xs.data(), count, in_rest, rows, outs, err));
        CHECK(backends::row_stats().rows == rows_before + rows);  // the split ran, not the points
        if (name != label) {
          unsetenv("FSCRIPT_AUTO_SWITCH_AFTER");
          CHECK(backends::tier_stats().native_points > tiers.native_points);  // both tiers ran rows
          CHECK(backends::tier_stats().vm_points > tiers.vm_points);
        }
        for (size_t i = 0; i < want.size(); ++i) {
          INFO("point " << i << (special ? ", special values" : ", ordinary values"));
          CHECK(same(want[i], got[i]));
        }
      }
    }
  }
}

// A run cancelled from another thread (fvrml-run --serve: a save, --max-seconds, Ctrl-C) stops
// generated code in its loops and recursive calls, on every backend, with the VM's message, line
// and column: a batch would otherwise last as long as the script's loops make it. With the flag
// set before the call, a loop of 10^8 iterations (its budget past int32 too: the SSE code's
// carried counters) and a tree of 2^27 recursive calls stop at once instead of running for
// seconds; straight-line code is not asked (the meshers ask between batches). Then the flag set
// by another thread during a long loop, through the batch and the one-point call.
// The wasm emitter's code does not poll the cancel flag: the browser build has no thread to cancel
// a run from (--max-seconds needs one), and auto moves onto that code there.
bool polls_cancellation(const Variant& v) {
#ifdef __EMSCRIPTEN__
  return v.name != "wasm" && v.name != "auto";
#else
  (void)v;
  return true;
#endif
}

TEST_CASE("backends: a cancelled run stops loops and recursive calls with the VM's message") {
  backends::Budgets big;
  big.max_loop_iterations = 4'000'000'000;
  const char* loop =
      "function FRep(x, y, z, t) {\n  var s = 0;\n  for (var i = 0; i < 1e8; i++) s += sin(x * i);\n"
      "  return s;\n}";
  const char* tree =
      "function grow(n) { return n <= 0 ? 1 : grow(n - 1) + grow(n - 1); }\n"
      "function FRep(x, y, z, t) {\n  return grow(26) + x;\n}";
  auto vl = test::build(loop, "", true), vb = test::build(loop, "", true, big), vt = test::build(tree, "", true),
       vp = test::build("function FRep(x, y, z, t) { return x * y + 1; }");
  REQUIRE((vl->ok && vb->ok && vt->ok && vp->ok));
  {
    std::atomic<bool> cancel{true};
    support::CancelScope scope(cancel);
    CHECK(batch_error(*vl->kernel, {1, 2, 3, 4, 5}) == "the run was cancelled @ 3:3");
    CHECK(batch_error(*vb->kernel, {1, 2, 3, 4, 5}) == "the run was cancelled @ 3:3");
    CHECK(batch_error(*vt->kernel, {1, 2, 3}).find("the run was cancelled @ ") == 0);
    for (const Variant& v : variants()) {
      INFO(v.name);
      if (!polls_cancellation(v)) continue;
      CHECK(batch_error(*compile_on(v, *vl->module), {1, 2, 3, 4, 5}) == batch_error(*vl->kernel, {1, 2, 3, 4, 5}));
      CHECK(batch_error(*compile_on(v, *vb->module, big), {1, 2, 3, 4, 5}) ==
            batch_error(*vb->kernel, {1, 2, 3, 4, 5}));
      CHECK(batch_error(*compile_on(v, *vt->module), {1, 2, 3}) == batch_error(*vt->kernel, {1, 2, 3}));
      CHECK(batch_error(*compile_on(v, *vp->module), {1, 2, 3}) == "");
    }
  }
#ifdef __EMSCRIPTEN__
  return;  // (cancelling from another thread: the browser build has none)
#endif
  for (const Variant& v : variants()) {
    INFO(v.name);
    if (!polls_cancellation(v)) continue;
    auto k = compile_on(v, *vl->module);
    for (bool one_point : {false, true}) {
      test::CancelAfter cancel(100);
      backends::RuntimeError err;
      float in[4] = {0.5f, 0, 0, 0}, out = 0;
      std::string got = one_point ? (k->eval(in, &out, err) ? "" : err.message) : batch_error(*k, {1, 2, 3, 4, 5});
      CHECK(got.find("the run was cancelled") == 0);
    }
  }
}

#ifdef __EMSCRIPTEN__
// The emitted bytes of programs with each construct pass Node's WebAssembly.validate, and a module
// cut short does not (compile names a refused module as the emitter's bug by the same check).
TEST_CASE("backends: the wasm emitter's modules pass WebAssembly.validate") {
  std::vector<std::string> bodies(test::kRecursiveBodies.begin(), test::kRecursiveBodies.end());
  for (const char* body : test::kControlFlowBodies) bodies.push_back(body);
  bodies.push_back("return sin(x) * cos(y) + sin(y) * cos(x) + atan2(x, y) + min(x, y) - max(z, 0.5);");
  for (const std::string& body : bodies) {
    INFO(body);
    auto vm = test::build(std::string(test::kRecursivePrelude) + "function FRep(x, y, z, t) { " +
                          test::kRecursiveSetup + body + " }");
    REQUIRE(vm->ok);
    wasm::CompiledModule c;
    std::string error;
    REQUIRE(wasm::compile_module(*vm->module, {}, c, error));
    CHECK(wasm::valid_module(c.bytes));
    c.bytes.pop_back();
    CHECK_FALSE(wasm::valid_module(c.bytes));
  }
}
#endif
