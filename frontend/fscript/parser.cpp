// FScript parser. Grammar, lowest precedence first (docs/language.md has the full table):
//   assign  -> cond (('=' | '+=' | ...) assign)?        cond -> binary ('?' assign ':' assign)?
//   binary  -> unary (binop unary)*  by precedence       unary -> ('-'|'+'|'!'|'++'|'--') unary | power
//   power   -> postfix (('^'|'**') unary)?               postfix -> primary ('(' args ')' | '[' e ']' | '.' id | '++' | '--')*
#include "frontend/fscript/parser.h"

#include <cmath>
#include <string>

namespace fscript::frontend {
namespace {

// Binary precedence levels 3..10 of the language table; 0 = not a binary operator.
int binary_prec(Tok t) {
  switch (t) {
    case Tok::OrOr: return 3;
    case Tok::AndAnd: return 4;
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
    case Tok::Star:
    case Tok::Slash:
    case Tok::Percent: return 10;
    default: return 0;
  }
}

bool is_assign_op(Tok t) {
  switch (t) {
    case Tok::Assign:
    case Tok::PlusAssign:
    case Tok::MinusAssign:
    case Tok::StarAssign:
    case Tok::SlashAssign:
    case Tok::PercentAssign:
    case Tok::CaretAssign: return true;
    default: return false;
  }
}

class Parser {
 public:
  Parser(const SourceFile& f, DiagnosticSink& d, std::vector<Token> toks) : f_(f), diag_(d), toks_(std::move(toks)) {}

  std::unique_ptr<Program> run(std::vector<Comment> comments) {
    prog_ = std::make_unique<Program>();
    prog_->comments = std::move(comments);
    while (!at(Tok::Eof)) {
      size_t before = pos_;
      prog_->top.push_back(statement(true));
      if (pos_ == before) advance();  // guarantee progress
    }
    auto& top = prog_->top;
    prog_->single_expression =
        top.size() == 1 && top[0]->kind == StmtKind::ExprStmt && top[0]->expr->kind != ExprKind::Assign;
    return std::move(prog_);
  }

 private:
  // ---- token helpers ----
  const Token& cur() const { return toks_[pos_]; }
  const Token& prev() const { return toks_[pos_ > 0 ? pos_ - 1 : 0]; }
  bool at(Tok t) const { return cur().kind == t; }
  const Token& advance() {
    if (!at(Tok::Eof)) ++pos_;
    return prev();
  }
  bool accept(Tok t) {
    if (!at(t)) return false;
    advance();
    return true;
  }
  std::string_view text(Span s) const { return std::string_view(f_.text()).substr(s.begin, s.end - s.begin); }
  Span from(Span start) const { return {start.begin, std::max(start.begin, prev().span.end)}; }

  // One diagnostic per mistake: after an error, stay quiet until the parser resynchronizes.
  void error_at(Span s, const std::string& msg) {
    if (panic_ || fatal_) return;
    panic_ = true;
    diag_.error(f_, s, msg);
  }
  void expected(const std::string& what) {
    if (at(Tok::Error)) {  // the lexer already reported this token
      panic_ = true;
      return;
    }
    std::string got = at(Tok::Eof) ? "end of input" : "'" + std::string(text(cur().span)) + "'";
    error_at(cur().span, "expected " + what + ", found " + got);
  }
  bool expect(Tok t, const char* context) {
    if (accept(t)) return true;
    expected(std::string("'") + token_spelling(t) + "' " + context);
    return false;
  }
  // Automatic semicolon insertion: a line break, '}' or end of input ends a statement.
  void end_statement() {
    if (accept(Tok::Semi) || at(Tok::RBrace) || at(Tok::Eof) || cur().newline_before) return;
    expected("';' after statement");
    synchronize();
  }
  // Skips to a point where a statement can start; clears panic mode.
  void synchronize() {
    int depth = 0;  // braces opened while skipping are skipped whole
    while (!at(Tok::Eof)) {
      if (at(Tok::LBrace)) {
        ++depth;
        advance();
        continue;
      }
      if (at(Tok::RBrace) && depth > 0) {
        --depth;
        advance();
        if (depth == 0 && (at(Tok::RBrace) || cur().newline_before)) break;
        continue;
      }
      if (depth > 0) {
        advance();
        continue;
      }
      if (accept(Tok::Semi)) break;
      if (at(Tok::RBrace)) break;
      Tok k = cur().kind;
      if (cur().newline_before &&
          (k == Tok::KwVar || k == Tok::KwLet || k == Tok::KwConst || k == Tok::KwIf || k == Tok::KwFor ||
           k == Tok::KwWhile || k == Tok::KwDo || k == Tok::KwReturn || k == Tok::KwFunction))
        break;
      advance();
    }
    panic_ = false;
  }
  // After this error the parser skips the rest of the file and reports nothing more.
  bool enter(Span where) {
    if (++depth_ <= kMaxNesting) return true;
    error_at(where, "nesting deeper than " + std::to_string(kMaxNesting) + " levels");
    fatal_ = true;
    return false;
  }
  struct DepthGuard {
    int& d;
    ~DepthGuard() { --d; }
  };

