// The LLVM backend against the VM, value for value, at every vector width (4, 8, 16 lanes): every
// operation on special values (bit-identical, or NaN on both), transcendentals, masked branches
// and loops, globals, arrays, recursion and the budgets; code that assumes bounded inputs and the
// general code; compile-and-free cycles; the compiled-code cache.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>
#include <filesystem>

#include <unistd.h>

#include "backends/llvm/llvm_backend.h"
#include "tests/unit/backend_cases.h"
#include "tests/unit/helpers.h"

using namespace fscript;
using test::kInf;
using test::kNan;
using test::kSpecial;
using test::same;

namespace {

const uint32_t kWidths[] = {4, 8, 16};

std::unique_ptr<backend::Kernel> llvm_kernel(const ir::Module& m, uint32_t width, const backend::Budgets& budgets = {}) {
  std::string error;
  auto k = llvmjit::LlvmBackend(width).compile(m, budgets, error);
  INFO(error);
  REQUIRE(k);
  return k;
}

// Both backends over every pair of special values (the third input cycling), in one batch whose
// length is no multiple of the width (the padded tail runs too).
void agree(const std::string& body, const std::string& prelude = "") {
  std::string text = prelude + "function FRep(x, y, z, t) { " + body + " }";
  auto vm = test::build(text, "", true, {}, "vm");
  INFO(body << "\n" << test::messages(vm->diag));
  REQUIRE(vm->ok);
  std::vector<float> x, y, z, t;
  for (float a : kSpecial)
    for (float b : kSpecial) x.push_back(a), y.push_back(b), z.push_back(kSpecial[(x.size() * 7) % kSpecial.size()]), t.push_back(0);
  x.push_back(0.25f), y.push_back(2), z.push_back(3), t.push_back(0);
  size_t n = x.size();
  std::vector<float> o1(n);
  const float* in[4] = {x.data(), y.data(), z.data(), t.data()};
  float* out1[1] = {o1.data()};
  backend::RuntimeError err;
  REQUIRE(vm->kernel->eval_batch(in, out1, n, err));
  for (uint32_t w : kWidths) {
    auto k = llvm_kernel(*vm->module, w);
    std::vector<float> o2(n);
    float* out2[1] = {o2.data()};
    REQUIRE(k->eval_batch(in, out2, n, err));
    int bad = 0;
    for (size_t i = 0; i < n && bad < 5; ++i)
      if (!same(o1[i], o2[i])) {
        ++bad;
        FAIL_CHECK("width " << w << " x=" << x[i] << " y=" << y[i] << " z=" << z[i] << ": vm " << o1[i] << ", llvm " << o2[i]);
      }
  }
}

}  // namespace

TEST_CASE("llvm: arithmetic, min/max, comparisons and selects are bit-identical to the VM") {
  for (const char* body : test::kArithmeticBodies) agree(body);
}

TEST_CASE("llvm: transcendentals and noise agree with the VM (the same runtime/math functions)") {
  for (const char* body : test::kTranscendentalBodies) agree(body);
}

TEST_CASE("llvm: branches, loops, globals and arrays run masked, lane by lane as the VM runs them") {
  agree("if (x > 0) return y; else if (x < -1) return z; return 7;");
  agree("var s = 0; for (var i = 0; i < 20; i++) { if (i > abs(x)) break; s += i * y; } return s;");
  agree("var n = 0; var v = abs(x); while (v > 1 && n < 50) { v = v / 2; n++; } return n + v;");
  agree("g = x; if (y > 0) g = g + 1; return g * 2;", "var g = 0;\n");
  agree("var a = new Array(5); for (var i = 0; i < 5; i++) a[i] = i * x; return a[y == y ? min(abs(floor(y)), 4) : 0] + a.length;");
}

TEST_CASE("llvm: recursive functions run under the caller's lanes, with the VM's budgets") {
  for (const char* body : test::kRecursiveBodies)
    agree(std::string(test::kRecursiveSetup) + body, test::kRecursivePrelude);
}

TEST_CASE("llvm: a partial last group runs only the points given (errors that depend on the inputs)") {
  backend::Budgets budgets = test::input_dependent_budgets();
  for (const char* text : test::kInputDependentErrors) {
    INFO(text);
    auto vm = test::build(text, "", true, budgets, "vm");
    REQUIRE(vm->ok);
    for (uint32_t w : kWidths) {
      INFO("width " << w);
      CHECK(test::partial_group_mismatch(*vm->kernel, *llvm_kernel(*vm->module, w, budgets), 17) == "");
    }
  }
}

