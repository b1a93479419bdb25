// fscript probe FILE --at x,y,z[,t] [--bound x0,x1,y0,y1,z0,z1[,t0,t1]] and the REPL's :probe and
// :bound: every variable of the script with its value at a point (or its interval over a box), in
// source order, with the branch each if takes and the side each min and max takes.
#include "tools/fscript/probe.h"

#include <algorithm>
#include <iostream>
#include <sstream>

#include "ir/interval_eval.h"
#include "tools/fscript/common.h"

namespace fscript::cli {
namespace {

// One probe slot (frontend::KernelSpec::probe) and the kernel output that returns it.
struct Site {
  std::string kind, function, name;
  uint32_t line = 0, col = 0;
  size_t output = 0;
};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string part;
  while (std::getline(ss, part, sep)) out.push_back(part);
  return out;
}

// The probe slots of the compiled module, in source order; the kernel returns them after the
// script's own outputs, in slot order.
std::vector<Site> sites(const ir::Module& m) {
  std::vector<Site> out;
  const std::string prefix = frontend::kProbePrefix;
  for (const std::string& g : m.globals) {
    if (g.compare(0, prefix.size(), prefix) != 0) continue;
    auto f = split(g.substr(prefix.size()), '|');
    if (f.size() != 5) continue;
    out.push_back(
        {f[0], f[1], f[2], static_cast<uint32_t>(std::stoul(f[3])), static_cast<uint32_t>(std::stoul(f[4])), 0});
  }
  const size_t first = m.kernel_function().num_results - out.size();
  for (size_t k = 0; k < out.size(); ++k) out[k].output = first + k;
  std::stable_sort(out.begin(), out.end(),
                   [](const Site& a, const Site& b) { return a.line != b.line ? a.line < b.line : a.col < b.col; });
  return out;
}

std::string where(const Site& s) {
  return std::to_string(s.line) + ":" + std::to_string(s.col) + (s.function.empty() ? "" : " " + s.function);
}

// min(a, b) and max(a, b): NaN if either is; of equal values, the first (docs/language.md).
std::string side(const std::string& kind, float a, float b) {
  if (a != a || b != b) return "NaN (an operand is NaN)";
  bool first = kind == "min" ? a <= b : a >= b;
  return std::string("takes ") + (first ? "the first" : "the second") + " (" + format_number(first ? a : b) + ")";
}

std::string interval_text(const math::Interval& v) {
  if (v.empty()) return "NaN";
  return "[" + format_number(v.lo) + ", " + format_number(v.hi) + "]" + (v.nan ? " or NaN" : "");
}

// The compiled probe of `path` (its entry point, or `entry`), on the VM.
int compile_probe(const std::string& path, const std::string& entry, Compiled& c) {
  Options o;
  o.backend = "vm";
  o.build.probe = true;
  return compile_file(path, entry, o, c);
}

}  // namespace

int probe_point(const std::string& path, const std::string& entry, const std::vector<float>& at, std::string& out) {
  Compiled c;
  if (int rc = compile_probe(path, entry, c); rc != kExitOk) return rc;
  const size_t n_in = c.spec.input_names.size(), n_out = c.kernel->num_outputs();
  std::vector<float> in(n_in, 0.0f), vals(n_out, 0.0f);
  std::copy_n(at.begin(), std::min(at.size(), n_in), in.begin());
  std::vector<const float*> ip;
  std::vector<float*> op;
  for (float& v : in) ip.push_back(&v);
  for (float& v : vals) op.push_back(&v);
  backends::RuntimeError err;
  if (!c.kernel->eval_batch(ip.data(), op.data(), 1, err)) {
    print_runtime_error(*c.script.file, err);
    return kExitInput;
  }
  std::vector<Site> ss = sites(*c.module);
  out += "at";
  for (size_t k = 0; k < n_in; ++k) out += " " + c.spec.input_names[k] + "=" + format_number(in[k]);
  out += ": " + format_number(vals[0]) + "\n";
  for (size_t k = 0; k < ss.size(); ++k) {
    const Site& s = ss[k];
    float v = vals[s.output];
    if (s.kind == "min" || s.kind == "max") {
      if (s.name != "1") continue;  // its pair is the next site at the same place
      float b = k + 1 < ss.size() ? vals[ss[k + 1].output] : v;
      out += where(s) + "  " + s.kind + "(" + format_number(v) + ", " + format_number(b) + ") " + side(s.kind, v, b) +
          "\n";
    } else if (s.kind == "if" || s.kind == "?:") {
      out += where(s) + "  " + s.kind + " " + (v != v ? "not reached" : v != 0 ? "true" : "false") + "\n";
    } else {
      out += where(s) + "  " + s.name + " = " + format_number(v) + (v != v ? " (or not reached)" : "") +
          (s.kind == "arg" ? " (argument)" : "") + "\n";
    }
  }
  return kExitOk;
}