  // ---- statements ----
  // stmt -> block | var_decl | if | for | while | do | break | continue | return | function | expr ';'
  Stmt* statement(bool top_level) {
    DepthGuard g{depth_};
    if (!enter(cur().span)) {
      Stmt* s = prog_->new_stmt(StmtKind::Error, cur().span);
      skip_to_eof();
      return s;
    }
    Stmt* s = statement_inner(top_level);
    if (panic_) synchronize();
    return s;
  }

  void skip_to_eof() {
    while (!at(Tok::Eof)) advance();
  }

  Stmt* statement_inner(bool top_level) {
    Span start = cur().span;
    switch (cur().kind) {
      case Tok::LBrace: return block();
      case Tok::KwVar:
      case Tok::KwLet:
      case Tok::KwConst: {
        Stmt* s = var_decl();
        end_statement();
        s->span = from(start);
        return s;
      }
      case Tok::KwIf: return if_stmt();
      case Tok::KwFor: return for_stmt();
      case Tok::KwWhile: return while_stmt();
      case Tok::KwDo: return do_stmt();
      case Tok::KwBreak:
      case Tok::KwContinue: {
        StmtKind kind = at(Tok::KwBreak) ? StmtKind::Break : StmtKind::Continue;
        Stmt* s = prog_->new_stmt(kind, advance().span);
        end_statement();
        return s;
      }
      case Tok::KwReturn: return return_stmt();
      case Tok::KwFunction: return function_decl(top_level);
      case Tok::Semi: return prog_->new_stmt(StmtKind::Empty, advance().span);
      case Tok::RBrace:
        error_at(cur().span, "unexpected '}' (no block is open here)");
        return prog_->new_stmt(StmtKind::Error, advance().span);
      default: {
        Stmt* s = prog_->new_stmt(StmtKind::ExprStmt, start);
        s->expr = expression();
        end_statement();
        s->span = from(start);
        return s;
      }
    }
  }

  // block -> '{' stmt* '}'
  Stmt* block() {
    Span start = cur().span;
    Stmt* s = prog_->new_stmt(StmtKind::Block, start);
    expect(Tok::LBrace, "to open a block");
    while (!at(Tok::RBrace) && !at(Tok::Eof)) {
      size_t before = pos_;
      s->stmts.push_back(statement(false));
      if (pos_ == before) advance();
    }
    if (!accept(Tok::RBrace)) {
      panic_ = false;
      error_at(start, "unterminated block: '{' has no matching '}'");
    }
    s->span = from(start);
    return s;
  }

  // var_decl -> ('var'|'let'|'const') name ('=' assign)? (',' name ('=' assign)?)*
  Stmt* var_decl() {
    Stmt* s = prog_->new_stmt(StmtKind::Var, cur().span);
    s->decl_kind = advance().kind;
    do {
      if (!at(Tok::Ident)) {
        expected("a variable name");
        return s;
      }
      Decl d;
      d.span = advance().span;
      d.name = std::string(text(d.span));
      if (accept(Tok::Assign)) d.init = assignment();
      else if (s->decl_kind == Tok::KwConst) error_at(d.span, "'const' declaration of '" + d.name + "' needs a value");
      s->decls.push_back(d);
    } while (accept(Tok::Comma));
    return s;
  }

  Expr* paren_condition(const char* what) {
    expect(Tok::LParen, (std::string("after '") + what + "'").c_str());
    Expr* e = expression();
    expect(Tok::RParen, (std::string("after the condition of '") + what + "'").c_str());
    return e;
  }

