// AST -> SSA IR. Locals use Braun et al.'s on-the-fly SSA construction (sealed blocks,
// incomplete phis, trivial-phi removal); globals are gload/gstore; control flow is explicit.
#include "frontend/fscript/lower.h"

#include "ir/ssa_builder.h"

#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace fscript::frontend {
namespace {

using ir::Block;
using ir::Inst;
using ir::Op;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

Op builtin_op(int index) {
  static const Op kOps[] = {
#define FS_BUILTIN(N, A, OP, SIG, DOC) Op::OP,
#include "frontend/fscript/builtins.def"
  };
  return kOps[index];
}

Op binary_op(Tok t) {
  switch (t) {
    case Tok::Plus: return Op::Add;
    case Tok::Minus: return Op::Sub;
    case Tok::Star: return Op::Mul;
    case Tok::Slash: return Op::Div;
    case Tok::Percent: return Op::Mod;
    case Tok::Caret:
    case Tok::StarStar: return Op::Pow;
    case Tok::Amp: return Op::Min;
    case Tok::Pipe: return Op::Max;
    case Tok::EqEq:
    case Tok::EqEqEq: return Op::Eq;
    case Tok::NotEq:
    case Tok::NotEqEq: return Op::Ne;
    case Tok::Less: return Op::Lt;
    case Tok::LessEq: return Op::Le;
    case Tok::Greater: return Op::Gt;
    case Tok::GreaterEq: return Op::Ge;
    case Tok::PlusAssign: return Op::Add;
    case Tok::MinusAssign: return Op::Sub;
    case Tok::StarAssign: return Op::Mul;
    case Tok::SlashAssign: return Op::Div;
    case Tok::PercentAssign: return Op::Mod;
    case Tok::CaretAssign: return Op::Pow;
    default: return Op::Add;
  }
}

struct Shared {
  const Program& prog;
  const SemaResult& sema;
  const SourceFile& file;
  DiagnosticSink& diag;
  ir::Module& mod;
  int value_slot = -1;  // "$value" for expression-form scripts
  bool probe = false;   // KernelSpec::probe
  std::vector<int> probe_slots;
};

class AstLowering {
 public:
  AstLowering(Shared& sh, ir::Function* fn, int owner)
      : sh_(sh), fn_(fn), owner_(owner), ssa_(*fn, [this](int var) { return undefined(var); }) {
    cur_ = fn_->add_block();
    ssa_.seal(cur_);
  }

  // ---- entry points ----
  void lower_function(const FunctionInfo& info) {
    for (size_t i = 0; i < info.params.size(); ++i) {
      Inst* p = emit(Op::Param, {});
      p->aux = static_cast<int>(i);
      ssa_.write(info.params[i], cur_, p);
      probe("arg", sym(info.params[i]).name, info.decl->name_span, p);
    }
    for (Stmt* s : info.decl->body->stmts) stmt(s);
    if (cur_) {
      sh_.diag.warning(sh_.file, info.decl->name_span,
                       "'" + info.name + "' can reach its end without 'return'; it returns NaN there");
      emit(Op::Ret, {konst(kNaN)});
    }
    finish();
  }

  void lower_kernel(const KernelSpec& spec) {
    std::vector<Inst*> params;
    for (size_t i = 0; i < spec.input_names.size(); ++i) {
      Inst* p = emit(Op::Param, {});
      p->aux = static_cast<int>(i);
      params.push_back(p);
    }
    for (size_t i = 0; i < spec.input_globals.size(); ++i)
      for (int g : spec.input_globals[i]) gstore(g, params[i]);
    for (Stmt* s : sh_.prog.top)
      if (s->kind != StmtKind::Function) stmt(s);
    if (!cur_) cur_ = fn_->add_block();  // top-level break/return was diagnosed by sema
    std::vector<Inst*> outs;
    for (const auto& o : spec.outputs) {
      if (o.function >= 0) {
        std::vector<Inst*> args;
        for (int a : o.args) args.push_back(params[a]);
        Inst* c = emit(Op::Call, args);
        c->aux = o.function;
        outs.push_back(c);
      } else if (o.global >= 0) {
        Inst* l = emit(Op::GLoad, {});
        l->aux = o.global;
        outs.push_back(l);
      } else {
        outs.push_back(konst(o.constant));
      }
    }
    for (int slot : sh_.probe_slots) outs.push_back(gload(slot));
    fn_->num_results = static_cast<uint32_t>(outs.size());
    emit(Op::Ret, outs);
    finish();
  }

