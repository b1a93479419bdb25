// The program generator of the differential targets: a small grammar walked by the fuzzer's
// bytes. Names are always fresh or in scope, arities always right, loops always bounded. Every
// choice is its own statement: the operands of `+` are evaluated in an unspecified order, and
// clang and gcc took the bytes in different orders (a campaign's input made another program in
// the replay build).
#include "tests/fuzz/program_gen.h"

#include <cctype>
#include <vector>

#include "ir/ir.h"

namespace fscript::fuzz {
namespace {

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

// Literals that reach every corner of float arithmetic: signed zeros, denormals, the largest
// finite values, infinities (1e39 rounds to inf) and NaN (0/0).
const char* const kLiterals[] = {"0",     "1",        "2",      "0.5",  "3",    "0.1",   "7.25",  "1e30",  "1e-40",
                                 "3e38",  "1e39",     "(0/0)",  "-0",   "pi",   "true",  "false", "0x10",  "1e-7",
                                 "0.49999997", "16777217", "2.5", "100", "-1", "1e-45"};
const char* const kBinary[] = {"+", "-", "*", "/", "%", "^", "**", "<", "<=", ">", ">=", "==", "!=", "===",
                               "!==", "&&", "||", "&", "|"};
const char* const kCompound[] = {"=", "+=", "-=", "*=", "/=", "%=", "^="};

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
      out_ += "var " + g + " = " + literal() + ";\n";
      globals_.push_back(g);
    }
    if (!opt_.straight_line && flag()) {
      global_arrays_.push_back({"ga", pick(1, 4)});
      out_ += "var ga = [";
      for (int i = 0; i < global_arrays_[0].length; ++i) out_ += (i ? ", " : "") + literal();
      out_ += "];\n";
    }
    int helpers = pick(0, 2);
    for (int i = 0; i < helpers; ++i) helper(i);
    function("FRep", {"x", "y", "z", "t"}, false);
    return {out_, transcendental_};
  }

 private:
  int pick(int lo, int hi) { return in_.ConsumeIntegralInRange<int>(lo, hi); }
  bool flag() { return in_.ConsumeBool(); }
  // Bytes run out: every choice becomes its first (short) alternative, so generation ends.
  bool exhausted() const { return in_.remaining_bytes() == 0; }

  std::string literal() { return kLiterals[pick(0, std::size(kLiterals) - 1)]; }

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
    out_ += "function " + name + "(";
    for (size_t i = 0; i < params.size(); ++i) out_ += (i ? ", " : "") + params[i];
    out_ += ") {\n";
    if (recursive) out_ += "  if (n <= 0) return " + expr(2) + ";\n";
    int statements = pick(0, 6);
    for (int s = 0; s < statements && !exhausted(); ++s) statement(1, 0);
    out_ += "  return ";
    if (recursive) {
      out_ += name + "(n - 1";
      for (size_t a = 1; a < params.size(); ++a) out_ += ", " + expr(2);
      out_ += std::string(") ") + kBinary[pick(0, 4)] + " ";
    }
    out_ += expr(4) + ";\n}\n";
  }

  std::vector<std::string>& locals() { return scopes_.back(); }

  std::string fresh(const char* prefix) { return prefix + std::to_string(next_local_++); }

  std::string scalar() {
    std::vector<std::string> all;
    for (const auto& s : scopes_) all.insert(all.end(), s.begin(), s.end());
    if (all.empty()) return literal();
    return all[static_cast<size_t>(pick(0, static_cast<int>(all.size()) - 1))];
  }

  void indent(int depth) { out_.append(static_cast<size_t>(2 * depth), ' '); }

  void statement(int depth, int loops) {
    indent(depth);
    int kind = pick(0, opt_.straight_line ? 3 : 9);
    switch (kind) {
      case 0: case 1: {
        std::string v = fresh("v");
        out_ += "var " + v + " = " + expr(3) + ";\n";
        locals().push_back(v);
        return;
      }
      case 2: {
        std::string target = assignable();
        if (target.empty()) {
          target = fresh("v");
          out_ += "var " + target + " = " + expr(3) + ";\n";
          locals().push_back(target);
        } else {
          std::string op = kCompound[pick(0, std::size(kCompound) - 1)];
          std::string value = expr(3);
          out_ += target + " " + op + " " + value + ";\n";
        }
        return;
      }
      case 3: {
        out_ += "if (" + expr(2) + ") {\n";
        block(depth, loops);
        if (flag()) {
          indent(depth);
          out_ += "} else {\n";
          block(depth, loops);
        }
        indent(depth);
        out_ += "}\n";
        return;
      }
      case 4: case 5: return loop(depth, loops);
      case 6: {
        std::string a = fresh("a");
        int n = pick(0, 5);
        if (flag()) {
          out_ += "var " + a + " = new Array(" + std::to_string(n) + ");\n";
        } else {
          out_ += "var " + a + " = [";
          for (int i = 0; i < n; ++i) out_ += (i ? ", " : "") + expr(1);
          out_ += "];\n";
        }
        arrays_.push_back({a, n});
        return;
      }
      case 7: {
        if (arrays_.empty()) return statement_empty();
        const Array& a = arrays_[static_cast<size_t>(pick(0, static_cast<int>(arrays_.size()) - 1))];
        std::string at = index(a);
        std::string op = kCompound[pick(0, std::size(kCompound) - 1)];
        std::string value = expr(2);
        out_ += a.name + "[" + at + "] " + op + " " + value + ";\n";
        return;
      }
      case 8: {
        std::string cond = expr(2);
        std::string value = expr(2);
        out_ += "if (" + cond + ") return " + value + ";\n";
        return;
      }
      default:
        if (loops > 0) {
          std::string cond = expr(1);
          out_ += "if (" + cond + ") " + (flag() ? "break" : "continue") + ";\n";
        } else {
          out_ += expr(3) + ";\n";
        }
        return;
    }
  }

  void statement_empty() { out_ += ";\n"; }

  // Locals declared in a block stay visible after it (var is function-scoped), possibly unset:
  // NaN then, which the backends must agree on too.
  void block(int depth, int loops) {
    int n = pick(0, 3);
    for (int i = 0; i < n && !exhausted(); ++i) statement(depth + 1, loops);
  }

  void loop(int depth, int loops) {
    if (loops >= 2) return statement_empty();
    std::string i = fresh("i");
    int trips = pick(0, 6);
    if (flag()) {
      out_ += "for (var " + i + " = 0; " + i + " < " + std::to_string(trips) + "; " + i + "++) {\n";
    } else {
      out_ += "var " + i + " = 0;\n";
      indent(depth);
      out_ += "while (" + i + " < " + std::to_string(trips) + ") {\n";
      indent(depth + 1);
      out_ += i + " = " + i + " + 1;\n";
    }
    locals().push_back(i);
    block(depth, loops + 1);
    indent(depth);
    out_ += "}\n";
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
  std::string index(const Array& a) {
    if (flag() && a.length > 0) return std::to_string(pick(0, a.length - 1));
    return expr(1);
  }

  std::string expr(int depth) {
    if (depth <= 0 || exhausted()) return leaf();
    switch (pick(0, 9)) {
      case 0: return leaf();
      case 1: {
        const char* u[] = {"-", "!", "+"};
        std::string op = u[pick(0, 2)];
        return op + "(" + expr(depth - 1) + ")";
      }
      case 2: case 3: {
        std::string op = kBinary[pick(0, std::size(kBinary) - 1)];
        if (op == "^" || op == "**") transcendental_ = true;
        std::string left = expr(depth - 1);
        std::string right = expr(depth - 1);
        return "(" + left + " " + op + " " + right + ")";
      }
      case 4: {
        std::string cond = expr(depth - 1);
        std::string yes = expr(depth - 1);
        std::string no = expr(depth - 1);
        return "(" + cond + " ? " + yes + " : " + no + ")";
      }
      case 5: case 6: {
        const Builtin& b = builtins()[static_cast<size_t>(pick(0, static_cast<int>(builtins().size()) - 1))];
        transcendental_ |= b.runtime;
        std::string s = std::string(flag() ? "" : "Math.") + b.name + "(";
        for (int a = 0; a < b.arity; ++a) s += (a ? ", " : "") + expr(depth - 1);
        return s + ")";
      }
      case 7: {
        if (functions_.empty()) return leaf();
        const Function& f = functions_[static_cast<size_t>(pick(0, static_cast<int>(functions_.size()) - 1))];
        std::string s = f.name + "(";
        for (int a = 0; a < f.arity; ++a) {
          s += a ? ", " : "";
          // A recursive helper's depth: a small count, or anything.
          s += a == 0 && f.recursive && flag() ? std::to_string(pick(0, 8)) : expr(depth - 1);
        }
        return s + ")";
      }
      case 8: {
        if (arrays_.empty()) return leaf();
        const Array& a = arrays_[static_cast<size_t>(pick(0, static_cast<int>(arrays_.size()) - 1))];
        return flag() ? a.name + ".length" : a.name + "[" + index(a) + "]";
      }
      default: {
        if (opt_.straight_line) return leaf();
        std::string v = assignable();
        if (v.empty()) return leaf();
        return "(" + v + (flag() ? "++" : " += " + expr(depth - 1)) + ")";
      }
    }
  }

  std::string leaf() { return flag() ? scalar() : literal(); }

  FuzzedDataProvider& in_;
  GenOptions opt_;
  std::string out_;
  bool transcendental_ = false;
  std::vector<std::string> globals_;
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
