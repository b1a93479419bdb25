#pragma once
// The programs and inputs every backend is checked on against the VM (backends_test, and the
// sse and llvm tests for what is their own):
// special values, one body per operation, transcendentals, and recursion with lanes of different
// depths.
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "tests/unit/helpers.h"

namespace fscript::test {

inline const float kInf = std::numeric_limits<float>::infinity(), kNan = std::numeric_limits<float>::quiet_NaN();
inline const std::vector<float> kSpecial = {0.0f,    -0.0f,       1.0f,   -1.0f,  0.5f,  -0.5f, 1.5f,
                                            -2.5f,   0.49999997f, 3.0f,   kInf,   -kInf, kNan,  1e-40f,
                                            -1e-40f, 1e30f,       -7.25f, 100.0f, 0.1f,  2.0f};

// Bit-identical, or NaN on both sides (payloads are not part of the semantics).
inline bool same(float a, float b) {
  if (std::isnan(a) && std::isnan(b)) return true;
  uint32_t x, y;
  std::memcpy(&x, &a, 4);
  std::memcpy(&y, &b, 4);
  return x == y;
}

inline const std::vector<const char*> kArithmeticBodies = {"return x + y;",
                                                           "return x - y;",
                                                           "return x * y;",
                                                           "return x / y;",
                                                           "return -x;",
                                                           "return abs(x);",
                                                           "return sqrt(x);",
                                                           "return min(x, y);",
                                                           "return max(x, y);",
                                                           "return min(y, x);",
                                                           "return floor(x);",
                                                           "return ceil(x);",
                                                           "return round(x);",
                                                           "return sign(x);",
                                                           "return clamp(x, y, z);",
                                                           "return x == y;",
                                                           "return x != y;",
                                                           "return x < y;",
                                                           "return x <= y;",
                                                           "return x > y;",
                                                           "return x >= y;",
                                                           "return !x;",
                                                           "return x ? y : z;",
                                                           "return (x && y) ? 1 : 2;",
                                                           "return x * x + y * y - 0.25;",
                                                           "return x % y;",
                                                           "return max(1, x * x - x * x) + min(y, 2 * y);"};

inline const std::vector<const char*> kTranscendentalBodies = {
    "return sin(x);",         "return cos(x) * y;",
    "return tan(x);",         "return exp(x);",
    "return log(x);",         "return log10(x);",
    "return pow(x, y);",      "return atan2(x, y);",
    "return asin(x);",        "return acos(x);",
    "return atan(x);",        "return sinh(x);",
    "return cosh(x);",        "return tanh(x);",
    "return noise(x, y, z);", "return sin(x) + cos(y) * sin(z);",
    "return hypot(x, y);",    "return hypot(x * 1e30, y) - hypot(y, -x);"};

// Branches and loops whose lanes take different paths (the JITs run them masked).
inline const std::vector<const char*> kControlFlowBodies = {
    "if (x < 0) { return -x; } else { return x * 2; }",
    "if (x > 0) return y; else if (x < -1) return z; return 7;",
    "var s = 0; for (var i = 0; i < abs(x) && i < 40; i++) s = s + i * y; return s;",
    "var s = 0; for (var i = 0; i < 20; i++) { if (i > abs(x)) break; s += i * y; } return s;",
    "var i = 0; while (true) { if (i * i > abs(x) * 10) break; i++; if (i > 50) break; } return i;",
    "var n = 0; var v = abs(x); while (v > 1 && n < 50) { v = v / 2; n++; } return n + v;",
    "var s = 0; for (var i = 0; i < 8; i++) { if (i % 2 == 0) continue; s = s + i; } return s + x;",
    "var c = 0; for (var i = 0; i < 5; i++) for (var j = 0; j < 5; j++) { if (j > i + x) break; c += 1; } return c;",
    "var k = floor(clamp(x, -3, 30)); var a = 0; var b = 1; while (k > 0) { var t = a + b; a = b; b = t; k -= 1; } "
    "return a;",
    "var s = 0; do { s = s + 1; } while (s < y && s < 20); return s;",
    "if (x) return sin(y); else if (y) return cos(x); return z;",
    "var a = new Array(5); for (var i = 0; i < 5; i++) a[i] = i * x; return a[y == y ? min(abs(floor(y)), 4) : 0] + "
    "a.length;"};

// Programs whose runtime errors depend on the inputs: every batch length must run exactly the
// points given (the padding of a last, partial group of lanes must not raise an error of its own).
inline const std::vector<const char*> kInputDependentErrors = {
    "function FRep(x, y, z, t) { var a = new Array(x); a[x - 1] = 2; return a[0] + a.length; }",
    "function FRep(x, y, z, t) { var s = 0; for (var i = 0; i < 1 / x; i++) s = s + 1; return s; }",
    "function f(n) { if (n <= 0) return 0; return 1 + f(n - 1); }\n"
    "function FRep(x, y, z, t) { return f(20 / x); }"};

// The budgets those programs run under (small, so their errors come quickly).
inline backends::Budgets input_dependent_budgets() {
  backends::Budgets b;
  b.max_loop_iterations = 100;
  b.max_call_depth = 50;
  return b;
}

// `k`'s batch over four input columns x, y, z, t (one output); false with the error in `err`.
inline bool eval_columns(const backends::Kernel& k, const std::vector<float> (&cols)[4], std::vector<float>& out,
                         backends::RuntimeError& err) {
  out.assign(cols[0].size(), 0.0f);
  const float* in[4] = {cols[0].data(), cols[1].data(), cols[2].data(), cols[3].data()};
  float* o[1] = {out.data()};
  return k.eval_batch(in, o, out.size(), err);
}

// "" when `jit` gives the VM's results for x = 1, 2, ... n (y = z = t = 0) at every batch length
// n up to `max_n`, else what differed.
inline std::string partial_group_mismatch(const backends::Kernel& vm, const backends::Kernel& jit, size_t max_n) {
  for (size_t n = 1; n <= max_n; ++n) {
    std::vector<float> x(n), zero(n, 0.0f), a(n), b(n);
    for (size_t i = 0; i < n; ++i) x[i] = 1.0f + static_cast<float>(i);
    const float* in[4] = {x.data(), zero.data(), zero.data(), zero.data()};
    float* oa[1] = {a.data()};
    float* ob[1] = {b.data()};
    backends::RuntimeError ea, eb;
    if (!vm.eval_batch(in, oa, n, ea)) return "the VM failed: " + ea.message;
    if (!jit.eval_batch(in, ob, n, eb)) return "n = " + std::to_string(n) + ": " + eb.message;
    for (size_t i = 0; i < n; ++i)
      if (!same(a[i], b[i])) return "n = " + std::to_string(n) + ": point " + std::to_string(i) + " differs";
  }
  return "";
}

// "" when `k` (with a call budget of at least 99,001) evaluates 99,000 nested calls of the FRep
// argument's recursion to 99,000 on a thread of 1 MiB (the guard stops the generated code, which
// runs again on a stack sized for the budget), of 64 MiB and of 1 GiB, as under any `ulimit -s`;
// else what went wrong.
inline std::string deep_recursion_mismatch(const backends::Kernel& k) {
  for (size_t stack : {size_t{1} << 20, size_t{64} << 20, size_t{1} << 30}) {
    backends::RuntimeError err;
    bool ok = false;
    float r = 0;
    on_thread_with_stack(stack, [&] {
      float p[4] = {99000, 0, 0, 0};
      ok = k.eval(p, &r, err);
    });
    if (!ok || r != 99000.0f)
      return "a thread of " + std::to_string(stack >> 20) + " MiB: " + (ok ? std::to_string(r) : err.message);
  }
  return "";
}

inline const char* kRecursivePrelude =
    "function fact(n) { if (n <= 1) return 1; return n * fact(n - 1); }\n"
    "function fib(n) { return n < 2 ? n : fib(n - 1) + fib(n - 2); }\n"
    "function even(n) { if (n <= 0) return 1; return odd(n - 1); }\n"
    "function odd(n) { if (n <= 0) return 0; return even(n - 1); }\n"
    "var calls = 0;\n"
    "function count(n) { calls = calls + 1; if (n <= 0) return calls; return count(n - 1); }\n"
    "var arr = new Array(4);\n"
    "function fill(n) { var a = new Array(3); a[0] = n; if (n > 0) fill(n - 1); arr[0] = arr[0] + a[0]; return a[0]; "
    "}\n"
    "function loopy(n) { var s = 0; for (var i = 0; i < n; i++) s += i; if (n <= 0) return s; return s + loopy(n - 1); "
    "}\n";
// n from the special values (NaN, inf, negatives, fractions): lanes recurse to different depths.
inline const char* kRecursiveSetup = "var n = x == x ? min(abs(floor(x)), 25) : 2; ";
inline const std::vector<const char*> kRecursiveBodies = {
    "return fact(n);",
    "return fib(min(n, 12)) + y;",
    "return even(n) + odd(3);",
    "return count(min(n, 20)) * 100 + calls;",
    "return fill(min(n, 6)) + arr[0];",
    "return loopy(min(n, 10));",
    "return x > 0 ? fact(min(n, 10)) : (y > 0 ? fib(min(y, 10)) : -1);"};

}  // namespace fscript::test