 private:
  // ---- instruction helpers ----
  Inst* emit(Op op, std::vector<Inst*> args, LineCol at = {0, 0}) {
    Inst* i = fn_->make(op);
    i->args = std::move(args);
    i->block = cur_;
    i->line = at.line;
    i->col = at.col;
    cur_->insts.push_back(i);
    return i;
  }
  Inst* konst(float v) {
    Inst* c = emit(Op::Const, {});
    c->imm = v;
    return c;
  }
  // Every value op keeps where it is written (runtime errors, and diagnostics that name the op
  // that makes a NaN): a call at its name, a binary operator at the operator itself.
  LineCol loc_of(Span s) const { return sh_.file.position(s.begin); }
  LineCol operator_at(const Expr* e) const {
    const std::string& text = sh_.file.text();
    uint32_t at = e->kids[0]->span.end, end = std::min<uint32_t>(e->kids[1]->span.begin, text.size());
    while (at < end && (text[at] == ' ' || text[at] == '\t' || text[at] == '\n' || text[at] == '\r' || text[at] == ')'))
      ++at;
    return sh_.file.position(at < end ? at : e->span.begin);
  }
  void gstore(int slot, Inst* v) {
    Inst* s = emit(Op::GStore, {v});
    s->aux = slot;
  }
  Inst* gload(int slot) {
    Inst* l = emit(Op::GLoad, {});
    l->aux = slot;
    return l;
  }
  void add_edge(Block* from, Block* to) { to->preds.push_back(from); }
  void jump(Block* to) {
    Inst* j = emit(Op::Jump, {});
    j->targets = {to};
    add_edge(cur_, to);
    cur_ = nullptr;
  }
  void branch(Inst* cond, Block* t, Block* f) {
    Inst* b = emit(Op::Branch, {cond});
    b->targets = {t, f};
    add_edge(cur_, t);
    add_edge(cur_, f);
    cur_ = nullptr;
  }
  Inst* phi_at(Block* b) {
    Inst* p = fn_->make(Op::Phi);
    p->block = b;
    b->insts.insert(b->insts.begin() + static_cast<long>(b->first_non_phi()), p);
    return p;
  }

  // ---- SSA construction for locals (ir::SsaBuilder) ----
  Inst* undefined_const() {
    Block* entry = fn_->entry();
    Inst* c = fn_->make(Op::Const);
    c->imm = kNaN;
    c->block = entry;
    entry->insts.insert(entry->insts.begin(), c);
    return c;
  }
  Inst* undefined(int var) {
    if (var >= 0 && warned_.insert(var).second)
      sh_.diag.warning(sh_.file, first_read_[var],
                       "'" + sh_.sema.symbols[var].name + "' may be used before it is assigned (it is NaN then)");
    return undefined_const();
  }
  void seal(Block* b) { ssa_.seal(b); }
  void finish() {
    ssa_.finish();
    fn_->remove_unreachable_blocks();
  }

