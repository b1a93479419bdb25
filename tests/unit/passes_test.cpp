// Passes: each keeps results identical (differential against the unoptimised program) and the
// verifier runs after every pass (build() sets verify_each).
#include <catch2/catch.hpp>
#include <cmath>

#include "ir/passes/passes.h"
#include "ir/passes/row_split.h"
#include "ir/verifier.h"
#include "ir/ranges.h"
#include "ir/text.h"
#include "tests/unit/helpers.h"

using namespace fscript;

static const char* kPrograms[] = {
    "function FRep(x,y,z,t){ var a = x*y + sin(x); var b = y*x + sin(x); return a - b + (z > 0 ? a : b); }",
    "function sq(v){return v*v;} function FRep(x,y,z,t){ return sqrt(sq(x)+sq(y)+sq(z)) - 0.5; }",
    "function FRep(x,y,z,t){ var s = 0; for (var i = 0; i < 5; i++) { if (x > i) s += i; else s -= y; } return s; }",
    "var c = 3; function f(v){ c = c + v; return c; } function FRep(x,y,z,t){ f(x); f(y); return c * z; }",
    "function fib(n){ return n < 2 ? n : fib(n-1) + fib(n-2); } function FRep(x,y,z,t){ return fib(floor(abs(x)) % 10) "
    "+ y; }",
    "function FRep(x,y,z,t){ var a = [x, y, z]; a[1] += 2; return a[0] * a[1] - a[2] + a.length; }",
    "function FRep(x,y,z,t){ return (x && y) + (x || z) + !y + (x == y) + (x != z) + (x <= y) + (x >= z); }",
};

TEST_CASE("passes: optimised and unoptimised programs agree") {
  const float pts[][4] = {{0, 0, 0, 0}, {1, 2, 3, 0}, {-1.5f, 0.25f, 7, 1}, {3, -2, 0.5f, 0}, {0.1f, 0.2f, -0.3f, 2}};
  for (const char* src : kPrograms) {
    auto plain = test::build(src, "", false);
    auto opt = test::build(src, "", true);
    INFO(src << "\n" << test::messages(plain->diag));
    REQUIRE(plain->ok);
    REQUIRE(opt->ok);
    for (const auto& p : pts) {
      std::vector<float> in(p, p + 4);
      float a = test::eval1(*plain, in), b = test::eval1(*opt, in);
      INFO("at " << p[0] << "," << p[1] << "," << p[2]);
      CHECK((a == b || (std::isnan(a) && std::isnan(b))));
    }
  }
}

TEST_CASE("passes: inlining leaves no calls to non-recursive functions") {
  auto b = test::build(kPrograms[1]);
  REQUIRE(b->ok);
  std::string text = ir::print(*b->module);
  CHECK(text.find("call") == std::string::npos);
  CHECK(b->module->functions.size() == 1);
}

TEST_CASE("passes: promotion removes global memory from a call-free kernel") {
  auto b = test::build(kPrograms[3]);
  REQUIRE(b->ok);
  std::string text = ir::print(*b->module);
  CHECK(text.find("gload") == std::string::npos);
  CHECK(text.find("gstore") == std::string::npos);
}

TEST_CASE("passes: if-conversion makes a straight-line kernel") {
  auto b = test::build("function FRep(x,y,z,t){ var d = x; if (x < 0) d = -x; return d > y ? d : y; }");
  REQUIRE(b->ok);
  CHECK(b->module->functions.back()->blocks.size() == 1);
}

TEST_CASE("passes: every pass runs alone on every program and verifies") {
  for (const char* src : kPrograms)
    for (const char* pass : {"inline", "promote", "fold", "dce", "gvn", "simplify", "ifconv"}) {
      auto b = test::build(src, "", false);
      REQUIRE(b->ok);
      ir::PassOptions po;
      po.verify_each = true;
      INFO(src << " / " << pass);
      CHECK(ir::run_passes(*b->module, pass, po) == "");
    }
}

namespace {
// The range of the kernel's returned value, parameters within +-bound.
ir::Range returned_range(const std::string& body, double bound) {
  auto b = test::build("function FRep(x, y, z, t) { " + body + " }");
  REQUIRE(b->ok);
  for (const auto& f : b->module->functions)
    if (f->kernel)
      for (const auto& blk : f->blocks)
        if (blk->terminator()->op == ir::Op::Ret) return ir::value_ranges(*f, bound)[blk->terminator()->args[0]->id];
  FAIL("no kernel");
  return {};
}
}  // namespace

TEST_CASE("ranges: intervals and the NaN bit under bounded parameters") {
  ir::Range r = returned_range("return sqrt(x * x + y * y);", 10);
  CHECK(r.lo == 0);  // a sum of squares keeps its zero lower bound, so its sqrt is no NaN
  CHECK(r.hi >= std::sqrt(200.0));
  CHECK(r.hi < 14.2);
  CHECK_FALSE(r.nan);
  CHECK(returned_range("return sqrt(x);", 10).nan);  // x may be negative
  r = returned_range("return x * x - x * x;", 1e4);
  CHECK_FALSE(r.nan);
  CHECK(r.lo <= -1e8);
  CHECK(r.hi >= 1e8);
  // Beyond the float range products overflow to infinity, and inf - inf is NaN.
  CHECK(returned_range("return x * x * x * x * x * x * x * x * x * x - 1;", 65536).hi == INFINITY);
  CHECK(returned_range("var a = x * x * x * x * x * x * x * x * x * x; return a - a;", 65536).nan);
  CHECK(returned_range("return max(x, y / y);", 10).nan);  // 0 / 0
  CHECK_FALSE(returned_range("return max(x, 1 / y);", 10).nan);  // 1 / 0 is infinite, never NaN
  CHECK_FALSE(returned_range("return min(x, y) + max(-x, 3) * abs(y);", 10).nan);
  r = returned_range("return min(x, y) + max(-x, 3) * abs(y);", 10);
  CHECK(r.lo <= -10 + 3 * 0);
  CHECK(r.hi >= 10 + 10 * 10);
  CHECK_FALSE(returned_range("return sin(x * 3) + (x < y);", 10).nan);
  CHECK(returned_range("var s = 0; for (var i = 0; i < x; i++) s += y; return s;", 10).nan);  // a loop phi
}

