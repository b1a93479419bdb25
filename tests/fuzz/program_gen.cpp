// The program generator of the differential targets: a small grammar walked by the fuzzer's
// bytes. Names are always fresh or in scope, arities always right, loops always bounded. Every
// choice is its own statement: the operands of `+` are evaluated in an unspecified order, and
// clang and gcc took the bytes in different orders (a campaign's input made another program in
// the replay build). Each piece is written twice, as FScript and as JavaScript (Code), so that
// node can run the same program as an independent oracle (tests/oracle).
#include "tests/fuzz/program_gen.h"

#include <cctype>
#include <vector>

#include "ir/ir.h"

namespace fscript::fuzz {
namespace {

// A piece of the program in both languages.
struct Code {
  std::string fs, js;
};

struct Builtin {
  const char* name;
  int arity;
  bool runtime;  // computed by runtime/math (folded by the scalar twin: within 4 ulp of the batch)
};

const std::vector<Builtin>& builtins() {
  static const std::vector<Builtin> table = {
#define FS_BUILTIN(N, A, OP, SIG, DOC) {N, A, ir::has_flag(ir::Op::OP, ir::CallsRuntime)},
#include "frontend/fscript/builtins.def"
  };
  return table;
}

// The exact built-ins alone (GenOptions::exact_only).
const std::vector<Builtin>& exact_builtins() {
  static const std::vector<Builtin> table = [] {
    std::vector<Builtin> t;
    for (const Builtin& b : builtins())
      if (!b.runtime) t.push_back(b);
    return t;
  }();
  return table;
}

// A built-in's call in JavaScript: Math's function rounded to float, or the prelude's for what
// Math has not (clamp) or defines otherwise (min and max of equal zeros); "" for noise.
std::string js_builtin(const std::string& name, const std::vector<std::string>& args) {
  std::string list;
  for (size_t i = 0; i < args.size(); ++i) list += (i ? ", " : "") + args[i];
  if (name == "noise") return "";
  if (name == "min" || name == "max" || name == "clamp") return "__" + name + "(" + list + ")";
  if (name == "mod") return "__f(" + args[0] + " % " + args[1] + ")";
  std::string math = name == "fabs" ? "abs" : name;
  if (name == "abs" || name == "fabs" || name == "floor" || name == "ceil" || name == "round" || name == "sign")
    return "Math." + math + "(" + list + ")";  // exact in double, and the result is a float
  return "__f(Math." + math + "(" + list + "))";
}

// A binary operator in JavaScript: arithmetic rounded to float, comparisons and logic as 1 or 0.
std::string js_binary(const std::string& op, const std::string& l, const std::string& r) {
  if (op == "+" || op == "-" || op == "*" || op == "/" || op == "%") return "__f(" + l + " " + op + " " + r + ")";
  if (op == "^" || op == "**") return "__f(Math.pow(" + l + ", " + r + "))";
  if (op == "&") return "__min(" + l + ", " + r + ")";
  if (op == "|") return "__max(" + l + ", " + r + ")";
  std::string js_op = op == "==" ? "===" : op == "!=" ? "!==" : op;
  return "((" + l + " " + js_op + " " + r + ") ? 1 : 0)";  // also && and ||: truth of the operands
}

// `target op= value` as a JavaScript expression (target read once, before value, as JavaScript's
// compound assignment does).
std::string js_compound(const std::string& op, const std::string& target, const std::string& value) {
  if (op == "=") return target + " = " + value;
  return target + " = " + js_binary(op.substr(0, op.size() - 1), target, "(" + value + ")");
}

std::string js_literal(const std::string& fs) {
  if (fs == "pi") return "__pi";
  if (fs == "true") return "1";
  if (fs == "false") return "0";
  return "__f(" + fs + ")";
}

// Literals that reach every corner of float arithmetic: signed zeros, denormals, the largest
// finite values, infinities (1e39 rounds to inf) and NaN (0/0).
const char* const kLiterals[] = {"0",     "1",    "2",          "0.5",      "3",   "0.1", "7.25", "1e30",
                                 "1e-40", "3e38", "1e39",       "(0/0)",    "-0",  "pi",  "true", "false",
                                 "0x10",  "1e-7", "0.49999997", "16777217", "2.5", "100", "-1",   "1e-45"};
const char* const kBinary[] = {"+",  "-",  "*",  "/",   "%",   "^",  "**", "<", "<=", ">",
                               ">=", "==", "!=", "===", "!==", "&&", "||", "&", "|"};
const char* const kExactBinary[] = {
    "+", "-", "*", "/", "%", "<", "<=", ">", ">=", "==", "!=", "===", "!==", "&&", "||", "&", "|"};
const char* const kCompound[] = {"=", "+=", "-=", "*=", "/=", "%=", "^="};
const int kExactCompound = 6;  // without ^=

struct Function {
  std::string name;
  int arity;
  bool recursive;
};

struct Array {
  std::string name;
  int length;
};

class Generator {
 public:
  Generator(FuzzedDataProvider& in, const GenOptions& o) : in_(in), opt_(o) {}

