// Lexer: tokens, numbers, comments, line-break flags, bad input.
#include <catch2/catch.hpp>

#include "frontend/fscript/lexer.h"

using namespace fscript::frontend;

static std::vector<Token> toks(const std::string& s, DiagnosticSink& d) {
  SourceFile f("t.fs", s);
  return lex(f, d).tokens;
}

TEST_CASE("lexer: punctuation takes the longest match") {
  DiagnosticSink d;
  auto t = toks("a === b !== c ** d ^= e && f || g ++ -- <= >=", d);
  std::vector<Tok> kinds;
  for (auto& k : t) kinds.push_back(k.kind);
  std::vector<Tok> want = {Tok::Ident, Tok::EqEqEq,      Tok::Ident,      Tok::NotEqEq, Tok::Ident,     Tok::StarStar,
                           Tok::Ident, Tok::CaretAssign, Tok::Ident,      Tok::AndAnd,  Tok::Ident,     Tok::OrOr,
                           Tok::Ident, Tok::PlusPlus,    Tok::MinusMinus, Tok::LessEq,  Tok::GreaterEq, Tok::Eof};
  CHECK(kinds == want);
  CHECK(!d.has_errors());
}

TEST_CASE("lexer: number forms") {
  DiagnosticSink d;
  auto t = toks("1 1.5 .5 5. 1e-3 2E+2 0x1F 0.1", d);
  REQUIRE(t.size() == 9);
  CHECK(t[0].number == 1);
  CHECK(t[1].number == 1.5);
  CHECK(t[2].number == 0.5);
  CHECK(t[3].number == 5);
  CHECK(t[4].number == static_cast<double>(1e-3f));
  CHECK(t[5].number == 200);
  CHECK(t[6].number == 31);
  CHECK(t[7].number == static_cast<double>(0.1f));  // rounded once, to float
  CHECK(!d.has_errors());
}

TEST_CASE("lexer: keywords, comments and line breaks") {
  DiagnosticSink d;
  auto t = toks("var x // c\n/* a\nb */ let y", d);
  REQUIRE(t.size() == 5);
  CHECK(t[0].kind == Tok::KwVar);
  CHECK(t[2].kind == Tok::KwLet);
  CHECK(t[2].newline_before);
  CHECK(!t[1].newline_before);
  SourceFile f("t.fs", "a // one\n/* two */ b");
  auto r = lex(f, d);
  CHECK(r.comments.size() == 2);
}

TEST_CASE("lexer: errors have positions and never repeat per byte") {
  DiagnosticSink d;
  toks("a @ b \xC3\xA9 c", d);
  REQUIRE(d.error_count() == 2);
  CHECK(d.all()[0].pos.col == 3);
  CHECK(d.all()[0].message.find("unexpected character '@'") != std::string::npos);
  CHECK(d.all()[1].message.find("unexpected byte") != std::string::npos);
  DiagnosticSink d2;
  toks("x /* never closed", d2);
  REQUIRE(d2.error_count() == 1);
  CHECK(d2.all()[0].pos.col == 3);
  CHECK(d2.all()[0].message == "unterminated comment");
}

TEST_CASE("lexer: positions inside an embedded script map to the outer file") {
  SourceFile f("scene.wrl", "ab\ncd", 10, 20);
  CHECK(f.position(0).line == 10);
  CHECK(f.position(0).col == 20);
  CHECK(f.position(1).col == 21);
  CHECK(f.position(3).line == 11);
  CHECK(f.position(3).col == 1);
}
