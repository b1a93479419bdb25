// FScript semantic analysis. Two walks over the same scope logic: the first collects implicit
// globals (names assigned while not declared in scope), the second resolves every name with
// diagnostics. Then the call graph (recursion) and the script's form and entry points.
#include "frontend/fscript/sema.h"

#include <algorithm>
#include <cctype>
#include <functional>
#include <unordered_map>

namespace fscript::frontend {

const BuiltinInfo kBuiltins[] = {
#define FS_BUILTIN(N, A, OP, SIG, DOC) {N, A, SIG, DOC},
#include "frontend/fscript/builtins.def"
};
const int kNumBuiltins = sizeof(kBuiltins) / sizeof(kBuiltins[0]);

int find_builtin(const std::string& name) {
  for (int i = 0; i < kNumBuiltins; ++i)
    if (name == kBuiltins[i].name) return i;
  return -1;
}

static std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

int SemaResult::function_index(const std::string& name, bool ignore_case) const {
  for (size_t i = 0; i < functions.size(); ++i)
    if (functions[i].name == name) return static_cast<int>(i);
  if (ignore_case)
    for (size_t i = 0; i < functions.size(); ++i)
      if (lower(functions[i].name) == lower(name)) return static_cast<int>(i);
  return -1;
}

int SemaResult::global_slot(const std::string& name) const {
  auto it = std::find(globals.begin(), globals.end(), name);
  return it == globals.end() ? -1 : static_cast<int>(it - globals.begin());
}

namespace {

bool is_array_init(const Expr* e) { return e && (e->kind == ExprKind::ArrayLit || e->kind == ExprKind::NewArray); }

class Sema {
 public:
  Sema(Program& p, const SourceFile& f, DiagnosticSink& d) : prog_(p), f_(f), diag_(d) {}

  SemaResult run(const std::vector<std::string>& extra_globals) {
    for (const char* g : kStandardGlobals) add_global(g, {}, false);
    for (const auto& g : extra_globals) add_global(g, {}, false);
    pi_ = add_symbol({"pi", SymKind::Constant, {}, -1, -1, false, true, false});
    collect_functions();
    collect_top_level_decls(prog_.top);
    collecting_ = true;
    walk_program();
    collecting_ = false;
    walk_program();
    find_recursion();
    find_form_and_entries();
    return std::move(r_);
  }

 private:
  // ---- symbols ----
  int add_symbol(Symbol s) {
    r_.symbols.push_back(std::move(s));
    return static_cast<int>(r_.symbols.size()) - 1;
  }
  int add_global(const std::string& name, Span decl, bool is_array) {
    auto it = globals_.find(name);
    if (it != globals_.end()) return it->second;
    Symbol s{name, SymKind::Global, decl, -1, -1, is_array, false, false};
    if (is_array) {
      s.slot = static_cast<int>(r_.global_arrays.size());
      r_.global_arrays.push_back(name);
    } else {
      s.slot = static_cast<int>(r_.globals.size());
      r_.globals.push_back(name);
    }
    int id = add_symbol(s);
    globals_[name] = id;
    return id;
  }
  int add_local(const Decl& d, bool is_array, bool is_const, bool is_param) {
    Symbol s{d.name, SymKind::Local, d.span, cur_fn_, -1, is_array, is_const, is_param};
    if (is_array) {
      auto& table = r_.local_arrays[cur_fn_ + 1];
      s.slot = static_cast<int>(table.size());
      table.push_back(d.name + "." + std::to_string(table.size()));
    }
    return add_symbol(s);
  }

  void note_assigned(const std::string& name) {
    auto& a = r_.assigned_globals;
    if (std::find(a.begin(), a.end(), name) == a.end()) a.push_back(name);
  }
  void error(Span s, const std::string& m) {
    if (!collecting_) diag_.error(f_, s, m);
  }
  void warning(Span s, const std::string& m) {
    if (!collecting_) diag_.warning(f_, s, m);
  }

  // ---- declarations ----
  void collect_functions() {
    for (Stmt* s : prog_.top) {
      if (s->kind != StmtKind::Function || s->name.empty()) continue;
      if (fn_syms_.count(s->name)) {
        diag_.error(f_, s->name_span, "redefinition of function '" + s->name + "'");
        continue;
      }
      FunctionInfo fi;
      fi.decl = s;
      fi.name = s->name;
      fi.symbol = add_symbol(
          {s->name, SymKind::Function, s->name_span, -1, static_cast<int>(r_.functions.size()), false, true, false});
      fn_syms_[s->name] = fi.symbol;
      r_.functions.push_back(fi);
    }
    r_.local_arrays.resize(r_.functions.size() + 1);  // [0] is the top-level code
  }

