// What is the LLVM backend's own: code that assumes bounded inputs and the general code, the cache
// of compiled code in memory and on disk. Everything every backend must do (each op on special
// values, control flow, recursion, budgets) is in backends_test.cpp, at each vector width.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>
#include <filesystem>

#include <unistd.h>

#include "backends/llvm_module.h"
#include "backends/row_split_kernel.h"
#include "backends/tiered/tiered.h"
#include "tests/unit/backend_cases.h"
#include "tests/unit/helpers.h"

using namespace fscript;
using test::kInf;
using test::kNan;
using test::kSpecial;
using test::same;

namespace {

// The backend's module (loaded by the first call); the test fails with the loader's reason if not.
const backends::LlvmModule& llvm() {
  std::string error;
  const backends::LlvmModule* m = backends::llvm_module(&error);
  if (!m) FAIL(error);
  return *m;
}

const uint32_t kWidths[] = {4, 8, 16};

std::unique_ptr<backends::Kernel> llvm_kernel(const ir::Module& m, uint32_t width,
                                              const backends::Budgets& budgets = {}) {
  std::string error;
  auto k = llvm().backend(width)->compile(m, budgets, error);
  INFO(error);
  REQUIRE(k);
  return k;
}

}  // namespace

// First in the file: nothing has loaded the module yet. An announced job whose VM time (2 ms here)
// is under LLVM's compile with the module's load (61 ms) but over the SSE middle tier's (0.2 ms)
// gets the middle tier at once, and never loads LLVM.
TEST_CASE("llvm: auto compiles the middle tier for a job that outlasts it, without loading LLVM") {
  REQUIRE_FALSE(backends::llvm_module_loaded());
  auto b = test::build(
      "function FRep(x,y,z,t){ var k = 12.5; return sin(x*k)*cos(y*k) + sin(y*k)*cos(z*k) + sin(z*k)*cos(x*k); }");
  REQUIRE(b->ok);
  uint64_t before = backends::tier_stats().compiles;
  {
    std::string error;
    auto k = backends::make_backend("auto")->compile(*b->module, {}, error);
    REQUIRE(k);
    k->expect_points(200000);
  }  // the kernel's end waits for its compile
  CHECK(backends::tier_stats().compiles == before + 1);
  CHECK_FALSE(backends::llvm_module_loaded());
}

TEST_CASE("llvm: auto's estimate of the first native code counts the module's load") {
  REQUIRE_FALSE(backends::llvm_module_loaded());
  double first = backends::native_compile_ns(21);
  llvm();
  REQUIRE(backends::llvm_module_loaded());
  double later = backends::native_compile_ns(21);
  CHECK(later == Approx(10e6 + 21 * 50e3));
  CHECK(first == Approx(later + 50e6));
}

// A row split under auto: the announced job reaches the prologue too, as rows (the points over the
// first call's row length). Unannounced, it never reached its compile estimate and ran the whole
// job on the VM (the gyroid mesh's 616,748 prologue rows).
TEST_CASE("llvm: auto announces a row split's prologue its rows") {
  auto b = test::build(
      "function FRep(x,y,z,t){ var k = 12.5; return sin(x*k)*cos(y*k) + sin(y*k)*cos(z*k) + sin(z*k)*cos(x*k); }");
  REQUIRE(b->ok);
  const size_t count = 16, rows = 64;
  std::vector<float> xs(count), y(rows), z(rows), t(rows, 0.0f), out(count * rows);
  for (size_t i = 0; i < count; ++i) xs[i] = 0.1f * static_cast<float>(i);
  for (size_t r = 0; r < rows; ++r) y[r] = 0.05f * static_cast<float>(r), z[r] = -y[r];
  uint64_t before = backends::tier_stats().compiles;
  {
    std::string error;
    auto k = backends::with_row_split(backends::make_backend("auto")->compile(*b->module, {}, error), "auto",
                                      *b->module, {});
    REQUIRE(k);
    // 13 M rows of 16: the prologue's VM time outlasts its first native code's compile, with or
    // without the LLVM module loaded (then that is LLVM's, about 10 ms).
    k->expect_points(uint64_t{200} << 20);
    const float* rest[] = {y.data(), z.data(), t.data()};
    float* outs[] = {out.data()};
    backends::RuntimeError err;
    REQUIRE(k->eval_rows(xs.data(), count, rest, rows, outs, err));
  }  // the kernels' ends wait for their compiles
  CHECK(backends::tier_stats().compiles == before + 3);  // the full kernel, the body and the prologue
}