  GeneratedProgram run() {
    int globals = pick(0, 2);
    for (int i = 0; i < globals; ++i) {
      std::string g = "g" + std::to_string(i);
      Code v = literal();
      emit({"var " + g + " = " + v.fs + ";\n", "var " + g + " = " + v.js + ";\n"});
      globals_.push_back(g);
    }
    if (!opt_.straight_line && flag()) {
      global_arrays_.push_back({"ga", pick(1, 4)});
      Code list;
      for (int i = 0; i < global_arrays_[0].length; ++i) {
        Code v = literal();
        list.fs += (i ? ", " : "") + v.fs;
        list.js += (i ? ", " : "") + v.js;
      }
      emit({"var ga = [" + list.fs + "];\n", "var ga = [" + list.js + "];\n"});
    }
    int helpers = pick(0, 2);
    for (int i = 0; i < helpers; ++i) helper(i);
    function("FRep", {"x", "y", "z", "t"}, false);
    js_ += "return FRep(x, y, z, t);\n";
    return {out_, transcendental_, js_ok_ ? js_ : std::string()};
  }

 private:
  int pick(int lo, int hi) { return in_.ConsumeIntegralInRange<int>(lo, hi); }
  bool flag() { return in_.ConsumeBool(); }
  // Bytes run out: every choice becomes its first (short) alternative, so generation ends.
  bool exhausted() const { return in_.remaining_bytes() == 0; }

  void emit(const Code& c) {
    out_ += c.fs;
    js_ += c.js;
  }
  void emit(const std::string& both) { emit({both, both}); }

  Code literal() {
    std::string fs = kLiterals[pick(0, std::size(kLiterals) - 1)];
    return {fs, js_literal(fs)};
  }

  // A recursive helper is linear: its one self-call is in its last return, with n - 1, so a huge
  // or NaN n from a caller ends in the call budget's runtime error, never in exponential work.
  void helper(int index) {
    bool recursive = !opt_.straight_line && flag();
    std::string name = (recursive ? "r" : "h") + std::to_string(index);
    int arity = pick(1, 3);
    std::vector<std::string> params;
    for (int p = 0; p < arity; ++p) params.push_back("p" + std::to_string(p));
    if (recursive) params[0] = "n";
    function(name, params, recursive);
    functions_.push_back({name, arity, recursive});
  }