  // Top-level var (anywhere outside functions) and top-level let/const are globals.
  void collect_top_level_decls(const std::vector<Stmt*>& stmts) {
    for (Stmt* s : stmts) hoist_vars(s, true);
  }

  // Visits var declarations of a function body (or the top level) for hoisting.
  void hoist_vars(Stmt* s, bool top) {
    if (!s) return;
    std::vector<Stmt*> stack{s};
    while (!stack.empty()) {
      Stmt* c = stack.back();
      stack.pop_back();
      if (!c || c->kind == StmtKind::Function) continue;
      if (c->kind == StmtKind::Var && (c->decl_kind == Tok::KwVar || (top && c == s)))
        for (auto& d : c->decls) hoist_decl(d, top, c->decl_kind == Tok::KwConst && top);
      for (Stmt* k : c->stmts) stack.push_back(k);
      stack.push_back(c->body);
      stack.push_back(c->else_body);
      stack.push_back(c->init);
    }
  }

  void hoist_decl(Decl& d, bool top, bool is_const) {
    bool arr = is_array_init(d.init);
    if (top) {
      auto it = globals_.find(d.name);
      if (it != globals_.end() && r_.symbols[it->second].is_array != arr) {
        diag_.error(f_, d.span, "'" + d.name + "' is used both as an array and as a number");
        return;
      }
      int id = add_global(d.name, d.span, arr);
      if (is_const) r_.symbols[id].is_const = true;
      if (d.init && !arr) note_assigned(d.name);
      d.sym = id;
      return;
    }
    auto& fs = scopes_.front();
    auto it = fs.find(d.name);
    if (it != fs.end()) {
      Symbol& s = r_.symbols[it->second];
      if (arr != s.is_array && (d.init || s.is_param))
        error(d.span, "'" + d.name + "' is used both as an array and as a number");
      d.sym = it->second;
      return;
    }
    fs[d.name] = d.sym = add_local(d, arr, false, false);
  }

  // ---- walking ----
  void walk_program() {
    cur_fn_ = -1;
    scopes_.clear();
    scopes_.emplace_back();  // the top-level code's block scope (let/const inside blocks)
    loop_depth_ = 0;
    for (Stmt* s : prog_.top) {
      if (s->kind == StmtKind::Function) continue;
      stmt(s, true);
    }
    for (size_t i = 0; i < r_.functions.size(); ++i) walk_function(static_cast<int>(i));
  }

  void walk_function(int fi) {
    FunctionInfo& info = r_.functions[fi];
    Stmt* fn = info.decl;
    cur_fn_ = fi;
    scopes_.clear();
    scopes_.emplace_back();
    loop_depth_ = 0;
    if (collecting_) {
      for (auto& p : fn->decls) {
        p.sym = add_local(p, false, false, true);
        info.params.push_back(p.sym);
      }
    } else {
      for (size_t i = 0; i < fn->decls.size(); ++i)
        for (size_t j = 0; j < i; ++j)
          if (fn->decls[i].name == fn->decls[j].name)
            error(fn->decls[i].span, "duplicate parameter '" + fn->decls[i].name + "'");
    }
    for (auto& p : fn->decls) scopes_.front()[p.name] = p.sym;
    if (collecting_) hoist_vars(fn->body, false);
    else rebuild_function_scope(fn->body);
    if (fn->body)
      for (Stmt* s : fn->body->stmts) stmt(s, false);
  }

  // The second walk reuses the symbols the first one created for hoisted vars.
  void rebuild_function_scope(Stmt* body) {
    std::vector<Stmt*> stack{body};
    while (!stack.empty()) {
      Stmt* c = stack.back();
      stack.pop_back();
      if (!c) continue;
      if (c->kind == StmtKind::Var && c->decl_kind == Tok::KwVar)
        for (auto& d : c->decls)
          if (d.sym >= 0) scopes_.front()[d.name] = d.sym;
      for (Stmt* k : c->stmts) stack.push_back(k);
      stack.push_back(c->body);
      stack.push_back(c->else_body);
      stack.push_back(c->init);
    }
  }