// The row split (ir/passes/row_split.h): what moves to the prologue, and when it does not pay.
TEST_CASE("row split: the gyroid's y and z work goes to the prologue; both parts verify") {
  auto b = test::build(
      "function FRep(x, y, z, t) { var k = 12.566370614359172; var X = x * k + t; var Y = y * k; var Z = z * k;"
      " return sin(X) * cos(Y) + sin(Y) * cos(Z) + sin(Z) * cos(X); }");
  REQUIRE(b->ok);
  ir::RowSplit s;
  REQUIRE(ir::split_rows(*b->module, s));
  CHECK(ir::verify(*s.prologue) == "");
  CHECK(ir::verify(*s.body) == "");
  // Once per row: y*k, z*k, sin and cos of each, sin(Y)*cos(Z). Per point: x*k+t, sin, cos, 2 *, 2 +
  // and the product with cos(Y). Row values: cos(Y), sin(Y)*cos(Z), sin(Z) and t.
  CHECK(s.hoisted == 7);
  CHECK(s.row_values == 4);
  CHECK(s.per_point == 8);
  CHECK(s.prologue->kernel_function().num_params == 4);
  CHECK(s.prologue->kernel_function().num_results == 4);
  CHECK(s.body->kernel_function().num_params == 5);
  CHECK(s.body->kernel_function().num_results == 1);
  // The body's row parameters are part of its text (the llvm cache keys by it) and read back.
  std::string text = ir::print(*s.body), error;
  CHECK(text.find(") -> 1 kernel rows 1 ranges ") != std::string::npos);
  auto again = ir::read(text, error);
  REQUIRE(again);
  CHECK(again->kernel_function().row_params_from == 1);
  CHECK(ir::print(*again) == text);
  CHECK(s.prologue->kernel_function().row_params_from == 0);
  // Row parameters only on a kernel, and before its last parameter.
  again->functions[0]->row_params_from = 5;
  CHECK(ir::verify(*again).find("row parameters") != std::string::npos);
}

TEST_CASE("row split: refused where it cannot or would not pay") {
  auto refused = [](const std::string& text) {
    auto b = test::build(text);
    REQUIRE(b->ok);
    ir::RowSplit s;
    return !ir::split_rows(*b->module, s) && !s.prologue && !s.body;
  };
  CHECK(refused("function FRep(x, y, z, t) { return x * 2 - 1; }"));              // nothing to hoist
  CHECK(refused("function FRep(x, y, z, t) { return x + y * y - z; }"));          // 1 operation for 2 values
  CHECK_FALSE(refused("function FRep(x, y, z, t) { return x + (y * y + z * z) * 0.5 - 2; }"));  // 3 for 1
  CHECK(refused("function FRep(x, y, z, t) { var s = 0; for (var i = 0; i < y * 9; i++) s += sin(x + i); return s; }"));
  CHECK(refused("function f(x) { return x < 1 ? x : f(x - 1) + 1; } function FRep(x, y, z, t) { return f(y) + x; }"));
  CHECK_FALSE(refused("function FRep(x, y, z, t) { return x - exp(y) * log(z + 2); }"));
}

// Found by backend_diff (tests/fuzz/corpus/backend_diff/promote-gstore-operand, the program it
// generates): in r1, `g1 = g1;` and calls before a loop whose body returns left the store at that
// return reading the replaced load of g1 (a value no longer in the function: the verifier failed,
// the JITs crashed).
TEST_CASE("passes: promotion keeps the stores at returns inside loops after g = g") {
  const char* text = R"(var g0 = 1e39;
var g1 = 0;
var ga = [pi, false];
function h0(p0) {
  var i0 = 0;
  while (i0 < 5) {
    i0 = i0 + 1;
    if (7.25) return (exp(0x10) ? (i0 % -0) : -(3));
    var i1 = 0;
    while (i1 < 4) {
      i1 = i1 + 1;
    }
  }
  p0 %= i1;
  for (var i2 = 0; i2 < 5; i2++) {
    var a3 = new Array(3);
    if ((+(-1) < (pi < g1))) {
    } else {
      if (log((i1 ? -0 : i2))) return (1e-40 ? g1 : -(g0));
    }
  }
  return !((ga.length ? g1 : -(atan2(i0, i0))));
}
function r1(n) {
  if (n <= 0) return atan2(atan2(n, g1), -(1e30));
  g1 = g1;
  ga[1] *= h0(h0(g1));
  ga[1] *= h0(h0(n));
  var i0 = 0;
  while (i0 < 0) {
    i0 = i0 + 1;
    var v1 = ((g0 += ga.length) ? tan(ga.length) : g1);
    if ((g1 < -(n))) return atan2(atan2(n, n), atan2(g1, g0));
    var v2 = ga[1];
  }
  return r1(n - 1) * g0;
}
function FRep(x, y, z, t) {
  var v0 = g1;
  return r1(8);
}

)";
  for (const char* be : {"vm", "sse"}) {
    auto b = test::build(text, "", true, {}, be);  // the verifier after every pass
    INFO(be << "\n" << test::messages(b->diag));
    REQUIRE(b->ok);
    CHECK(std::isinf(test::eval1(*b, {0, 0, 0, 0})));
  }
}