  void function(const std::string& name, const std::vector<std::string>& params, bool recursive) {
    scopes_ = {params};
    for (const auto& g : globals_) scopes_[0].push_back(g);
    arrays_ = global_arrays_;
    next_local_ = 0;
    std::string list;
    for (size_t i = 0; i < params.size(); ++i) list += (i ? ", " : "") + params[i];
    emit("function " + name + "(" + list + ") {\n");
    // JavaScript's var starts undefined, which == itself; FScript's unset local is NaN. Every
    // local is declared NaN here, once the body has said which there are.
    size_t hoist_at = js_.size();
    declared_.clear();
    if (recursive) {
      Code base = expr(2);
      emit({"  if (n <= 0) return " + base.fs + ";\n", "  if (n <= 0) return " + base.js + ";\n"});
    }
    int statements = pick(0, 6);
    for (int s = 0; s < statements && !exhausted(); ++s) statement(1, 0);
    if (recursive) {
      Code call{name + "(n - 1", name + "(__f(n - 1)"};
      for (size_t a = 1; a < params.size(); ++a) {
        Code arg = expr(2);
        call.fs += ", " + arg.fs;
        call.js += ", " + arg.js;
      }
      std::string op = kBinary[pick(0, 4)];
      Code rest = expr(4);
      emit({"  return " + call.fs + ") " + op + " " + rest.fs + ";\n}\n",
            "  return " + js_binary(op, call.js + ")", rest.js) + ";\n}\n"});
    } else {
      Code value = expr(4);
      emit({"  return " + value.fs + ";\n}\n", "  return " + value.js + ";\n}\n"});
    }
    if (!declared_.empty()) {  // an array not yet created is null: reading it throws, as it fails here
      std::string decl = "  var ";
      for (size_t i = 0; i < declared_.size(); ++i)
        decl += (i ? ", " : "") + declared_[i] + (declared_[i][0] == 'a' ? " = null" : " = NaN");
      js_.insert(hoist_at, decl + ";\n");
    }
  }

  std::vector<std::string>& locals() { return scopes_.back(); }

  std::string fresh(const char* prefix) {
    std::string name = prefix + std::to_string(next_local_++);
    declared_.push_back(name);
    return name;
  }

  std::string scalar() {
    std::vector<std::string> all;
    for (const auto& s : scopes_) all.insert(all.end(), s.begin(), s.end());
    if (all.empty()) return literal().fs;
    return all[static_cast<size_t>(pick(0, static_cast<int>(all.size()) - 1))];
  }

  std::string indent(int depth) { return std::string(static_cast<size_t>(2 * depth), ' '); }

  void statement(int depth, int loops) {
    std::string in = indent(depth);
    int kind = pick(0, opt_.straight_line ? 3 : 9);
    switch (kind) {
      case 0:
      case 1: {
        std::string v = fresh("v");
        Code e = expr(3);
        emit({in + "var " + v + " = " + e.fs + ";\n", in + "var " + v + " = " + e.js + ";\n"});
        locals().push_back(v);
        return;
      }
      case 2: {
        std::string target = assignable();
        if (target.empty()) {
          target = fresh("v");
          Code e = expr(3);
          emit({in + "var " + target + " = " + e.fs + ";\n", in + "var " + target + " = " + e.js + ";\n"});
          locals().push_back(target);
        } else {
          std::string op = compound();
          Code value = expr(3);
          emit({in + target + " " + op + " " + value.fs + ";\n", in + js_compound(op, target, value.js) + ";\n"});
        }
        return;
      }
      case 3: {
        Code cond = expr(2);
        emit({in + "if (" + cond.fs + ") {\n", in + "if (" + cond.js + ") {\n"});
        block(depth, loops);
        if (flag()) {
          emit(in + "} else {\n");
          block(depth, loops);
        }
        emit(in + "}\n");
        return;
      }
      case 4:
      case 5: return loop(depth, loops);
      case 6: {
        std::string a = fresh("a");
        int n = pick(0, 5);
        if (flag()) {
          emit({in + "var " + a + " = new Array(" + std::to_string(n) + ");\n",
                in + "var " + a + " = __new_array(" + std::to_string(n) + ");\n"});
        } else {
          Code list;
          for (int i = 0; i < n; ++i) {
            Code e = expr(1);
            list.fs += (i ? ", " : "") + e.fs;
            list.js += (i ? ", " : "") + e.js;
          }
          emit({in + "var " + a + " = [" + list.fs + "];\n", in + "var " + a + " = [" + list.js + "];\n"});
        }
        arrays_.push_back({a, n});
        return;
      }
      case 7: {
        if (arrays_.empty()) return emit(in + ";\n");
        const Array& a = arrays_[static_cast<size_t>(pick(0, static_cast<int>(arrays_.size()) - 1))];
        Code at = index(a);
        std::string op = compound();
        Code value = expr(2);
        // The index is checked (and rounded) once, before the value, as in every backend.
        emit({in + a.name + "[" + at.fs + "] " + op + " " + value.fs + ";\n",
              in + "{ let __k = __idx(" + a.name + ", " + at.js + "); " + js_compound(op, a.name + "[__k]", value.js) +
                  "; }\n"});
        return;
      }
      case 8: {
        Code cond = expr(2);
        Code value = expr(2);
        emit({in + "if (" + cond.fs + ") return " + value.fs + ";\n",
              in + "if (" + cond.js + ") return " + value.js + ";\n"});
        return;
      }
      default:
        if (loops > 0) {
          Code cond = expr(1);
          std::string jump = flag() ? "break" : "continue";
          emit({in + "if (" + cond.fs + ") " + jump + ";\n", in + "if (" + cond.js + ") " + jump + ";\n"});
        } else {
          Code e = expr(3);
          emit({in + e.fs + ";\n", in + e.js + ";\n"});
        }
        return;
    }
  }