  void stmt(Stmt* s, bool top_level) {
    if (!s) return;
    switch (s->kind) {
      case StmtKind::Block:
        scopes_.emplace_back();
        for (Stmt* k : s->stmts) stmt(k, false);
        scopes_.pop_back();
        break;
      case StmtKind::Var: var_stmt(s, top_level); break;
      case StmtKind::ExprStmt: value(s->expr); break;
      case StmtKind::If:
        value(s->expr);
        stmt(s->body, false);
        stmt(s->else_body, false);
        break;
      case StmtKind::For:
        scopes_.emplace_back();
        stmt(s->init, false);
        if (s->expr) value(s->expr);
        if (s->step) value(s->step);
        ++loop_depth_;
        stmt(s->body, false);
        --loop_depth_;
        scopes_.pop_back();
        break;
      case StmtKind::While:
      case StmtKind::DoWhile:
        value(s->expr);
        ++loop_depth_;
        stmt(s->body, false);
        --loop_depth_;
        break;
      case StmtKind::Break:
      case StmtKind::Continue:
        if (loop_depth_ == 0)
          error(s->span, std::string("'") + (s->kind == StmtKind::Break ? "break" : "continue") + "' outside a loop");
        break;
      case StmtKind::Return:
        if (cur_fn_ < 0) error(s->span, "'return' outside a function");
        if (s->expr && s->expr->kind == ExprKind::Name && name_is_array(s->expr->name))
          error(s->expr->span, "arrays cannot be returned (they are storage, not values)");
        else if (s->expr) value(s->expr);
        break;
      case StmtKind::Function:
      case StmtKind::Empty:
      case StmtKind::Error: break;
    }
  }

  void var_stmt(Stmt* s, bool top_level) {
    bool global = cur_fn_ < 0 && (top_level || s->decl_kind == Tok::KwVar);
    for (auto& d : s->decls) {
      if (d.init && !is_array_init(d.init)) value(d.init);
      if (is_array_init(d.init)) array_init(d.init);
      if (global || s->decl_kind == Tok::KwVar) {
        if (d.sym >= 0 && !global) scopes_.front()[d.name] = d.sym;
        continue;
      }
      auto& scope = scopes_.back();
      if (scope.count(d.name)) {
        error(d.span, "redeclaration of '" + d.name + "' in the same block");
        continue;
      }
      if (collecting_ || d.sym < 0) d.sym = add_local(d, is_array_init(d.init), s->decl_kind == Tok::KwConst, false);
      scope[d.name] = d.sym;
    }
  }

  void array_init(Expr* e) {
    if (e->kind == ExprKind::NewArray) value(e->kids[0]);
    else
      for (Expr* k : e->kids) value(k);
  }

  // ---- name lookup ----
  int lookup(const std::string& name) const {
    for (auto it = scopes_.rbegin(); it != scopes_.rend(); ++it) {
      auto f = it->find(name);
      if (f != it->end()) return f->second;
    }
    auto g = globals_.find(name);
    if (g != globals_.end()) return g->second;
    if (name == "pi") return pi_;
    auto fn = fn_syms_.find(name);
    if (fn != fn_syms_.end()) return fn->second;
    return -1;
  }
  bool name_is_array(const std::string& name) const {
    int id = lookup(name);
    return id >= 0 && r_.symbols[id].is_array;
  }

  // A known name that differs only in letter case, or "" if none (or several).
  // `builtins_only`: for Math.NAME, which names a built-in even where a user function differs from
  // it only in case.
  std::string case_slip(const std::string& name, bool want_function, bool builtins_only = false) const {
    std::vector<std::string> pool;
    if (want_function) {
      if (!builtins_only)
        for (auto& [n, id] : fn_syms_) pool.push_back(n);
      for (int i = 0; i < kNumBuiltins; ++i) pool.push_back(kBuiltins[i].name);
    } else {
      for (auto& sc : scopes_)
        for (auto& [n, id] : sc) pool.push_back(n);
      for (auto& [n, id] : globals_) pool.push_back(n);
      pool.push_back("pi");
    }
    std::string found, key = lower(name);
    for (auto& n : pool)
      if (lower(n) == key && n != name) {
        if (!found.empty() && found != n) return "";
        found = n;
      }
    return found;
  }