int probe_box(const std::string& path, const std::string& entry, const std::vector<float>& box, std::string& out) {
  Compiled c;
  if (int rc = compile_probe(path, entry, c); rc != kExitOk) return rc;
  const ir::Function& fn = c.module->kernel_function();
  if (!ir::interval_evaluable(fn)) {
    std::cerr << path << ": error: the script keeps loops, calls or memory after optimisation, so intervals cannot "
              << "bound it (probe a point instead)\n";
    return kExitInput;
  }
  std::vector<math::Interval> inputs;
  for (size_t k = 0; k < c.spec.input_names.size(); ++k)
    inputs.push_back(2 * k + 1 < box.size() ? math::Interval{std::min(box[2 * k], box[2 * k + 1]),
                                                             std::max(box[2 * k], box[2 * k + 1]), false}
                                            : math::Interval::point(0));
  ir::IntervalEval ev;
  ir::eval_intervals(fn, inputs, ev);
  std::vector<Site> ss = sites(*c.module);
  out += "over";
  for (size_t k = 0; k < inputs.size(); ++k) out += " " + c.spec.input_names[k] + " in " + interval_text(inputs[k]);
  out += ": " + interval_text(ev.outputs[0]) + "\n";
  for (size_t k = 0; k < ss.size(); ++k) {
    const Site& s = ss[k];
    math::Interval v = ev.outputs[s.output];
    if (s.kind == "min" || s.kind == "max") {
      if (s.name != "1") continue;
      math::Interval b = k + 1 < ss.size() ? ev.outputs[ss[k + 1].output] : v;
      ir::Choice ch = ir::choice_of(s.kind == "min" ? ir::Op::Min : ir::Op::Max, v, b, {});
      out += where(s) + "  " + s.kind + "(" + interval_text(v) + ", " + interval_text(b) + ") " +
          (ch == ir::Choice::Left        ? "always the first"
               : ch == ir::Choice::Right ? "always the second"
                                         : "either") +
          "\n";
    } else if (s.kind == "if" || s.kind == "?:") {
      math::Truth t = math::truth_of(v);
      out += where(s) + "  " + s.kind + " " +
          (t == math::Truth::Always      ? "always true"
               : t == math::Truth::Never ? "always false"
                                         : "either") +
          "\n";
    } else {
      out += where(s) + "  " + s.name + (v.empty() ? " not reached (or NaN)" : " in " + interval_text(v)) +
          (s.kind == "arg" ? " (argument)" : "") + "\n";
    }
  }
  return kExitOk;
}

int cmd_probe(const std::string& file, const std::string& entry, const std::string& at, const std::string& box) {
  if (refuse_scene(file)) return kExitInput;
  if (at.empty() == box.empty()) {
    std::cerr << "error: fscript probe needs --at x,y,z[,t] or --bound x0,x1,y0,y1,z0,z1[,t0,t1]\n";
    return kExitUsage;
  }
  std::vector<float> v;
  for (const std::string& part : split(at.empty() ? box : at, ',')) {
    float x;
    if (!parse_number(part, x)) {
      std::cerr << "error: " << (at.empty() ? "--bound" : "--at") << ": '" << part << "' is not a number\n";
      return kExitUsage;
    }
    v.push_back(x);
  }
  if (!box.empty() && v.size() % 2) {
    std::cerr << "error: --bound takes pairs lo,hi (x0,x1,y0,y1,z0,z1[,t0,t1]); it has " << v.size() << " numbers\n";
    return kExitUsage;
  }
  std::string out;
  int rc = at.empty() ? probe_box(file, entry, v, out) : probe_point(file, entry, v, out);
  std::cout << out;
  return rc;
}

}  // namespace fscript::cli