TEST_CASE("llvm: bounded-input code, and the general code for batches outside the bound") {
  std::string text = "function FRep(x, y, z, t) { return max(1, x * x - x * x); }";
  auto vm = test::build(text, "", true, {}, "vm");
  auto k = llvm_kernel(*vm->module, 16);
  std::string error;
  std::string ir = llvm().kernel_text(*vm->module, {}, false, error);
  CHECK(ir.find("inputs finite with |x| <= 65536") != std::string::npos);
  std::vector<float> x = {0.5f, 1e30f, 2.0f, kInf, kNan, 70000.0f, -3.0f}, zero(x.size()), out(x.size());
  const float* in[4] = {x.data(), zero.data(), zero.data(), zero.data()};
  float* o[1] = {out.data()};
  backends::RuntimeError err;
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
    backends::RuntimeError err;
    REQUIRE(k->eval(in, &r, err));
    CHECK(r == static_cast<float>(i));
  }
  auto vm = test::build("function FRep(x, y, z, t) { return x * 123.5 + y; }");
  backends::LlvmCacheStats before = llvm().cache_stats();
  auto k1 = llvm_kernel(*vm->module, 8);
  auto k2 = llvm_kernel(*vm->module, 8);  // the same IR: no second compile
  backends::LlvmCacheStats after = llvm().cache_stats();
  CHECK(after.compiles == before.compiles + 1);
  CHECK(after.hits == before.hits + 1);
  float in[4] = {2, 1, 0, 0}, r1 = 0, r2 = 0;
  backends::RuntimeError err;
  REQUIRE(k1->eval(in, &r1, err));
  REQUIRE(k2->eval(in, &r2, err));
  CHECK(r1 == 248.0f);
  CHECK(r2 == 248.0f);
}

// The one-point code is a one-lane module with its own entry (plain input and output arrays):
// a one-lane batch kernel of the same program is other code under another cache key.
TEST_CASE("llvm: the one-point entry agrees with the VM on recursion, arrays and loops, next to one-lane batch code") {
  for (const char* body : test::kRecursiveBodies) {
    auto vm = test::build(std::string(test::kRecursivePrelude) + "function FRep(x, y, z, t) { " +
                          test::kRecursiveSetup + body + " }");
    REQUIRE(vm->ok);
    auto batch = llvm_kernel(*vm->module, 1);
    auto k = llvm_kernel(*vm->module, 16);
    for (float x : kSpecial) {
      float in[4] = {x, 3.0f, 0.5f, 0}, r0 = 0, r1 = 0, r2 = 0;
      const float* cols[4] = {&in[0], &in[1], &in[2], &in[3]};
      float* outs[1] = {&r2};
      backends::RuntimeError e0, e1, e2;
      INFO(body << " x = " << x);
      REQUIRE(vm->kernel->eval(in, &r0, e0));
      REQUIRE(k->eval(in, &r1, e1));
      REQUIRE(batch->eval_batch(cols, outs, 1, e2));
      CHECK(same(r1, r0));
      CHECK(same(r2, r0));
    }
  }
}

// Calls inlined into hundreds of loops and branches: a module of thousands of blocks gets the quick
// compile (the full one took 45 s for a generated program like this), and the same answers.
TEST_CASE("llvm: a kernel of thousands of blocks is compiled quickly and agrees with the VM") {
  std::string text =
      "function h(p) { var s = 0; for (var i = 0; i < 3; i++) { if (p > i) s += sin(p * i); else s -= i; } return s; "
      "}\n"
      "function k(p) { return h(p) + h(p + 1) * 0.5 + h(p * 2) - h(p - 1); }\n"
      "function FRep(x, y, z, t) {\n  var r = 0;\n";
  for (int i = 0; i < 48; ++i)
    text += "  r = r * 0.75 + k(x * " + std::to_string(i % 7) + " + y - z * " + std::to_string(i % 5) + ");\n";
  text += "  return r;\n}";
  auto vm = test::build(text);
  REQUIRE(vm->ok);
  backends::LlvmCacheStats before = llvm().cache_stats();
  auto k = llvm_kernel(*vm->module, 16);
  std::vector<float> cols[4], o1, o2;
  auto& [x, y, z, t] = cols;
  for (float a : kSpecial)
    for (float b : {0.5f, -2.0f, 3.25f}) x.push_back(a), y.push_back(b), z.push_back(a * 0.25f), t.push_back(0);
  backends::RuntimeError err;
  REQUIRE(test::eval_columns(*vm->kernel, cols, o1, err));
  REQUIRE(test::eval_columns(*k, cols, o2, err));
  for (size_t i = 0; i < x.size(); ++i) {
    INFO("x = " << x[i] << ", y = " << y[i]);
    CHECK(same(o1[i], o2[i]));
    float p[4] = {x[i], y[i], z[i], 0}, r = 0;
    REQUIRE(k->eval(p, &r, err));
    CHECK(same(o1[i], r));
  }
  backends::LlvmCacheStats after = llvm().cache_stats();
  CHECK(after.quick_compiles >= before.quick_compiles + 2);  // the batch code and the one-point code
}