  int resolve_read(Expr* e) {
    int id = lookup(e->name);
    if (id < 0) {
      std::string alt = case_slip(e->name, false);
      if (!alt.empty()) {
        warning(e->span, "'" + e->name + "' is not defined; using '" + alt + "' (names are case-sensitive)");
        id = lookup(alt);
      } else {
        error(e->span, "unknown name '" + e->name + "'");
      }
    }
    return id;
  }

  int resolve_write(Expr* target) {
    int id = lookup(target->name);
    if (id < 0 && collecting_) id = add_global(target->name, target->span, false);
    if (id < 0) return -1;
    const Symbol& s = r_.symbols[id];
    if (collecting_ && s.kind == SymKind::Global) note_assigned(s.name);
    if (s.kind == SymKind::Constant) error(target->span, "cannot assign to the constant '" + s.name + "'");
    else if (s.kind == SymKind::Function) error(target->span, "cannot assign to the function '" + s.name + "'");
    else if (s.is_const) error(target->span, "cannot assign to '" + s.name + "': it is declared const");
    return id;
  }

  // ---- expressions ----
  // Visits an expression used as a value. Left-leaning binary chains are walked with an explicit
  // stack, so a megabyte-long sum never recurses deeply.
  void value(Expr* root) {
    std::vector<Expr*> stack{root};
    while (!stack.empty()) {
      Expr* e = stack.back();
      stack.pop_back();
      if (!e) continue;
      if (e->kind == ExprKind::Binary || e->kind == ExprKind::Logical) {
        stack.push_back(e->kids[1]);
        stack.push_back(e->kids[0]);
        continue;
      }
      expr(e);
    }
  }

  void expr(Expr* e) {
    switch (e->kind) {
      case ExprKind::Number:
      case ExprKind::Error: break;
      case ExprKind::Name: name_read(e); break;
      case ExprKind::Unary: value(e->kids[0]); break;
      case ExprKind::Binary:
      case ExprKind::Logical:
      case ExprKind::Conditional:
        for (Expr* k : e->kids) value(k);
        break;
      case ExprKind::Assign: assign(e); break;
      case ExprKind::Update: update(e); break;
      case ExprKind::Call: call(e); break;
      case ExprKind::Index:
      case ExprKind::Length: array_use(e); break;
      case ExprKind::ArrayLit:
      case ExprKind::NewArray:
        error(e->span, "an array literal can only initialize an array variable");
        array_init(e);
        break;
    }
  }

  void name_read(Expr* e) {
    e->sym = resolve_read(e);
    if (e->sym < 0) return;
    const Symbol& s = r_.symbols[e->sym];
    if (s.is_array) error(e->span, "'" + s.name + "' is an array; use an element 'a[i]' or 'a.length'");
    else if (s.kind == SymKind::Function) error(e->span, "'" + s.name + "' is a function; call it with arguments");
  }

  void assign(Expr* e) {
    Expr* target = e->kids[0];
    Expr* rhs = e->kids[1];
    if (target->kind == ExprKind::Index) {
      array_use(target);
      value(rhs);
      return;
    }
    if (target->kind != ExprKind::Name) return;
    if (is_array_init(rhs)) {
      array_init(rhs);
      e->sym = target->sym = lookup(target->name);
      if (e->op != Tok::Assign || target->sym < 0 || !r_.symbols[target->sym].is_array)
        error(rhs->span, "an array literal can only initialize an array variable");
      return;
    }
    value(rhs);
    if (e->op != Tok::Assign) name_read(target);
    target->sym = e->sym = resolve_write(target);
    if (target->sym >= 0 && r_.symbols[target->sym].is_array)
      error(target->span, "cannot assign a number to the array '" + target->name + "'");
  }

  void update(Expr* e) {
    Expr* target = e->kids[0];
    if (target->kind == ExprKind::Index) return array_use(target);
    if (target->kind != ExprKind::Name) return;
    name_read(target);
    target->sym = e->sym = resolve_write(target);
  }

  void array_use(Expr* e) {
    for (Expr* k : e->kids) value(k);
    int id = lookup(e->name);
    if (id < 0) {
      error(e->name_span, "unknown array '" + e->name + "'");
      return;
    }
    if (!r_.symbols[id].is_array) {
      error(e->name_span, "'" + e->name + "' is not an array");
      return;
    }
    e->sym = id;
  }

