// Forward-mode differentiation (ir/passes/gradient.h): each value of the straight-line kernel is
// copied, followed by its three partial derivatives, built from the values already there by the
// chain rule of its op. A derivative known to be zero is no instruction at all, so what depends
// only on t or on constants costs nothing more.
#include "ir/passes/gradient.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <unordered_map>
#include <vector>

#include "ir/passes/passes.h"

namespace fscript::ir {
namespace {

using Tangent = std::array<Inst*, 3>;  // d/dp0, d/dp1, d/dp2; nullptr: known to be zero

class Builder {
 public:
  Builder(Function& f, Block* b) : f_(f), b_(b) {}

  // The derivatives built next stand for `from`'s in the source (a profile charges them to its line).
  void at(const Inst* from) { line_ = from->line, col_ = from->col; }
  Inst* op(Op o, Inst* a, Inst* b = nullptr, Inst* c = nullptr) {
    Inst* i = f_.make(o);
    i->line = line_, i->col = col_;
    for (Inst* x : {a, b, c})
      if (x) i->args.push_back(x);
    return append(i);
  }
  Inst* constant(float v) {
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    Inst*& c = consts_[bits];
    if (!c) {
      c = f_.make(Op::Const);
      c->imm = v;
      append(c);
    }
    return c;
  }
  Inst* append(Inst* i) {
    i->block = b_;
    b_->insts.push_back(i);
    return i;
  }
  Inst* or_zero(Inst* t) { return t ? t : constant(0); }

  // t * s, component by component.
  Tangent scale(const Tangent& t, Inst* s) {
    Tangent r{};
    for (int k = 0; k < 3; ++k) r[k] = t[k] ? op(Op::Mul, t[k], s) : nullptr;
    return r;
  }
  Tangent divide(const Tangent& t, Inst* s) {
    Tangent r{};
    for (int k = 0; k < 3; ++k) r[k] = t[k] ? op(Op::Div, t[k], s) : nullptr;
    return r;
  }
  Tangent sum(const Tangent& a, const Tangent& b) {
    Tangent r{};
    for (int k = 0; k < 3; ++k) r[k] = a[k] && b[k] ? op(Op::Add, a[k], b[k]) : a[k] ? a[k] : b[k];
    return r;
  }
  Tangent difference(const Tangent& a, const Tangent& b) { return sum(a, negate(b)); }
  Tangent negate(const Tangent& a) {
    Tangent r{};
    for (int k = 0; k < 3; ++k) r[k] = a[k] ? op(Op::Neg, a[k]) : nullptr;
    return r;
  }
  // cond ? a : b, component by component.
  Tangent choose(Inst* cond, const Tangent& a, const Tangent& b) {
    Tangent r{};
    for (int k = 0; k < 3; ++k) r[k] = a[k] || b[k] ? op(Op::Select, cond, or_zero(a[k]), or_zero(b[k])) : nullptr;
    return r;
  }

