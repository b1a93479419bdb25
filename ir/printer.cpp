// IR printer. Format (one instruction per line):
//   global @x            garray @buf          fn @name(nparams) -> nresults [recursive] {
//   b0:                  v3 = fadd v1, v2     gstore @x, v3     v5 = aload %a, v4 !12:5
//   v7 = phi [v2, b0], [v6, b1]               v8 = call @f(v3, v4) !9      cbr v8, b1, b2
#include <cmath>
#include <cstdio>

#include "ir/text.h"

namespace fscript::ir {

std::string format_float(float v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
  return buf;
}

static std::string val(const Inst* i) { return "v" + std::to_string(i->id); }
static std::string blk(const Block* b) { return "b" + std::to_string(b->id); }

static std::string array_ref(const Module& m, const Function& fn, const Inst& i) {
  if (i.array_global) return "@" + m.arrays.at(i.aux);
  return "%" + fn.arrays.at(i.aux);
}

static std::string operands(const Module& m, const Function& fn, const Inst& i) {
  std::string s;
  auto sep = [&] { s += s.empty() ? " " : ", "; };
  switch (i.op) {
    case Op::Const: return " " + format_float(i.imm);
    case Op::Param: return " " + std::to_string(i.aux);
    case Op::GLoad: return " @" + m.globals.at(i.aux);
    case Op::GStore: return " @" + m.globals.at(i.aux) + ", " + val(i.args[0]);
    case Op::ANew:
    case Op::ALoad:
    case Op::AStore:
    case Op::ALen:
      s = " " + array_ref(m, fn, i);
      for (Inst* a : i.args) s += ", " + val(a);
      return s;
    case Op::Call: {
      s = " @" + m.functions.at(i.aux)->name + "(";
      for (size_t k = 0; k < i.args.size(); ++k) s += (k ? ", " : "") + val(i.args[k]);
      return s + ")";
    }
    case Op::Phi:
      for (size_t k = 0; k < i.args.size(); ++k) {
        sep();
        s += "[" + val(i.args[k]) + ", " + blk(i.targets[k]) + "]";
      }
      return s;
    default:
      for (Inst* a : i.args) {
        sep();
        s += val(a);
      }
      for (Block* t : i.targets) {
        sep();
        s += blk(t);
      }
      return s;
  }
}

std::string print(const Module& m, const Function& fn) {
  std::string out = "fn @" + fn.name + "(" + std::to_string(fn.num_params) + ") -> " + std::to_string(fn.num_results) +
      (fn.recursive ? " recursive" : "") + (fn.kernel ? " kernel" : "") +
      (fn.row_params_from ? " rows " + std::to_string(fn.row_params_from) : "");
  if (!fn.row_param_ranges.empty()) {
    out += " ranges";
    for (const ParamRange& r : fn.row_param_ranges)
      out += " " + format_float(r.lo) + " " + format_float(r.hi) + (r.nan ? " nan" : " num");
  }
  out += " {\n";
  for (const auto& a : fn.arrays) out += "  array %" + a + "\n";
  for (const auto& b : fn.blocks) {
    out += blk(b.get()) + ":\n";
    for (const Inst* i : b->insts) {
      out += "  ";
      if (i->defines_value()) out += val(i) + " = ";
      out += mnemonic(i->op) + operands(m, fn, *i);
      if (i->line) out += " !" + std::to_string(i->line) + (i->col ? ":" + std::to_string(i->col) : "");
      out += "\n";
    }
  }
  return out + "}\n";
}

std::string print(const Module& m) {
  std::string out;
  for (const auto& g : m.globals) out += "global @" + g + "\n";
  for (const auto& a : m.arrays) out += "garray @" + a + "\n";
  for (const auto& f : m.functions) out += print(m, *f);
  return out;
}

}  // namespace fscript::ir
