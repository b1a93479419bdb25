// Sema: globals, scopes, entry points, diagnostics.
#include <catch2/catch.hpp>

#include "tests/unit/helpers.h"

using namespace fscript;

TEST_CASE("sema: entry points are found without regard to case") {
  auto b = test::build("function frep(x, y, z) { return x; }");
  REQUIRE(b->ok);
  CHECK(b->script.sema.entry.frep == 0);
  auto p = test::build("function PARAMETRIC_X(u, v) { return u; } function parametric_y(u, v) { return v; }");
  REQUIRE(p->ok);
  CHECK(p->script.sema.entry.parametric[0] == 0);
  CHECK(p->script.sema.entry.parametric[1] == 1);
  CHECK(p->script.sema.entry.parametric[2] == -1);
  CHECK(p->kernel->num_outputs() == 3);
}

TEST_CASE("sema: FRep wins over parametric functions") {
  auto b = test::build("function parametric_x(u,v,w){return 5;} function FRep(x,y,z){return 7;}");
  REQUIRE(b->ok);
  CHECK(b->kernel->num_outputs() == 1);
  CHECK(test::eval1(*b, {0, 0, 0}) == 7);
}

TEST_CASE("sema: script forms") {
  auto e = test::build("0.7^2-x^2");
  REQUIRE(e->ok);
  CHECK(e->script.sema.form == frontend::ScriptForm::Expression);
  auto a = test::build("x=u; y=v; z=0;");
  REQUIRE(a->ok);
  CHECK(a->script.sema.form == frontend::ScriptForm::Assignments);
  CHECK(a->kernel->num_outputs() == 3);
}

TEST_CASE("sema: implicit globals from assignments inside functions") {
  auto b = test::build("function set(v) { g1 = v; return 0; } function FRep(x,y,z) { set(x); return g1 + 1; }");
  REQUIRE(b->ok);
  CHECK(test::eval1(*b, {2}) == 3);
}

TEST_CASE("sema: reading another function's local is an unknown name") {
  auto b = test::build("function f() { var loc = 1; return loc; } function g() { return loc; }", "g");
  CHECK(!b->ok);
  CHECK(test::messages(b->diag).find("unknown name 'loc'") != std::string::npos);
}

TEST_CASE("sema: the case-slip rule warns and runs") {
  auto b = test::build("function FRep(x,y,z) { return X + Pi; }");
  REQUIRE(b->ok);
  CHECK(b->diag.error_count() == 0);
  CHECK(b->diag.all().size() == 2);
  CHECK(test::eval1(*b, {1}) == 1 + static_cast<float>(M_PI));
}

TEST_CASE("sema: recursion is detected through cycles") {
  auto b = test::build(
      "function a(n){ return n <= 0 ? 0 : b(n-1); } function b(n){ return a(n); } "
      "function c(n){ return a(n) + 1; }",
      "c");
  REQUIRE(b->ok);
  CHECK(b->script.sema.functions[0].recursive);
  CHECK(b->script.sema.functions[1].recursive);
  CHECK(!b->script.sema.functions[2].recursive);
  CHECK(test::eval1(*b, {5}) == 1);
}