  // ---- the probe (KernelSpec::probe) ----
  void probe(const char* kind, const std::string& name, Span at, Inst* v) {
    if (!sh_.probe || !cur_) return;
    LineCol lc = loc_of(at);
    std::string fn = owner_ >= 0 ? sh_.sema.functions[static_cast<size_t>(owner_)].name : "";
    std::string key = std::string(kProbePrefix) + kind + "|" + fn + "|" + name + "|" + std::to_string(lc.line) + "|" +
        std::to_string(lc.col);
    size_t before = sh_.mod.globals.size();
    int slot = sh_.mod.global_slot(key);
    if (sh_.mod.globals.size() > before) sh_.probe_slots.push_back(slot);
    gstore(slot, v);
  }

  // ---- variables ----
  const Symbol& sym(int id) const { return sh_.sema.symbols[id]; }
  bool is_global(int id) const { return sym(id).kind == SymKind::Global; }
  Inst* read_var(int id, Span at) {
    const Symbol& s = sym(id);
    if (s.kind == SymKind::Constant) return konst(static_cast<float>(M_PI));
    if (s.kind == SymKind::Global) return gload(s.slot);
    if (!first_read_.count(id)) first_read_[id] = at;
    return ssa_.read(id, cur_);
  }
  void write_var(int id, Inst* v) {
    if (is_global(id)) gstore(sym(id).slot, v);
    else ssa_.write(id, cur_, v);
  }
  void array_op(Inst* i, int id) {
    i->aux = sym(id).slot;
    i->array_global = is_global(id);
  }

  // ---- statements ----
  void stmt(Stmt* s) {
    if (!s || !cur_) return;  // code after return/break/continue is unreachable: not lowered
    switch (s->kind) {
      case StmtKind::Block:
        for (Stmt* k : s->stmts) stmt(k);
        break;
      case StmtKind::Var:
        for (const auto& d : s->decls) declare(d);
        break;
      case StmtKind::ExprStmt: {
        Inst* v = expr(s->expr);
        if (sh_.value_slot >= 0 && sh_.prog.single_expression && owner_ < 0) gstore(sh_.value_slot, v);
        break;
      }
      case StmtKind::If: if_stmt(s); break;
      case StmtKind::While: while_stmt(s); break;
      case StmtKind::For: for_stmt(s); break;
      case StmtKind::DoWhile: do_stmt(s); break;
      case StmtKind::Break:
        if (!loops_.empty()) jump(loops_.back().second);
        break;
      case StmtKind::Continue:
        if (!loops_.empty()) jump(loops_.back().first);
        break;
      case StmtKind::Return:
        if (owner_ < 0) break;  // diagnosed by sema
        emit(Op::Ret, {s->expr ? expr(s->expr) : konst(kNaN)});
        cur_ = nullptr;
        break;
      case StmtKind::Function:
      case StmtKind::Empty:
      case StmtKind::Error: break;
    }
  }

  void declare(const Decl& d) {
    if (d.sym < 0) return;
    if (sym(d.sym).is_array) {
      if (d.init) array_init(d.sym, d.init);
      return;
    }
    if (!d.init) return;
    Inst* v = expr(d.init);
    write_var(d.sym, v);
    probe("var", sym(d.sym).name, d.span, v);
  }

  void array_init(int id, Expr* init) {
    LineCol line = loc_of(init->span);
    if (init->kind == ExprKind::NewArray) {
      Inst* n = emit(Op::ANew, {expr(init->kids[0])}, line);
      array_op(n, id);
      return;
    }
    std::vector<Inst*> vals;
    for (Expr* k : init->kids) vals.push_back(expr(k));
    array_op(emit(Op::ANew, {konst(static_cast<float>(vals.size()))}, line), id);
    for (size_t i = 0; i < vals.size(); ++i)
      array_op(emit(Op::AStore, {konst(static_cast<float>(i)), vals[i]}, line), id);
  }

  Block* continue_block(Block* b) {
    if (b->preds.empty()) return nullptr;
    return b;
  }