  // if -> 'if' '(' expr ')' stmt ('else' stmt)?
  Stmt* if_stmt() {
    Stmt* s = prog_->new_stmt(StmtKind::If, advance().span);
    s->expr = paren_condition("if");
    s->body = statement(false);
    if (accept(Tok::KwElse)) s->else_body = statement(false);
    s->span = from(s->span);
    return s;
  }

  // for -> 'for' '(' (var_decl | expr)? ';' expr? ';' expr? ')' stmt
  Stmt* for_stmt() {
    Stmt* s = prog_->new_stmt(StmtKind::For, advance().span);
    expect(Tok::LParen, "after 'for'");
    if (at(Tok::KwVar) || at(Tok::KwLet) || at(Tok::KwConst)) {
      s->init = var_decl();
    } else if (!at(Tok::Semi)) {
      s->init = prog_->new_stmt(StmtKind::ExprStmt, cur().span);
      s->init->expr = expression();
    }
    expect(Tok::Semi, "after the initializer of 'for'");
    if (!at(Tok::Semi)) s->expr = expression();
    expect(Tok::Semi, "after the condition of 'for'");
    if (!at(Tok::RParen)) s->step = expression();
    expect(Tok::RParen, "to close 'for ('");
    s->body = statement(false);
    s->span = from(s->span);
    return s;
  }

  // while -> 'while' '(' expr ')' stmt
  Stmt* while_stmt() {
    Stmt* s = prog_->new_stmt(StmtKind::While, advance().span);
    s->expr = paren_condition("while");
    s->body = statement(false);
    s->span = from(s->span);
    return s;
  }

  // do -> 'do' stmt 'while' '(' expr ')' ';'?
  Stmt* do_stmt() {
    Stmt* s = prog_->new_stmt(StmtKind::DoWhile, advance().span);
    s->body = statement(false);
    if (expect(Tok::KwWhile, "after the body of 'do'")) s->expr = paren_condition("while");
    accept(Tok::Semi);
    s->span = from(s->span);
    return s;
  }

  // return -> 'return' expr? ';'   (a value must start on the same line, as in JavaScript)
  Stmt* return_stmt() {
    Stmt* s = prog_->new_stmt(StmtKind::Return, advance().span);
    if (!at(Tok::Semi) && !at(Tok::RBrace) && !at(Tok::Eof) && !cur().newline_before) s->expr = expression();
    end_statement();
    s->span = from(s->span);
    return s;
  }

  // function -> 'function' name '(' (name (',' name)*)? ')' block
  Stmt* function_decl(bool top_level) {
    Stmt* s = prog_->new_stmt(StmtKind::Function, advance().span);
    if (!top_level) error_at(s->span, "functions can only be declared at the top level");
    if (!at(Tok::Ident)) {
      expected("a function name after 'function'");
      return s;
    }
    s->name_span = advance().span;
    s->name = std::string(text(s->name_span));
    expect(Tok::LParen, "after the function name");
    if (!at(Tok::RParen)) {
      do {
        if (!at(Tok::Ident)) {
          expected("a parameter name");
          while (!at(Tok::RParen) && !at(Tok::LBrace) && !at(Tok::Eof)) advance();
          break;
        }
        Decl d;
        d.span = advance().span;
        d.name = std::string(text(d.span));
        s->decls.push_back(d);
      } while (accept(Tok::Comma));
    }
    expect(Tok::RParen, "after the parameters");
    if (panic_ && at(Tok::LBrace)) panic_ = false;  // the body is parsed and checked on its own
    if (at(Tok::LBrace)) {
      s->body = block();
    } else {
      expected("'{' to open the function body");
      s->body = prog_->new_stmt(StmtKind::Block, cur().span);
    }
    s->span = from(s->span);
    return s;
  }

  // ---- expressions ----
  Expr* error_expr() { return prog_->new_expr(ExprKind::Error, cur().span); }

  Expr* expression() { return assignment(); }

  // assign -> cond (assign_op assign)?
  Expr* assignment() {
    DepthGuard g{depth_};
    if (!enter(cur().span)) {
      skip_to_eof();
      return error_expr();
    }
    Expr* lhs = conditional();
    if (!is_assign_op(cur().kind)) return lhs;
    Token op = advance();
    if (lhs->kind != ExprKind::Name && lhs->kind != ExprKind::Index && lhs->kind != ExprKind::Error)
      error_at(op.span, "the left side of '" + std::string(token_spelling(op.kind)) + "' cannot be assigned to");
    Expr* e = prog_->new_expr(ExprKind::Assign, lhs->span);
    e->op = op.kind;
    e->kids = {lhs, assignment()};
    e->span = from(lhs->span);
    return e;
  }