  std::string compound() {
    return kCompound[pick(0, opt_.exact_only ? kExactCompound - 1 : static_cast<int>(std::size(kCompound)) - 1)];
  }

  // Locals declared in a block stay visible after it (var is function-scoped), possibly unset:
  // NaN then, which the backends must agree on too.
  void block(int depth, int loops) {
    int n = pick(0, 3);
    for (int i = 0; i < n && !exhausted(); ++i) statement(depth + 1, loops);
  }

  void loop(int depth, int loops) {
    if (loops >= 2) return emit(indent(depth) + ";\n");
    std::string i = fresh("i");
    int trips = pick(0, 6);
    std::string in = indent(depth);
    if (flag()) {
      emit(in + "for (var " + i + " = 0; " + i + " < " + std::to_string(trips) + "; " + i + "++) {\n");
    } else {
      emit(in + "var " + i + " = 0;\n" + in + "while (" + i + " < " + std::to_string(trips) + ") {\n" +
           indent(depth + 1) + i + " = " + i + " + 1;\n");
    }
    locals().push_back(i);
    block(depth, loops + 1);
    emit(in + "}\n");
  }

  // A scalar that is not a loop counter or a recursion depth (those keep loops and recursion
  // bounded), or "" when there is none.
  std::string assignable() {
    std::string s = scalar();
    if (s.empty() || s[0] == 'i' || s == "n" || !std::isalpha(static_cast<unsigned char>(s[0])) || s == "pi" ||
        s == "true" || s == "false")
      return "";
    return s;
  }

  // Mostly in range; sometimes anything (out of range and NaN indices are runtime errors).
  Code index(const Array& a) {
    if (flag() && a.length > 0) {
      std::string at = std::to_string(pick(0, a.length - 1));
      return {at, at};
    }
    return expr(1);
  }

