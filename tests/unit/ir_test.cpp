// IR: text round trip, reader errors, verifier.
#include <catch2/catch.hpp>

#include "ir/text.h"
#include "ir/verifier.h"
#include "tests/unit/helpers.h"

using namespace fscript;

static const char* kLoop = R"(global @x
garray @tab
fn @f(2) -> 1 {
  array %a
b0:
  v0 = param 0
  v1 = param 1
  v2 = const 0
  anew %a, v1 !3
  br b1
b1:
  v3 = phi [v2, b0], [v6, b2]
  v4 = flt v3, v1
  cbr v4, b2, b3
b2:
  tick !4:3
  v5 = const 1
  v6 = fadd v3, v5
  astore %a, v3, v0 !5
  br b1
b3:
  v7 = aload @tab, v2 !6
  gstore @x, v7
  v8 = call @f(v0, v1) !7:12
  ret v3
}
)";

TEST_CASE("ir: print -> read -> print is exact") {
  std::string err;
  auto m = ir::read(kLoop, err);
  INFO(err);
  REQUIRE(m);
  CHECK(ir::print(*m) == kLoop);
  CHECK(ir::verify(*m) == "");
}

TEST_CASE("ir: special constants round-trip") {
  std::string text =
      "fn @k(0) -> 4 kernel {\nb0:\n  v0 = const nan\n  v1 = const inf\n  v2 = const -inf\n"
      "  v3 = const 1.17549435e-38\n  ret v0, v1, v2, v3\n}\n";
  std::string err;
  auto m = ir::read(text, err);
  REQUIRE(m);
  CHECK(ir::print(*m) == text);
}

TEST_CASE("ir: reader reports bad text with a line") {
  std::string err;
  CHECK(!ir::read("fn @f(0) -> 1 {\nb0:\n  v0 = bogus\n}\n", err));
  CHECK(err.find("line 3") != std::string::npos);
  CHECK(!ir::read("fn @f(0) -> 1 {\nb0:\n  ret v9\n}\n", err));
  CHECK(err.find("undefined value") != std::string::npos);
  CHECK(!ir::read("fn @f(0) -> 0 {\nb0:\n  tick !4:x\n  ret\n}\n", err));
  CHECK(err.find("line 3: bad source position '!x'") != std::string::npos);
}

// Found by the ir_reader fuzz target: "v-07" read as value 2^32 - 7 made the reader resize its value
// table to 32 GB; "fn @f(4000000000)" asked for billions of parameter ranges.
TEST_CASE("ir: reader refuses ids and counts past its limit, and malformed ones") {
  std::string err;
  CHECK(!ir::read("fn @f(0) -> 1 {\nb0:\n  v-07 = const 2\n  ret v-07\n}\n", err));
  CHECK(err == "line 3: bad value number '-07'");
  CHECK(!ir::read("fn @f(0) -> 1 {\nb0:\n  v99999999 = const 2\n  ret v99999999\n}\n", err));
  CHECK(err == "line 3: value number 99999999 is over the reader's limit of 4194304");
  CHECK(!ir::read("fn @f(4000000000) -> 1 ranges {\nb0:\n  ret\n}\n", err));
  CHECK(err.find("line 1: bad parameter count '4000000000'") == 0);
  CHECK(!ir::read("fn @f(0) -> 1 {\nb77777777:\n  ret\n}\n", err));
  CHECK(err.find("over the reader's limit") != std::string::npos);
  CHECK(!ir::read("fn @f(3) -> 1 rows 1 ranges 0 1\n", err));
  CHECK(err.find("parameter ranges") != std::string::npos);
}

TEST_CASE("ir: the verifier catches broken SSA") {
  std::string err;
  // v1 is used in b1 but defined in b2, which does not dominate b1.
  auto m = ir::read(
      "fn @f(1) -> 1 {\nb0:\n  v0 = param 0\n  cbr v0, b1, b2\nb1:\n  ret v1\nb2:\n  v1 = fneg v0\n  ret v1\n}\n", err);
  REQUIRE(m);
  CHECK(ir::verify(*m).find("does not dominate") != std::string::npos);
  auto m2 = ir::read("fn @f(1) -> 1 {\nb0:\n  v0 = param 0\n  v1 = fadd v0\n  ret v1\n}\n", err);
  REQUIRE(m2);
  CHECK(ir::verify(*m2).find("wrong operand count") != std::string::npos);
  auto m3 =
      ir::read("fn @f(1) -> 1 {\nb0:\n  v0 = param 0\n  br b1\nb1:\n  v1 = phi [v0, b0], [v0, b1]\n  ret v1\n}\n", err);
  REQUIRE(m3);
  CHECK(ir::verify(*m3).find("does not match the predecessors") != std::string::npos);
}

TEST_CASE("ir: lowering output verifies for a program with every construct") {
  auto b = test::build(R"(
    var g = 2; var arr = [1, 2, 3];
    function h(n) { return n <= 0 ? 0 : h(n - 1) + 1; }
    function FRep(x, y, z, t) {
      var s = 0; let k = 1; const c = 3;
      for (var i = 0; i < 3; i++) { if (i == 1) continue; s += arr[i]; }
      while (s > 100) { s -= 1; if (s < 50) break; }
      do { k *= 2; } while (k < 8);
      s = x > 0 && y > 0 || z > 0 ? s + k : -s;
      s ^= 1; s %= 7; s /= 1; ++s; s--;
      return s + g + h(2) + c + arr.length;
    })",
                       "", false);
  REQUIRE(b->ok);
  CHECK(ir::verify(*b->module) == "");
}