  // cond -> binary ('?' assign ':' assign)?
  Expr* conditional() {
    Expr* c = binary(3);
    if (!accept(Tok::Question)) return c;
    Expr* e = prog_->new_expr(ExprKind::Conditional, c->span);
    Expr* a = assignment();
    expect(Tok::Colon, "in conditional expression");
    Expr* b = assignment();
    e->kids = {c, a, b};
    e->span = from(c->span);
    return e;
  }

  // binary -> unary (op unary)* by precedence climbing; left chains iterate, never recurse deeper.
  Expr* binary(int min_prec) {
    Expr* lhs = unary();
    while (true) {
      int p = binary_prec(cur().kind);
      if (p == 0 || p < min_prec) return lhs;
      Token op = advance();
      Expr* rhs = binary(p + 1);
      Expr* e = prog_->new_expr(op.kind == Tok::AndAnd || op.kind == Tok::OrOr ? ExprKind::Logical : ExprKind::Binary,
                                lhs->span);
      e->op = op.kind;
      e->kids = {lhs, rhs};
      e->span = from(lhs->span);
      lhs = e;
    }
  }

  // unary -> ('-' | '+' | '!' | '++' | '--') unary | power
  Expr* unary() {
    Tok k = cur().kind;
    if (k != Tok::Minus && k != Tok::Plus && k != Tok::Bang && k != Tok::PlusPlus && k != Tok::MinusMinus)
      return power();
    DepthGuard g{depth_};
    Token op = advance();
    if (!enter(op.span)) {
      skip_to_eof();
      return error_expr();
    }
    Expr* operand = unary();
    if (k == Tok::PlusPlus || k == Tok::MinusMinus) return update(op, operand, true);
    if (k == Tok::Minus && operand->kind == ExprKind::Number) {  // fold "-1" so "-1" prints as a literal
      operand->num = -operand->num;
      operand->span = from(op.span);
      return operand;
    }
    Expr* e = prog_->new_expr(ExprKind::Unary, op.span);
    e->op = k;
    e->kids = {operand};
    e->span = from(op.span);
    return e;
  }

  Expr* update(const Token& op, Expr* target, bool prefix) {
    if (target->kind != ExprKind::Name && target->kind != ExprKind::Index && target->kind != ExprKind::Error)
      error_at(op.span, std::string("'") + token_spelling(op.kind) + "' needs a variable or array element");
    Expr* e = prog_->new_expr(ExprKind::Update, prefix ? op.span : target->span);
    e->op = op.kind;
    e->prefix = prefix;
    e->kids = {target};
    e->span = from(e->span);
    return e;
  }

  // power -> postfix (('^' | '**') unary)?
  Expr* power() {
    Expr* base = postfix();
    if (!at(Tok::Caret) && !at(Tok::StarStar)) return base;
    DepthGuard g{depth_};
    Token op = advance();
    if (!enter(op.span)) {
      skip_to_eof();
      return error_expr();
    }
    Expr* e = prog_->new_expr(ExprKind::Binary, base->span);
    e->op = Tok::Caret;
    e->kids = {base, unary()};
    e->span = from(base->span);
    return e;
  }

  // postfix -> primary ('(' args ')' | '[' expr ']' | '.' ident | '++' | '--')*
  Expr* postfix() {
    Expr* e = primary();
    while (true) {
      if (at(Tok::LParen)) {
        e = call(e);
      } else if (at(Tok::LBracket)) {
        e = index(e);
      } else if (at(Tok::Dot)) {
        e = member(e);
      } else if ((at(Tok::PlusPlus) || at(Tok::MinusMinus)) && !cur().newline_before) {
        Token op = advance();
        e = update(op, e, false);
      } else {
        return e;
      }
    }
  }

  Expr* call(Expr* callee) {
    Span open = advance().span;
    Expr* e = prog_->new_expr(ExprKind::Call, callee->span);
    if (callee->kind != ExprKind::Name) {
      if (callee->kind != ExprKind::Error) error_at(open, "only a function name can be called");
    } else {
      e->name = callee->name;
      e->name_span = callee->span;
      e->builtin_only = callee->builtin_only;
    }
    if (!at(Tok::RParen)) {
      do {
        e->kids.push_back(assignment());
      } while (accept(Tok::Comma));
    }
    expect(Tok::RParen, "to close the argument list");
    e->span = from(callee->span);
    return e;
  }