  void if_stmt(Stmt* s) {
    Inst* c = expr(s->expr);
    probe("if", "", s->span, c);
    Block* then_b = fn_->add_block();
    Block* else_b = s->else_body ? fn_->add_block() : nullptr;
    Block* join = fn_->add_block();
    branch(c, then_b, else_b ? else_b : join);
    seal(then_b);
    cur_ = then_b;
    stmt(s->body);
    if (cur_) jump(join);
    if (else_b) {
      seal(else_b);
      cur_ = else_b;
      stmt(s->else_body);
      if (cur_) jump(join);
    }
    seal(join);
    cur_ = continue_block(join);
  }

  void loop_body(Stmt* s, Block* body, Block* cont, Block* exit) {
    seal(body);
    cur_ = body;
    emit(Op::Tick, {}, loc_of(s->span));
    loops_.push_back({cont, exit});
    stmt(s->body);
    loops_.pop_back();
    if (cur_) jump(cont);
  }

  void while_stmt(Stmt* s) {
    Block* header = fn_->add_block();
    jump(header);
    cur_ = header;
    Inst* c = expr(s->expr);
    Block* body = fn_->add_block();
    Block* exit = fn_->add_block();
    branch(c, body, exit);
    loop_body(s, body, header, exit);
    seal(header);
    seal(exit);
    cur_ = continue_block(exit);
  }

  void for_stmt(Stmt* s) {
    stmt(s->init);
    if (!cur_) return;
    Block* header = fn_->add_block();
    jump(header);
    cur_ = header;
    Block* body = fn_->add_block();
    Block* exit = fn_->add_block();
    if (s->expr) branch(expr(s->expr), body, exit);
    else jump(body);
    Block* step = fn_->add_block();
    loop_body(s, body, step, exit);
    seal(step);
    cur_ = continue_block(step);
    if (cur_) {
      if (s->step) expr(s->step);
      jump(header);
    }
    seal(header);
    seal(exit);
    cur_ = continue_block(exit);
  }

  void do_stmt(Stmt* s) {
    Block* body = fn_->add_block();
    jump(body);
    Block* cond = fn_->add_block();
    Block* exit = fn_->add_block();
    cur_ = body;
    emit(Op::Tick, {}, loc_of(s->span));
    loops_.push_back({cond, exit});
    stmt(s->body);
    loops_.pop_back();
    if (cur_) jump(cond);
    seal(cond);
    cur_ = continue_block(cond);
    if (cur_) branch(expr(s->expr), body, exit);
    seal(body);
    seal(exit);
    cur_ = continue_block(exit);
  }

  // ---- expressions ----
  Inst* expr(Expr* e) {
    switch (e->kind) {
      case ExprKind::Number: return konst(static_cast<float>(e->num));
      case ExprKind::Name: return e->sym >= 0 ? read_var(e->sym, e->span) : konst(kNaN);
      case ExprKind::Unary: {
        Inst* v = expr(e->kids[0]);
        if (e->op == Tok::Minus) return emit(Op::Neg, {v}, loc_of(e->span));
        if (e->op == Tok::Bang) return emit(Op::Not, {v}, loc_of(e->span));
        return v;  // unary plus
      }
      case ExprKind::Binary: return binary_chain(e);
      case ExprKind::Logical: return logical(e);
      case ExprKind::Conditional: return conditional(e);
      case ExprKind::Assign: return assign(e);
      case ExprKind::Update: return update(e);
      case ExprKind::Call: return call(e);
      case ExprKind::Index: {
        Inst* idx = expr(e->kids[0]);
        if (e->sym < 0) return konst(kNaN);
        Inst* l = emit(Op::ALoad, {idx}, loc_of(e->span));
        array_op(l, e->sym);
        return l;
      }
      case ExprKind::Length: {
        if (e->sym < 0) return konst(kNaN);
        Inst* l = emit(Op::ALen, {}, loc_of(e->span));
        array_op(l, e->sym);
        return l;
      }
      case ExprKind::ArrayLit:
      case ExprKind::NewArray:
      case ExprKind::Error: return konst(kNaN);
    }
    return konst(kNaN);
  }