 private:
  Function& f_;
  Block* b_;
  std::unordered_map<uint32_t, Inst*> consts_;
  uint32_t line_ = 0, col_ = 0;
};

bool zero(const Tangent& t) { return !t[0] && !t[1] && !t[2]; }

// The derivative of `r` (the copy of an instruction, its operands `a` already copied) from its
// operands' derivatives `d`. False for an op without a rule here.
bool rule(Builder& B, Inst* r, const std::vector<Tangent>& d, Tangent& out) {
  const std::vector<Inst*>& a = r->args;
  out = Tangent{};
  Tangent none{};
  const Tangent& d0 = d.size() > 0 ? d[0] : none;
  const Tangent& d1 = d.size() > 1 ? d[1] : none;
  const Tangent& d2 = d.size() > 2 ? d[2] : none;
  if (r->op != Op::Param && r->op != Op::Ret && d.size() == a.size() &&
      std::all_of(d.begin(), d.end(), [](const Tangent& t) { return zero(t); }))
    return true;  // constant in p0..p2
  switch (r->op) {
    case Op::Const: return true;
    case Op::Param:
      if (r->aux < 3) out[r->aux] = B.constant(1);
      return true;
    case Op::Add: out = B.sum(d0, d1); return true;
    case Op::Sub: out = B.difference(d0, d1); return true;
    case Op::Mul: out = B.sum(B.scale(d0, a[1]), B.scale(d1, a[0])); return true;
    case Op::Div: out = B.divide(B.difference(d0, B.scale(d1, r)), a[1]); return true;
    case Op::Mod:  // a - b * q with q = (a - r) / b, the truncated quotient, held fixed
      out = zero(d1) ? d0 : B.difference(d0, B.scale(d1, B.op(Op::Div, B.op(Op::Sub, a[0], r), a[1])));
      return true;
    case Op::Neg: out = B.negate(d0); return true;
    case Op::Min: out = B.choose(B.op(Op::Lt, a[1], a[0]), d1, d0); return true;
    case Op::Max: out = B.choose(B.op(Op::Gt, a[1], a[0]), d1, d0); return true;
    case Op::Abs: out = B.scale(d0, B.op(Op::Sign, a[0])); return true;
    case Op::Sqrt: out = B.scale(d0, B.op(Op::Div, B.constant(0.5f), r)); return true;
    case Op::Floor:
    case Op::Ceil:
    case Op::Round:
    case Op::Sign: return true;
    case Op::Clamp: {  // min(max(a, lo), hi)
      Inst* m = B.op(Op::Max, a[0], a[1]);
      Tangent dm = B.choose(B.op(Op::Gt, a[1], a[0]), d1, d0);
      out = B.choose(B.op(Op::Gt, m, a[2]), d2, dm);
      return true;
    }
    case Op::Pow: {  // b a^(b-1) da + a^b log(a) db
      Inst* lower = B.op(Op::Pow, a[0], B.op(Op::Sub, a[1], B.constant(1)));
      out = B.scale(d0, B.op(Op::Mul, a[1], lower));
      if (!zero(d1)) out = B.sum(out, B.scale(d1, B.op(Op::Mul, r, B.op(Op::Log, a[0]))));
      return true;
    }
    case Op::Exp: out = B.scale(d0, r); return true;
    case Op::Log: out = B.divide(d0, a[0]); return true;
    case Op::Log10: out = B.divide(d0, B.op(Op::Mul, a[0], B.constant(2.302585093f))); return true;
    case Op::Sin: out = B.scale(d0, B.op(Op::Cos, a[0])); return true;
    case Op::Cos: out = B.negate(B.scale(d0, B.op(Op::Sin, a[0]))); return true;
    case Op::Tan: out = B.scale(d0, B.op(Op::Add, B.constant(1), B.op(Op::Mul, r, r))); return true;
    case Op::Asin:
    case Op::Acos: {
      Inst* root = B.op(Op::Sqrt, B.op(Op::Sub, B.constant(1), B.op(Op::Mul, a[0], a[0])));
      out = B.divide(r->op == Op::Asin ? d0 : B.negate(d0), root);
      return true;
    }
    case Op::Atan: out = B.divide(d0, B.op(Op::Add, B.constant(1), B.op(Op::Mul, a[0], a[0]))); return true;
    case Op::Atan2: {  // atan2(y, x): (x dy - y dx) / (x^2 + y^2)
      Inst* r2 = B.op(Op::Add, B.op(Op::Mul, a[0], a[0]), B.op(Op::Mul, a[1], a[1]));
      out = B.divide(B.difference(B.scale(d0, a[1]), B.scale(d1, a[0])), r2);
      return true;
    }
    case Op::Hypot: out = B.divide(B.sum(B.scale(d0, a[0]), B.scale(d1, a[1])), r); return true;
    case Op::Sinh: out = B.scale(d0, B.op(Op::Cosh, a[0])); return true;
    case Op::Cosh: out = B.scale(d0, B.op(Op::Sinh, a[0])); return true;
    case Op::Tanh: out = B.scale(d0, B.op(Op::Sub, B.constant(1), B.op(Op::Mul, r, r))); return true;
    case Op::Noise: return false;
    case Op::Eq:
    case Op::Ne:
    case Op::Lt:
    case Op::Le:
    case Op::Gt:
    case Op::Ge:
    case Op::Not:
    case Op::Truth: return true;
    case Op::Select: out = B.choose(a[0], d1, d2); return true;
    case Op::Ret: return true;
    // Not in a straight-line kernel of pure operations (gradient_module checks first).
    case Op::Phi:
    case Op::GLoad:
    case Op::GStore:
    case Op::ANew:
    case Op::ALoad:
    case Op::AStore:
    case Op::ALen:
    case Op::Call:
    case Op::Tick:
    case Op::Jump:
    case Op::Branch: return false;
  }
  return false;
}

bool straight_line(const Function& fn) {
  if (fn.blocks.size() != 1 || fn.num_results < 1) return false;
  for (const Inst* i : fn.entry()->insts)
    if (i->op != Op::Ret && (!has_flag(i->op, Pure) || i->op == Op::Phi)) return false;
  const Inst* t = fn.entry()->terminator();
  return t && t->op == Op::Ret && !t->args.empty();
}

}  // namespace

std::unique_ptr<Module> gradient_module(const Module& m) {
  const Function& src = m.kernel_function();
  if (!straight_line(src)) return nullptr;
  auto out = std::make_unique<Module>();
  out->globals = m.globals;
  auto fn = std::make_unique<Function>();
  fn->name = src.name + ".gradient";
  fn->num_params = src.num_params;
  fn->num_results = 4;
  fn->kernel = true;
  Builder B(*fn, fn->add_block());
  std::vector<Inst*> copy(src.next_value, nullptr);
  std::vector<Tangent> tangent(src.next_value, Tangent{});
  for (const Inst* i : src.entry()->insts) {
    if (i->op == Op::Ret) {
      Inst* f = copy[i->args[0]->id];
      const Tangent& d = tangent[i->args[0]->id];
      Inst* ret = fn->make(Op::Ret);
      ret->args = {f, B.or_zero(d[0]), B.or_zero(d[1]), B.or_zero(d[2])};
      B.append(ret);
      break;
    }
    Inst* c = fn->make(i->op);
    c->imm = i->imm, c->aux = i->aux, c->line = i->line, c->col = i->col;
    std::vector<Tangent> d;
    for (const Inst* a : i->args) c->args.push_back(copy[a->id]), d.push_back(tangent[a->id]);
    B.append(c);
    B.at(i);
    copy[i->id] = c;
    if (!rule(B, c, d, tangent[i->id])) return nullptr;
  }
  out->functions.push_back(std::move(fn));
  optimize(*out);
  return out;
}

}  // namespace fscript::ir
