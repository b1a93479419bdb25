// The formatter: an AST printer with comment re-attachment by source position.
#include "frontend/fscript/formatter.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace fscript::frontend {

std::string shortest_float(float v) {
  if (std::isnan(v)) return "(0 / 0)";
  if (std::isinf(v)) return v > 0 ? "(1 / 0)" : "(-1 / 0)";
  char buf[32];
  for (int p = 1; p <= 9; ++p) {
    std::snprintf(buf, sizeof buf, "%.*g", p, static_cast<double>(v));
    if (std::strtof(buf, nullptr) == v) break;
  }
  return buf;
}

namespace {

// Precedence levels of the language table; 14 = primary.
int level(const Expr* e) {
  switch (e->kind) {
    case ExprKind::Assign: return 1;
    case ExprKind::Conditional: return 2;
    case ExprKind::Logical: return e->op == Tok::OrOr ? 3 : 4;
    case ExprKind::Binary:
      switch (e->op) {
        case Tok::Pipe: return 5;
        case Tok::Amp: return 6;
        case Tok::EqEq:
        case Tok::NotEq:
        case Tok::EqEqEq:
        case Tok::NotEqEq: return 7;
        case Tok::Less:
        case Tok::LessEq:
        case Tok::Greater:
        case Tok::GreaterEq: return 8;
        case Tok::Plus:
        case Tok::Minus: return 9;
        case Tok::Caret:
        case Tok::StarStar: return 12;
        default: return 10;
      }
    case ExprKind::Unary: return 11;
    case ExprKind::Update: return e->prefix ? 11 : 13;
    case ExprKind::Number: return e->num < 0 || std::signbit(e->num) ? 11 : 14;
    default: return 14;
  }
}

class Formatter {
 public:
  Formatter(const Program& p, const std::string& src) : p_(p), src_(src) {}

  std::string run() {
    for (Stmt* s : p_.top) {
      if (s->kind == StmtKind::Function && !out_.empty() && last_kind_ != StmtKind::Function) blank_line();
      else if (last_kind_ == StmtKind::Function) blank_line();
      stmt(s, 0);
      last_kind_ = s->kind;
    }
    comments_before(UINT32_MAX, 0);
    return out_;
  }

 private:
  void blank_line() {
    if (out_.size() >= 2 && out_.substr(out_.size() - 2) != "\n\n") out_ += "\n";
  }
  void line(int indent, const std::string& text) { out_ += std::string(indent * 2, ' ') + text + "\n"; }

  // Emits comments that start before `pos`, each on its own line (or after the previous line).
  void comments_before(uint32_t pos, int indent) {
    while (next_comment_ < p_.comments.size() && p_.comments[next_comment_].span.begin < pos) {
      const Comment& c = p_.comments[next_comment_++];
      std::string text = src_.substr(c.span.begin, c.span.end - c.span.begin);
      if (!c.own_line && !out_.empty() && out_.back() == '\n') {
        out_.pop_back();
        out_ += " " + text + "\n";
      } else {
        line(indent, text);
      }
    }
  }

  // ---- statements ----
  void stmt(const Stmt* s, int indent) {
    comments_before(s->span.begin, indent);
    switch (s->kind) {
      case StmtKind::Block:
        line(indent, "{");
        block_body(s, indent);
        line(indent, "}");
        break;
      case StmtKind::Function: function(s, indent); break;
      case StmtKind::Var: line(indent, var_text(s) + ";"); break;
      case StmtKind::ExprStmt: line(indent, expr(s->expr) + ";"); break;
      case StmtKind::Return: line(indent, s->expr ? "return " + expr(s->expr) + ";" : "return;"); break;
      case StmtKind::Break: line(indent, "break;"); break;
      case StmtKind::Continue: line(indent, "continue;"); break;
      case StmtKind::Empty: line(indent, ";"); break;
      case StmtKind::If: if_stmt(s, indent, ""); break;
      case StmtKind::While: body_stmt("while (" + expr(s->expr) + ")", s->body, indent); break;
      case StmtKind::For: {
        std::string init = !s->init ? "" : s->init->kind == StmtKind::Var ? var_text(s->init) : expr(s->init->expr);
        std::string head =
            "for (" + init + "; " + (s->expr ? expr(s->expr) : "") + "; " + (s->step ? expr(s->step) : "") + ")";
        body_stmt(head, s->body, indent);
        break;
      }
      case StmtKind::DoWhile: {
        std::string tail = "while (" + expr(s->expr) + ");";
        if (s->body->kind == StmtKind::Block) {
          line(indent, "do {");
          block_body(s->body, indent);
          line(indent, "} " + tail);
        } else {
          line(indent, "do");
          stmt(s->body, indent + 1);
          line(indent, tail);
        }
        break;
      }
      case StmtKind::Error: break;
    }
  }