  Code expr(int depth) {
    if (depth <= 0 || exhausted()) return leaf();
    switch (pick(0, 9)) {
      case 0: return leaf();
      case 1: {
        const char* u[] = {"-", "!", "+"};
        std::string op = u[pick(0, 2)];
        Code e = expr(depth - 1);
        std::string js = op == "!" ? "((" + e.js + ") ? 0 : 1)" : "(" + op + "(" + e.js + "))";
        return {op + "(" + e.fs + ")", js};
      }
      case 2:
      case 3: {
        std::string op = opt_.exact_only ? kExactBinary[pick(0, std::size(kExactBinary) - 1)]
                                         : kBinary[pick(0, std::size(kBinary) - 1)];
        if (op == "^" || op == "**") transcendental_ = true;
        Code left = expr(depth - 1);
        Code right = expr(depth - 1);
        return {"(" + left.fs + " " + op + " " + right.fs + ")", js_binary(op, left.js, right.js)};
      }
      case 4: {
        Code cond = expr(depth - 1);
        Code yes = expr(depth - 1);
        Code no = expr(depth - 1);
        return {"(" + cond.fs + " ? " + yes.fs + " : " + no.fs + ")",
                "((" + cond.js + ") ? " + yes.js + " : " + no.js + ")"};
      }
      case 5:
      case 6: {
        const std::vector<Builtin>& table = opt_.exact_only ? exact_builtins() : builtins();
        const Builtin& b = table[static_cast<size_t>(pick(0, static_cast<int>(table.size()) - 1))];
        transcendental_ |= b.runtime;
        std::string fs = std::string(flag() ? "" : "Math.") + b.name + "(";
        std::vector<std::string> args;
        for (int a = 0; a < b.arity; ++a) {
          Code arg = expr(depth - 1);
          fs += (a ? ", " : "") + arg.fs;
          args.push_back(arg.js);
        }
        std::string js = js_builtin(b.name, args);
        if (js.empty()) js_ok_ = false, js = "NaN";
        return {fs + ")", js};
      }
      case 7: {
        if (functions_.empty()) return leaf();
        const Function& f = functions_[static_cast<size_t>(pick(0, static_cast<int>(functions_.size()) - 1))];
        Code call{f.name + "(", f.name + "("};
        for (int a = 0; a < f.arity; ++a) {
          // A recursive helper's depth: a small count, or anything.
          Code arg;
          if (a == 0 && f.recursive && flag()) arg.fs = arg.js = std::to_string(pick(0, 8));
          else arg = expr(depth - 1);
          call.fs += (a ? ", " : "") + arg.fs;
          call.js += (a ? ", " : "") + arg.js;
        }
        return {call.fs + ")", call.js + ")"};
      }
      case 8: {
        if (arrays_.empty()) return leaf();
        const Array& a = arrays_[static_cast<size_t>(pick(0, static_cast<int>(arrays_.size()) - 1))];
        if (flag()) return {a.name + ".length", a.name + ".length"};
        Code at = index(a);
        return {a.name + "[" + at.fs + "]", a.name + "[__idx(" + a.name + ", " + at.js + ")]"};
      }
      default: {
        if (opt_.straight_line) return leaf();
        std::string v = assignable();
        if (v.empty()) return leaf();
        if (flag())  // the old value, and v one more (rounded to float)
          return {"(" + v + "++)", "((__o) => (" + v + " = __f(__o + 1), __o))(" + v + ")"};
        Code e = expr(depth - 1);
        return {"(" + v + " += " + e.fs + ")", "(" + js_compound("+=", v, e.js) + ")"};
      }
    }
  }

  Code leaf() {
    if (flag()) {
      std::string s = scalar();
      return {s, scalar_js(s)};
    }
    return literal();
  }
  // scalar() may fall back to a literal when nothing is in scope.
  static std::string scalar_js(const std::string& s) {
    return std::isalpha(static_cast<unsigned char>(s[0])) && s != "pi" && s != "true" && s != "false" ? s
                                                                                                      : js_literal(s);
  }

  FuzzedDataProvider& in_;
  GenOptions opt_;
  std::string out_, js_;
  bool transcendental_ = false, js_ok_ = true;
  std::vector<std::string> globals_, declared_;
  std::vector<Array> global_arrays_, arrays_;
  std::vector<Function> functions_;
  std::vector<std::vector<std::string>> scopes_;
  int next_local_ = 0;
};

}  // namespace

GeneratedProgram generate_program(FuzzedDataProvider& in, const GenOptions& options) {
  return Generator(in, options).run();
}

}  // namespace fscript::fuzz