  Expr* index(Expr* array) {
    Span open = advance().span;
    Expr* e = prog_->new_expr(ExprKind::Index, array->span);
    if (array->kind != ExprKind::Name) {
      if (array->kind != ExprKind::Error) error_at(open, "only a named array can be indexed");
    } else {
      e->name = array->name;
      e->name_span = array->span;
    }
    e->kids = {expression()};
    expect(Tok::RBracket, "to close the index");
    e->span = from(array->span);
    return e;
  }

  // '.length' on an array; 'Math.NAME' is the built-in NAME ('Math.PI' is pi).
  Expr* member(Expr* obj) {
    advance();
    if (!at(Tok::Ident)) {
      expected("a name after '.'");
      return error_expr();
    }
    Span m = advance().span;
    std::string field(text(m));
    if (obj->kind == ExprKind::Name && obj->name == "Math") {
      Expr* e = prog_->new_expr(ExprKind::Name, from(obj->span));
      e->name = field == "PI" ? "pi" : field;
      e->name_span = e->span;
      e->builtin_only = true;
      return e;
    }
    if (field == "length" && obj->kind == ExprKind::Name) {
      Expr* e = prog_->new_expr(ExprKind::Length, from(obj->span));
      e->name = obj->name;
      e->name_span = obj->span;
      return e;
    }
    if (obj->kind != ExprKind::Error)
      error_at(m, "unknown property '" + field + "' (only 'length' of an array and 'Math.' built-ins exist)");
    return error_expr();
  }

  // primary -> number | name | 'true' | 'false' | '(' expr ')' | '[' args ']' | 'new' 'Array' '(' expr ')'
  Expr* primary() {
    const Token& t = cur();
    switch (t.kind) {
      case Tok::Number: {
        Expr* e = prog_->new_expr(ExprKind::Number, advance().span);
        e->num = t.number;
        return e;
      }
      case Tok::KwTrue:
      case Tok::KwFalse: {
        Expr* e = prog_->new_expr(ExprKind::Number, advance().span);
        e->num = t.kind == Tok::KwTrue ? 1 : 0;
        return e;
      }
      case Tok::Ident: {
        Expr* e = prog_->new_expr(ExprKind::Name, advance().span);
        e->name = std::string(text(e->span));
        e->name_span = e->span;
        return e;
      }
      case Tok::LParen: return parenthesized();
      case Tok::LBracket: return array_literal();
      case Tok::KwNew: return new_array();
      default: expected("an expression"); return error_expr();
    }
  }

  Expr* parenthesized() {
    Span open = advance().span;
    Expr* e = expression();
    if (!accept(Tok::RParen)) {
      if (!panic_)
        error_at(cur().span,
                 "expected ')' to match the '(' at column " + std::to_string(f_.position(open.begin).col) +
                     ", found '" + std::string(text(cur().span)) + "'");
    }
    return e;
  }

  Expr* array_literal() {
    Expr* e = prog_->new_expr(ExprKind::ArrayLit, advance().span);
    if (!at(Tok::RBracket)) {
      do {
        e->kids.push_back(assignment());
      } while (accept(Tok::Comma));
    }
    expect(Tok::RBracket, "to close the array literal");
    e->span = from(e->span);
    return e;
  }

  Expr* new_array() {
    Span start = advance().span;
    if (!at(Tok::Ident) || text(cur().span) != "Array") {
      expected("'Array' after 'new'");
      return error_expr();
    }
    Expr* e = prog_->new_expr(ExprKind::NewArray, start);
    advance();
    expect(Tok::LParen, "after 'new Array'");
    e->kids = {at(Tok::RParen) ? prog_->new_expr(ExprKind::Number, cur().span) : expression()};
    expect(Tok::RParen, "to close 'new Array('");
    e->span = from(e->span);
    return e;
  }

  const SourceFile& f_;
  DiagnosticSink& diag_;
  std::vector<Token> toks_;
  size_t pos_ = 0;
  int depth_ = 0;
  bool panic_ = false;
  bool fatal_ = false;
  std::unique_ptr<Program> prog_;
};

}  // namespace

std::unique_ptr<Program> parse(const SourceFile& file, DiagnosticSink& diag) {
  LexResult lr = lex(file, diag);
  Parser p(file, diag, std::move(lr.tokens));
  return p.run(std::move(lr.comments));
}

}  // namespace fscript::frontend