TEST_CASE("llvm: the budgets give the VM's errors; the budget, not the caller's stack, decides how deep recursion goes") {
  std::string text = "function down(n) { if (n <= 0) return 0; return 1 + down(n - 1); }\n"
                     "function FRep(x, y, z, t) { return down(x); }";
  backend::Budgets budgets;
  budgets.max_call_depth = 50;
  auto vm = test::build(text, "", true, budgets, "vm");
  REQUIRE(vm->ok);
  for (uint32_t w : kWidths) {
    auto k = llvm_kernel(*vm->module, w, budgets);
    float in[4] = {49, 0, 0, 0}, out = 0;
    backend::RuntimeError e1, e2;
    REQUIRE(k->eval(in, &out, e2));
    CHECK(out == 49.0f);
    in[0] = 51;
    CHECK_FALSE(vm->kernel->eval(in, &out, e1));
    CHECK_FALSE(k->eval(in, &out, e2));
    CHECK(e2.message == e1.message);
    CHECK(e2.line == e1.line);
  }
  budgets.max_call_depth = backend::kCallDepthCeiling;
  auto deep = test::build(text, "", true, budgets, "vm");
  auto k = llvm_kernel(*deep->module, 16, budgets);
  // 99,000 nested calls within the budget succeed on any caller's stack.
  CHECK(test::deep_recursion_mismatch(*k) == "");

  auto loop = test::build("function FRep(x, y, z, t) { var s = 0; while (true) s++; return s; }", "", true, {}, "vm");
  auto lk = llvm_kernel(*loop->module, 8);
  float p[4] = {0, 0, 0, 0}, r = 0;
  backend::RuntimeError e4;
  CHECK_FALSE(lk->eval(p, &r, e4));
  CHECK(e4.message.find("loop iteration budget exceeded") != std::string::npos);
  CHECK(e4.line == 1);
}

TEST_CASE("llvm: bounded-input code, and the general code for batches outside the bound") {
  std::string text = "function FRep(x, y, z, t) { return max(1, x * x - x * x); }";
  auto vm = test::build(text, "", true, {}, "vm");
  auto k = llvm_kernel(*vm->module, 16);
  std::string error;
  std::string ir = llvmjit::kernel_text(*vm->module, {}, false, error);
  CHECK(ir.find("inputs finite with |x| <= 65536") != std::string::npos);
  std::vector<float> x = {0.5f, 1e30f, 2.0f, kInf, kNan, 70000.0f, -3.0f}, zero(x.size()), out(x.size());
  const float* in[4] = {x.data(), zero.data(), zero.data(), zero.data()};
  float* o[1] = {out.data()};
  backend::RuntimeError err;
  REQUIRE(k->eval_batch(in, o, x.size(), err));
  CHECK(out[0] == 1.0f);
  CHECK(std::isnan(out[1]));
  CHECK(std::isnan(out[3]));
  CHECK(std::isnan(out[4]));
  CHECK(out[5] == 1.0f);
}

TEST_CASE("llvm: kernels compiled and freed, and the cache of compiled code") {
  for (int i = 0; i < 40; ++i) {  // each a new program: its JITDylib goes with the last kernel
    auto vm = test::build("function FRep(x, y, z, t) { return x * " + std::to_string(i) + " + sin(y); }");
    auto k = llvm_kernel(*vm->module, 8);
    float in[4] = {1, 0, 0, 0}, r = -1;
    backend::RuntimeError err;
    REQUIRE(k->eval(in, &r, err));
    CHECK(r == static_cast<float>(i));
  }
  auto vm = test::build("function FRep(x, y, z, t) { return x * 123.5 + y; }");
  llvmjit::CacheStats before = llvmjit::cache_stats();
  auto k1 = llvm_kernel(*vm->module, 8);
  auto k2 = llvm_kernel(*vm->module, 8);  // the same IR: no second compile
  llvmjit::CacheStats after = llvmjit::cache_stats();
  CHECK(after.compiles == before.compiles + 1);
  CHECK(after.hits == before.hits + 1);
  float in[4] = {2, 1, 0, 0}, r1 = 0, r2 = 0;
  backend::RuntimeError err;
  REQUIRE(k1->eval(in, &r1, err));
  REQUIRE(k2->eval(in, &r2, err));
  CHECK(r1 == 248.0f);
  CHECK(r2 == 248.0f);
}

TEST_CASE("llvm: the on-disk cache of machine code serves the next compile of the same program") {
  std::string dir = "/tmp/fscript-llvm-test-cache-" + std::to_string(::getpid());
  setenv("XDG_CACHE_HOME", dir.c_str(), 1);
  REQUIRE(llvmjit::set_disk_cache_enabled(true) == dir + "/fscript/llvm");
  llvmjit::set_cache_enabled(false);  // so the second compile cannot come from memory
  auto vm = test::build("function FRep(x, y, z, t) { return sin(x) * 7.25 + y * y; }");
  llvmjit::CacheStats before = llvmjit::cache_stats();
  auto k1 = llvm_kernel(*vm->module, 16);
  auto k2 = llvm_kernel(*vm->module, 16);
  llvmjit::CacheStats after = llvmjit::cache_stats();
  llvmjit::set_cache_enabled(true);
  llvmjit::set_disk_cache_enabled(false);
  CHECK(after.compiles == before.compiles + 2);
  CHECK(after.disk_hits == before.disk_hits + 1);
  float in[4] = {0.5f, 3, 0, 0}, r1 = 0, r2 = 0, r0 = 0;
  backend::RuntimeError err;
  REQUIRE(vm->kernel->eval(in, &r0, err));
  REQUIRE(k1->eval(in, &r1, err));
  REQUIRE(k2->eval(in, &r2, err));
  CHECK(same(r1, r0));
  CHECK(same(r2, r0));
  std::filesystem::remove_all(dir);
}
