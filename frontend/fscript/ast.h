#pragma once
// FScript abstract syntax tree. Nodes live in an arena owned by the Program; children are raw
// pointers into it. Sema annotates names with symbol ids; lowering reads those annotations.
#include <memory>
#include <string>
#include <vector>

#include "frontend/fscript/lexer.h"
#include "frontend/source.h"

namespace fscript::frontend {

enum class ExprKind : uint8_t {
  Number,       // num
  Name,         // name
  Unary,        // op kids[0]          (- + !)
  Binary,       // kids[0] op kids[1]  (arithmetic, comparison, & | ^)
  Logical,      // kids[0] op kids[1]  (&& ||), short-circuit
  Conditional,  // kids[0] ? kids[1] : kids[2]
  Assign,       // kids[0] op= kids[1]; kids[0] is Name or Index
  Update,       // ++/-- on kids[0], prefix or postfix
  Call,         // name(kids...)
  Index,        // name[kids[0]]
  Length,       // name.length
  ArrayLit,     // [kids...]
  NewArray,     // new Array(kids[0])
  Error,        // placeholder after a syntax error
};

struct Expr {
  ExprKind kind = ExprKind::Error;
  Span span;
  Tok op = Tok::Eof;
  bool prefix = false;
  bool builtin_only = false;  // Math.NAME: the built-in NAME, even where a user function takes its name
  double num = 0;
  std::string name;  // Name, Call callee, Index/Length array
  Span name_span;
  std::vector<Expr*> kids;
  int sym = -1;  // sema: resolved symbol (Name, Index, Length, Assign/Update targets)
};

enum class StmtKind : uint8_t {
  Block,
  Var,
  ExprStmt,
  If,
  For,
  While,
  DoWhile,
  Break,
  Continue,
  Return,
  Function,
  Empty,
  Error
};

struct Decl {
  std::string name;
  Span span;
  Expr* init = nullptr;
  int sym = -1;
};

struct Stmt {
  StmtKind kind = StmtKind::Error;
  Span span;
  Tok decl_kind = Tok::KwVar;  // Var: var / let / const
  std::vector<Decl> decls;     // Var: declarators; Function: parameters
  Expr* expr = nullptr;        // ExprStmt, If/While/DoWhile/For condition, Return value
  Expr* step = nullptr;        // For
  Stmt* init = nullptr;        // For
  Stmt* body = nullptr;        // If then, loops, Function body
  Stmt* else_body = nullptr;   // If
  std::vector<Stmt*> stmts;    // Block
  std::string name;            // Function
  Span name_span;
};

// A parsed script: top-level statements in order, functions among them.
struct Program {
  std::vector<Stmt*> top;
  std::vector<Comment> comments;
  std::vector<std::unique_ptr<Expr>> expr_arena;
  std::vector<std::unique_ptr<Stmt>> stmt_arena;
  bool single_expression = false;  // the analytical form "0.7^2-x^2-..."

  Expr* new_expr(ExprKind k, Span s) {
    expr_arena.push_back(std::make_unique<Expr>());
    expr_arena.back()->kind = k;
    expr_arena.back()->span = s;
    return expr_arena.back().get();
  }
  Stmt* new_stmt(StmtKind k, Span s) {
    stmt_arena.push_back(std::make_unique<Stmt>());
    stmt_arena.back()->kind = k;
    stmt_arena.back()->span = s;
    return stmt_arena.back().get();
  }
};

}  // namespace fscript::frontend
