// The row split (ir/passes/row_split.h): classify each value of a straight-line kernel as varying along
// the row (it depends on input 0) or not, then copy each class into a kernel of its own.
#include "ir/passes/row_split.h"

#include "ir/passes/passes.h"
#include "ir/ranges.h"

#include <vector>

namespace fscript::ir {
namespace {

bool splittable(const Function& fn) {
  if (fn.blocks.size() != 1) return false;
  for (const Inst* i : fn.entry()->insts)
    if (i->op != Op::Ret && !has_flag(i->op, Pure)) return false;  // calls, memory, traps, phis
  return true;
}

void append(Block* b, Inst* in) {
  in->block = b;
  b->insts.push_back(in);
}

Inst* copy_of(Function& f, const Inst* src, const std::vector<Inst*>& map) {
  Inst* c = f.make(src->op);
  c->imm = src->imm, c->aux = src->aux, c->line = src->line, c->col = src->col;
  for (const Inst* a : src->args) c->args.push_back(map[a->id]);
  return c;
}

std::unique_ptr<Function> kernel_shell(const Function& fn, uint32_t params, uint32_t results) {
  auto f = std::make_unique<Function>();
  f->name = fn.name;
  f->num_params = params;
  f->num_results = results;
  f->kernel = true;
  f->add_block();
  return f;
}

}  // namespace

bool split_rows(const Module& m, RowSplit& out) {
  const Function& fn = m.kernel_function();
  if (!splittable(fn) || fn.num_params < 2) return false;
  const auto& insts = fn.entry()->insts;
  // Varying: input 0 and everything computed from it. Constants are neither: the body makes its own.
  std::vector<char> varying(fn.next_value, 0), is_const(fn.next_value, 0);
  size_t hoisted_weight = 0, hoisted = 0, per_point = 0;
  for (const Inst* i : insts) {
    if (!i->defines_value()) continue;
    if (i->op == Op::Const) {
      is_const[i->id] = 1;
      continue;
    }
    bool v = i->op == Op::Param && i->aux == 0;
    for (const Inst* a : i->args) v = v || varying[a->id];
    varying[i->id] = v;
    if (i->op == Op::Param) continue;
    if (v) ++per_point;
    else ++hoisted, hoisted_weight += has_flag(i->op, CallsRuntime) ? kCallWeight : 1;
  }
  // The row values: non-constant invariant values that a varying instruction or the return reads.
  std::vector<int> row_index(fn.next_value, -1);
  std::vector<const Inst*> row_values;
  for (const Inst* i : insts) {
    if (i->op != Op::Ret && !(i->defines_value() && varying[i->id])) continue;
    for (const Inst* a : i->args)
      if (!varying[a->id] && !is_const[a->id] && row_index[a->id] < 0) {
        row_index[a->id] = static_cast<int>(row_values.size());
        row_values.push_back(a);
      }
  }
  if (row_values.empty() || double(hoisted_weight) <= kRowValueCost * double(row_values.size())) return false;

  uint32_t k = static_cast<uint32_t>(row_values.size());
  auto pro = kernel_shell(fn, fn.num_params, k), body = kernel_shell(fn, 1 + k, fn.num_results);
  body->row_params_from = 1;
  std::vector<Inst*> in_pro(fn.next_value, nullptr), in_body(fn.next_value, nullptr);
  // A row parameter's instruction goes just before its first use: backends load it there, so
  // hundreds of them (prospero) are not all live from the top.
  auto row_params_of = [&](const Inst* i) {
    for (const Inst* a : i->args)
      if (int r = row_index[a->id]; r >= 0 && !in_body[a->id]) {
        Inst* p = body->make(Op::Param);
        p->aux = 1 + r;
        append(body->entry(), p);
        in_body[a->id] = p;
      }
  };
  for (const Inst* i : insts) {
    if (i->op == Op::Ret || varying[i->id]) row_params_of(i);
    if (i->op == Op::Ret) {
      Inst* r = copy_of(*body, i, in_body);
      append(body->entry(), r);
      continue;
    }
    if (is_const[i->id] || varying[i->id]) {
      Inst* c = copy_of(*body, i, in_body);
      append(body->entry(), c);
      if (!in_body[i->id]) in_body[i->id] = c;
    }
    if (!varying[i->id]) {
      Inst* c = copy_of(*pro, i, in_pro);
      append(pro->entry(), c);
      in_pro[i->id] = c;
    }
  }
  Inst* ret = pro->make(Op::Ret);
  for (const Inst* v : row_values) ret->args.push_back(in_pro[v->id]);
  append(pro->entry(), ret);
  // What the body's bounded code may assume of each row value: its range in the whole kernel under
  // each parameter bound (checked on every row's values when the body runs).
  for (double bound : kParamBounds) {
    std::vector<Range> r = value_ranges(fn, bound);
    for (const Inst* v : row_values)
      body->row_param_ranges.push_back(
          {static_cast<float>(r[v->id].lo), static_cast<float>(r[v->id].hi), r[v->id].nan});
  }
  run_dce(*body);  // constants only the prologue reads
  out.prologue = std::make_unique<Module>();
  out.prologue->functions.push_back(std::move(pro));
  out.body = std::make_unique<Module>();
  out.body->functions.push_back(std::move(body));
  out.hoisted = hoisted, out.per_point = per_point, out.row_values = k;
  return true;
}

}  // namespace fscript::ir