// A straight-line kernel of 30,000 operations: instruction selection sees blocks of at most 8,192
// instructions (one block took 196 s at 100,000 operations), the one-point code (over 25,000
// instructions) gets the quick compile, and both agree with the VM.
TEST_CASE("llvm: a straight-line kernel of 30,000 operations compiles in pieces and agrees with the VM") {
  std::string body = "var s = x;";
  for (int i = 0; i < 15000; ++i)
    body += i % 3 ? "s = s * 0.99991 + y * " + std::to_string(i % 7) + ".5;" : std::string("s = max(s, z) - 0.001;");
  auto vm = test::build("function FRep(x, y, z, t) { " + body + " return s; }");
  REQUIRE(vm->ok);
  backends::LlvmCacheStats before = llvm().cache_stats();
  auto k = llvm_kernel(*vm->module, 16);
  for (float x : {0.5f, -3.0f, 1e6f, kNan}) {
    float in[4] = {x, 0.25f, 0.1f, 0}, a = 0, b = 0, c = 0;
    const float* cols[4] = {&in[0], &in[1], &in[2], &in[3]};
    float* out[1] = {&b};
    backends::RuntimeError err;
    REQUIRE(vm->kernel->eval(in, &a, err));
    REQUIRE(k->eval_batch(cols, out, 1, err));
    REQUIRE(k->eval(in, &c, err));
    CHECK(same(a, b));
    CHECK(same(a, c));
  }
  CHECK(llvm().cache_stats().quick_compiles >= before.quick_compiles + 1);
}

TEST_CASE("llvm: the memory cache forgets freed programs (a long session compiles without end)") {
  // 300 distinct programs, each freed at once: the cache may keep the last few and a sweep's
  // slack, never a key per program ever compiled (it did: 3,318 keys, 2.6 MB, after a fuzz run).
  for (int i = 0; i < 300; ++i) {
    auto vm = test::build("function FRep(x, y, z, t) { return x * " + std::to_string(i) + ".25 + y; }");
    auto k = llvm_kernel(*vm->module, 8);
    REQUIRE(k);
  }
  CHECK(llvm().cache_stats().keys <= 128);
}

TEST_CASE("llvm: the on-disk cache of machine code serves the next compile of the same program") {
  std::string dir = "/tmp/fscript-llvm-test-cache-" + std::to_string(::getpid());
  setenv("XDG_CACHE_HOME", dir.c_str(), 1);
  REQUIRE(llvm().set_disk_cache_enabled(true) == dir + "/fscript/llvm");
  llvm().set_cache_enabled(false);  // so the second compile cannot come from memory
  auto vm = test::build("function FRep(x, y, z, t) { return sin(x) * 7.25 + y * y; }");
  backends::LlvmCacheStats before = llvm().cache_stats();
  auto k1 = llvm_kernel(*vm->module, 16);
  auto k2 = llvm_kernel(*vm->module, 16);
  backends::LlvmCacheStats after = llvm().cache_stats();
  llvm().set_cache_enabled(true);
  llvm().set_disk_cache_enabled(false);
  CHECK(after.compiles == before.compiles + 2);
  CHECK(after.disk_hits == before.disk_hits + 1);
  float in[4] = {0.5f, 3, 0, 0}, r1 = 0, r2 = 0, r0 = 0;
  backends::RuntimeError err;
  REQUIRE(vm->kernel->eval(in, &r0, err));
  REQUIRE(k1->eval(in, &r1, err));
  REQUIRE(k2->eval(in, &r2, err));
  CHECK(same(r1, r0));
  CHECK(same(r2, r0));
  std::filesystem::remove_all(dir);
}