  // Left-leaning chains of binary operators are lowered iteratively (a 1 MB sum is one chain).
  Inst* binary_chain(Expr* e) {
    std::vector<Expr*> spine;
    while (e->kind == ExprKind::Binary) {
      spine.push_back(e);
      e = e->kids[0];
    }
    Inst* acc = expr(e);
    for (auto it = spine.rbegin(); it != spine.rend(); ++it)
      acc = emit(binary_op((*it)->op), {acc, expr((*it)->kids[1])}, operator_at(*it));
    return acc;
  }

  // a && b  ->  truthy(a) ? truth(b) : 0     a || b  ->  truthy(a) ? 1 : truth(b)
  Inst* logical(Expr* e) {
    bool is_and = e->op == Tok::AndAnd;
    Inst* a = expr(e->kids[0]);
    Inst* short_value = konst(is_and ? 0.0f : 1.0f);
    Block* from = cur_;
    Block* rhs = fn_->add_block();
    Block* join = fn_->add_block();
    if (is_and) branch(a, rhs, join);
    else branch(a, join, rhs);
    seal(rhs);
    cur_ = rhs;
    Inst* b = emit(Op::Truth, {expr(e->kids[1])});
    return merge(join, short_value, from, b);
  }

  // Ends the current block with a jump to `join` and goes on there with the phi of the two ways
  // in: `a` from `a_end`, `b` from the current block.
  Inst* merge(Block* join, Inst* a, Block* a_end, Inst* b) {
    Block* b_end = cur_;
    jump(join);
    seal(join);
    cur_ = join;
    Inst* p = phi_at(join);
    p->args = {a, b};
    p->targets = {a_end, b_end};
    return p;
  }

  Inst* conditional(Expr* e) {
    Inst* c = expr(e->kids[0]);
    probe("?:", "", e->span, c);
    Block* a_b = fn_->add_block();
    Block* b_b = fn_->add_block();
    Block* join = fn_->add_block();
    branch(c, a_b, b_b);
    seal(a_b);
    seal(b_b);
    cur_ = a_b;
    Inst* va = expr(e->kids[1]);
    Block* a_end = cur_;
    jump(join);
    cur_ = b_b;
    Inst* vb = expr(e->kids[2]);
    return merge(join, va, a_end, vb);
  }

  Inst* assign(Expr* e) {
    Expr* target = e->kids[0];
    if (target->kind == ExprKind::Index) return assign_index(e, target);
    if (target->sym < 0 && e->sym < 0) return expr(e->kids[1]);
    int id = target->sym >= 0 ? target->sym : e->sym;
    if (sym(id).is_array) {
      array_init(id, e->kids[1]);
      return konst(kNaN);
    }
    Inst* v;
    if (e->op == Tok::Assign) {
      v = expr(e->kids[1]);
    } else {
      Inst* old = read_var(id, target->span);
      v = emit(binary_op(e->op), {old, expr(e->kids[1])}, loc_of(e->span));
    }
    write_var(id, v);
    probe("var", sym(id).name, e->span, v);
    return v;
  }

  Inst* assign_index(Expr* e, Expr* target) {
    LineCol line = loc_of(target->span);
    Inst* idx = expr(target->kids[0]);
    Inst* v;
    if (e->op == Tok::Assign) {
      v = expr(e->kids[1]);
    } else {
      Inst* old = target->sym >= 0 ? emit(Op::ALoad, {idx}, line) : konst(kNaN);
      if (target->sym >= 0) array_op(old, target->sym);
      v = emit(binary_op(e->op), {old, expr(e->kids[1])}, loc_of(e->span));
    }
    if (target->sym >= 0) array_op(emit(Op::AStore, {idx, v}, line), target->sym);
    return v;
  }