  void call(Expr* e) {
    if (e->name.empty()) return;
    for (Expr* a : e->kids) {
      if (a->kind == ExprKind::Name && name_is_array(a->name))
        error(a->span, "arrays cannot be passed to functions (they are storage, not values)");
      else value(a);
    }
    std::string name = e->name;
    int arity = -1;
    auto fn = e->builtin_only ? fn_syms_.end() : fn_syms_.find(name);
    int builtin = find_builtin(name);
    if (fn == fn_syms_.end() && builtin < 0) {
      std::string alt = case_slip(name, true, e->builtin_only);
      if (alt.empty()) {
        error(e->name_span, lookup(name) >= 0 ? "'" + name + "' is not a function" : "unknown function '" + name + "'");
        return;
      }
      warning(e->name_span, "'" + name + "' is not defined; using '" + alt + "' (names are case-sensitive)");
      name = alt;
      fn = e->builtin_only ? fn_syms_.end() : fn_syms_.find(name);
      builtin = find_builtin(name);
    }
    if (fn != fn_syms_.end()) {
      e->sym = fn->second;
      const FunctionInfo& callee = r_.functions[r_.symbols[e->sym].slot];
      arity = static_cast<int>(callee.decl->decls.size());
      if (cur_fn_ >= 0 && !collecting_) r_.functions[cur_fn_].callees.push_back(r_.symbols[e->sym].slot);
    } else {
      e->sym = -2 - builtin;  // builtins are encoded as -2 - index
      arity = kBuiltins[builtin].arity;
    }
    if (static_cast<int>(e->kids.size()) != arity)
      error(e->name_span,
            "'" + name + "' takes " + std::to_string(arity) + " argument" + (arity == 1 ? "" : "s") + " but " +
                std::to_string(e->kids.size()) + (e->kids.size() == 1 ? " was" : " were") + " given");
  }

  // ---- whole-program facts ----
  void find_recursion() {
    size_t n = r_.functions.size();
    for (size_t start = 0; start < n; ++start) {
      std::vector<bool> seen(n, false);
      std::vector<int> stack(r_.functions[start].callees.begin(), r_.functions[start].callees.end());
      while (!stack.empty()) {
        int f = stack.back();
        stack.pop_back();
        if (f == static_cast<int>(start)) {
          r_.functions[start].recursive = true;
          break;
        }
        if (seen[f]) continue;
        seen[f] = true;
        for (int c : r_.functions[f].callees) stack.push_back(c);
      }
    }
  }

  void find_form_and_entries() {
    if (!r_.functions.empty()) r_.form = ScriptForm::Script;
    else if (prog_.single_expression) r_.form = ScriptForm::Expression;
    else r_.form = ScriptForm::Assignments;
    static const char* kParam[3] = {"parametric_x", "parametric_y", "parametric_z"};
    static const char* kColour[3] = {"parametric_r", "parametric_g", "parametric_b"};
    for (size_t i = 0; i < r_.functions.size(); ++i) {
      const FunctionInfo& f = r_.functions[i];
      std::string n = lower(f.name);
      size_t arity = f.decl->decls.size();
      if (n == "frep") {
        if (arity == 3 || arity == 4) r_.entry.frep = static_cast<int>(i);
        else diag_.error(f_, f.decl->name_span, "'" + f.name + "' must take 3 or 4 parameters (x, y, z[, t])");
      }
      for (int k = 0; k < 3; ++k) {
        if (n == kParam[k]) r_.entry.parametric[k] = static_cast<int>(i);
        if (n == kColour[k]) r_.entry.colour[k] = static_cast<int>(i);
        if ((n == kParam[k] || n == kColour[k]) && arity > 4)
          diag_.error(f_, f.decl->name_span, "'" + f.name + "' takes at most 4 parameters (u, v, w, t)");
      }
    }
  }

  Program& prog_;
  const SourceFile& f_;
  DiagnosticSink& diag_;
  SemaResult r_;
  bool collecting_ = false;
  int cur_fn_ = -1;
  int pi_ = -1;
  int loop_depth_ = 0;
  std::vector<std::unordered_map<std::string, int>> scopes_;
  std::unordered_map<std::string, int> globals_;
  std::unordered_map<std::string, int> fn_syms_;
};

}  // namespace

SemaResult analyze(Program& prog, const SourceFile& file, DiagnosticSink& diag,
                   const std::vector<std::string>& extra_globals) {
  return Sema(prog, file, diag).run(extra_globals);
}

}  // namespace fscript::frontend