  void block_body(const Stmt* b, int indent) {
    for (const Stmt* k : b->stmts) stmt(k, indent + 1);
    comments_before(b->span.end, indent + 1);
  }

  void body_stmt(const std::string& head, const Stmt* body, int indent) {
    if (body->kind == StmtKind::Block) {
      line(indent, head + " {");
      block_body(body, indent);
      line(indent, "}");
    } else {
      line(indent, head);
      stmt(body, indent + 1);
    }
  }

  // if -> "if (c) {" ... "} else if (d) {" ... "} else {" ... "}"
  void if_stmt(const Stmt* s, int indent, const std::string& prefix) {
    std::string head = prefix + "if (" + expr(s->expr) + ")";
    if (!s->else_body) return body_stmt(head, s->body, indent);
    bool braced = s->body->kind == StmtKind::Block;
    if (braced) {
      line(indent, head + " {");
      block_body(s->body, indent);
    } else {
      line(indent, head);
      stmt(s->body, indent + 1);
    }
    const Stmt* e = s->else_body;
    std::string lead = braced ? "} else" : "else";
    if (e->kind == StmtKind::If) return if_stmt(e, indent, lead + " ");
    if (e->kind == StmtKind::Block) {
      line(indent, lead + " {");
      block_body(e, indent);
      line(indent, "}");
      return;
    }
    if (braced) line(indent, "}");
    line(indent, "else");
    stmt(e, indent + 1);
  }

  void function(const Stmt* s, int indent) {
    std::string head = "function " + s->name + "(";
    for (size_t k = 0; k < s->decls.size(); ++k) head += (k ? ", " : "") + s->decls[k].name;
    line(indent, head + ") {");
    if (s->body) block_body(s->body, indent);
    line(indent, "}");
  }

  std::string var_text(const Stmt* s) {
    std::string t = s->decl_kind == Tok::KwLet ? "let " : s->decl_kind == Tok::KwConst ? "const " : "var ";
    for (size_t k = 0; k < s->decls.size(); ++k) {
      t += (k ? ", " : "") + s->decls[k].name;
      if (s->decls[k].init) t += " = " + expr(s->decls[k].init);
    }
    return t;
  }

  // ---- expressions ----
  std::string sub(const Expr* e, int min_level) {
    std::string t = expr(e);
    return level(e) < min_level ? "(" + t + ")" : t;
  }

  std::string expr(const Expr* e) {
    switch (e->kind) {
      case ExprKind::Number: return shortest_float(static_cast<float>(e->num));
      case ExprKind::Name: return e->name;
      case ExprKind::Unary: {
        std::string op = token_spelling(e->op);
        std::string operand = sub(e->kids[0], 11);
        bool clash = (op == "-" && operand[0] == '-') || (op == "+" && operand[0] == '+');
        return op + (clash ? " " : "") + operand;
      }
      case ExprKind::Binary:
      case ExprKind::Logical: {
        int l = level(e);
        bool power = l == 12;
        std::string lhs = sub(e->kids[0], power ? 13 : l);
        std::string rhs = sub(e->kids[1], power ? 11 : l + 1);
        return lhs + " " + token_spelling(e->op == Tok::StarStar ? Tok::Caret : e->op) + " " + rhs;
      }
      case ExprKind::Conditional: return sub(e->kids[0], 3) + " ? " + sub(e->kids[1], 1) + " : " + sub(e->kids[2], 1);
      case ExprKind::Assign: return sub(e->kids[0], 13) + " " + token_spelling(e->op) + " " + sub(e->kids[1], 1);
      case ExprKind::Update:
        return e->prefix ? token_spelling(e->op) + sub(e->kids[0], 13) : sub(e->kids[0], 13) + token_spelling(e->op);
      case ExprKind::Call: return e->name + "(" + list(e->kids) + ")";
      case ExprKind::Index: return e->name + "[" + expr(e->kids[0]) + "]";
      case ExprKind::Length: return e->name + ".length";
      case ExprKind::ArrayLit: return "[" + list(e->kids) + "]";
      case ExprKind::NewArray: return "new Array(" + expr(e->kids[0]) + ")";
      case ExprKind::Error: return "";
    }
    return "";
  }

  std::string list(const std::vector<Expr*>& kids) {
    std::string t;
    for (size_t k = 0; k < kids.size(); ++k) t += (k ? ", " : "") + sub(kids[k], 1);
    return t;
  }

  const Program& p_;
  const std::string& src_;
  std::string out_;
  size_t next_comment_ = 0;
  StmtKind last_kind_ = StmtKind::Empty;
};

}  // namespace

std::string format_program(const Program& prog, const std::string& source) { return Formatter(prog, source).run(); }

}  // namespace fscript::frontend