  Inst* update(Expr* e) {
    Expr* target = e->kids[0];
    Inst* one = konst(1.0f);
    Op op = e->op == Tok::PlusPlus ? Op::Add : Op::Sub;
    if (target->kind == ExprKind::Index) {
      if (target->sym < 0) return konst(kNaN);
      LineCol line = loc_of(target->span);
      Inst* idx = expr(target->kids[0]);
      Inst* old = emit(Op::ALoad, {idx}, line);
      array_op(old, target->sym);
      Inst* nv = emit(op, {old, one});
      array_op(emit(Op::AStore, {idx, nv}, line), target->sym);
      return e->prefix ? nv : old;
    }
    int id = target->sym >= 0 ? target->sym : e->sym;
    if (id < 0) return konst(kNaN);
    Inst* old = read_var(id, target->span);
    Inst* nv = emit(op, {old, one});
    write_var(id, nv);
    probe("var", sym(id).name, e->span, nv);
    return e->prefix ? nv : old;
  }

  Inst* call(Expr* e) {
    std::vector<Inst*> args;
    for (Expr* k : e->kids) args.push_back(expr(k));
    if (e->sym <= -2) {
      int b = -2 - e->sym;
      if (static_cast<int>(args.size()) != kBuiltins[b].arity) return konst(kNaN);
      Op op = builtin_op(b);
      if (op == Op::Min || op == Op::Max)
        for (size_t k = 0; k < 2; ++k) probe(op == Op::Min ? "min" : "max", std::to_string(k + 1), e->span, args[k]);
      return emit(op, args, loc_of(e->span));
    }
    if (e->sym < 0) return konst(kNaN);
    int fi = sym(e->sym).slot;
    if (args.size() != sh_.sema.functions[fi].params.size()) return konst(kNaN);
    Inst* c = emit(Op::Call, args, loc_of(e->span));
    c->aux = fi;
    return c;
  }

  Shared& sh_;
  ir::Function* fn_;
  int owner_;
  Block* cur_;
  ir::SsaBuilder ssa_;
  std::unordered_map<int, Span> first_read_;
  std::unordered_set<int> warned_;
  std::vector<std::pair<Block*, Block*>> loops_;  // (continue target, break target)
};

}  // namespace

std::unique_ptr<ir::Module> lower_to_ir(const Program& prog, const SemaResult& sema, const KernelSpec& spec,
                                        const SourceFile& file, DiagnosticSink& diag) {
  auto mod = std::make_unique<ir::Module>();
  mod->globals = sema.globals;
  mod->arrays = sema.global_arrays;
  Shared sh{prog, sema, file, diag, *mod, -1, false, {}};
  sh.probe = spec.probe;
  if (sema.form == ScriptForm::Expression) sh.value_slot = mod->global_slot(kValueGlobal);
  for (const auto& f : sema.functions) {
    auto fn = std::make_unique<ir::Function>();
    fn->name = f.name;
    fn->num_params = static_cast<uint32_t>(f.params.size());
    fn->recursive = f.recursive;
    mod->functions.push_back(std::move(fn));
  }
  for (size_t i = 0; i < sema.functions.size(); ++i) {
    ir::Function* fn = mod->functions[i].get();
    fn->arrays = sema.local_arrays[i + 1];
    AstLowering(sh, fn, static_cast<int>(i)).lower_function(sema.functions[i]);
  }
  auto k = std::make_unique<ir::Function>();
  k->name = kKernelName;
  k->num_params = static_cast<uint32_t>(spec.input_names.size());
  k->num_results = static_cast<uint32_t>(spec.outputs.size());
  k->arrays = sema.local_arrays[0];
  k->kernel = true;
  ir::Function* kp = k.get();
  mod->functions.push_back(std::move(k));
  AstLowering(sh, kp, -1).lower_kernel(spec);
  for (auto& f : mod->functions) f->renumber();
  return mod;
}

}  // namespace fscript::frontend
