// Parser: precedence (checked through the formatter), recovery, limits.
#include <catch2/catch.hpp>

#include "runtime/support/big_stack.h"
#include "frontend/fscript/formatter.h"
#include "frontend/fscript/parser.h"

using namespace fscript::frontend;

static std::string fmt(const std::string& s, size_t* errors = nullptr) {
  SourceFile f("t.fs", s);
  DiagnosticSink d;
  auto p = parse(f, d);
  if (errors) *errors = d.error_count();
  return format_program(*p, s);
}

TEST_CASE("parser: precedence and associativity") {
  CHECK(fmt("a = -x^2;") == "a = -x ^ 2;\n");
  CHECK(fmt("a = (-x)^2;") == "a = (-x) ^ 2;\n");
  CHECK(fmt("a = 2^-1;") == "a = 2 ^ -1;\n");
  CHECK(fmt("a = (a^b)^c;") == "a = (a ^ b) ^ c;\n");
  CHECK(fmt("a = a^(b^c);") == "a = a ^ b ^ c;\n");
  CHECK(fmt("a = (a | b) & c;") == "a = (a | b) & c;\n");
  CHECK(fmt("a = a | (b & c);") == "a = a | b & c;\n");
  CHECK(fmt("a = (a - b) - c;") == "a = a - b - c;\n");
  CHECK(fmt("a = a - (b - c);") == "a = a - (b - c);\n");
  CHECK(fmt("a = b = c;") == "a = b = c;\n");
  CHECK(fmt("a = c ? d : e ? f : g;") == "a = c ? d : e ? f : g;\n");
  CHECK(fmt("a = - -x;") == "a = - -x;\n");
  CHECK(fmt("a = x ** 2;") == "a = x ^ 2;\n");
  CHECK(fmt("a = Math.sin(Math.PI);") == "a = sin(pi);\n");
}

TEST_CASE("parser: formatting is idempotent and keeps comments") {
  std::string src =
      "// head\nfunction f(x){ // trailing\n var a=[1,2,3]; if(x>0){return a[0];}else if (x<0) return 1; else {return "
      "2}\n"
      "for(var i=0;i<3;i++){x+=i} do x--; while(x>0)\n /* tail */ }\n";
  std::string once = fmt(src);
  CHECK(fmt(once) == once);
  CHECK(once.find("// head") != std::string::npos);
  CHECK(once.find("// trailing") != std::string::npos);
  CHECK(once.find("/* tail */") != std::string::npos);
}

TEST_CASE("parser: every error once, in one run") {
  size_t errors = 0;
  fmt("function f(x) { return x + ; }\nfunction g(x) { var = 1; }\nfunction h( { }\n", &errors);
  CHECK(errors == 3);
}

TEST_CASE("parser: 100,000-deep nesting is one clear error, not a crash") {
  std::string s = "a = " + std::string(100000, '(') + "1" + std::string(100000, ')') + ";";
  SourceFile f("t.fs", s);
  DiagnosticSink d;
  fscript::support::run_with_big_stack([&] { parse(f, d); });
  REQUIRE(d.error_count() == 1);
  CHECK(d.all()[0].message.find("nesting deeper than") != std::string::npos);
}

TEST_CASE("parser: a 1 MB expression parses") {
  std::string s = "function FRep(x, y, z) { return x";
  while (s.size() < (1u << 20)) s += " + x";
  s += "; }";
  SourceFile f("t.fs", s);
  DiagnosticSink d;
  std::unique_ptr<Program> p;
  fscript::support::run_with_big_stack([&] { p = parse(f, d); });
  CHECK(!d.has_errors());
  REQUIRE(p->top.size() == 1);
}
