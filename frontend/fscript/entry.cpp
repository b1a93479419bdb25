// Entry-point kernel specifications.
#include "frontend/fscript/entry.h"

#include <algorithm>

namespace fscript::frontend {
namespace {

// Inputs (x, y, z, t) for a point in space: x also sets u, and so on (u v w equal x y z).
void cartesian_inputs(const SemaResult& s, KernelSpec& spec) {
  spec.input_names = {"x", "y", "z", "t"};
  spec.input_globals = {{s.global_slot("x"), s.global_slot("u")},
                        {s.global_slot("y"), s.global_slot("v")},
                        {s.global_slot("z"), s.global_slot("w")},
                        {s.global_slot("t")}};
}

// Inputs (u, v, w, t) for a parametric point; x y z start equal to u v w for assignment lists.
void parametric_inputs(const SemaResult& s, KernelSpec& spec, bool also_xyz) {
  spec.input_names = {"u", "v", "w", "t"};
  spec.input_globals = {{s.global_slot("u")}, {s.global_slot("v")}, {s.global_slot("w")}, {s.global_slot("t")}};
  if (also_xyz)
    for (int k = 0; k < 3; ++k) spec.input_globals[k].push_back(s.global_slot(std::string(1, "xyz"[k])));
}

KernelOutput call_output(const SemaResult& s, int fn, const std::string& name) {
  KernelOutput o;
  o.name = name;
  o.function = fn;
  for (size_t k = 0; k < s.functions[fn].params.size(); ++k) o.args.push_back(static_cast<int>(k));
  return o;
}

void triple_spec(const SemaResult& s, const int (&fns)[3], const char* names, KernelSpec& spec) {
  parametric_inputs(s, spec, false);
  for (int k = 0; k < 3; ++k) {
    if (fns[k] >= 0) {
      spec.outputs.push_back(call_output(s, fns[k], std::string(1, names[k])));
    } else {
      KernelOutput o;
      o.name = std::string(1, names[k]);
      spec.outputs.push_back(o);  // the constant 0
    }
  }
}

}  // namespace

bool frep_spec(const SemaResult& s, KernelSpec& spec, std::string& error) {
  if (s.entry.frep < 0) {
    error = "the script defines no FRep(x, y, z[, t]) function";
    return false;
  }
  spec = {};
  cartesian_inputs(s, spec);
  spec.outputs.push_back(call_output(s, s.entry.frep, "f"));
  return true;
}

bool default_spec(const SemaResult& s, KernelSpec& spec, std::string& error) {
  spec = {};
  if (s.form == ScriptForm::Expression) {
    cartesian_inputs(s, spec);
    KernelOutput o;
    o.name = "value";
    o.global = static_cast<int>(s.globals.size());  // "$value" is appended by lowering
    spec.outputs.push_back(o);
    return true;
  }
  if (s.form == ScriptForm::Assignments) {
    parametric_inputs(s, spec, true);
    std::vector<std::string> names;
    for (const char* n : {"x", "y", "z", "r", "g", "b"})
      for (const auto& a : s.assigned_globals)
        if (a == n) names.push_back(n);
    if (names.empty()) names = s.assigned_globals;
    for (const auto& n : names) {
      KernelOutput o;
      o.name = n;
      o.global = s.global_slot(n);
      spec.outputs.push_back(o);
    }
    return true;
  }
  if (s.entry.frep >= 0) return frep_spec(s, spec, error);
  if (s.entry.parametric[0] >= 0 || s.entry.parametric[1] >= 0 || s.entry.parametric[2] >= 0) {
    triple_spec(s, s.entry.parametric, "xyz", spec);
    return true;
  }
  if (s.entry.colour[0] >= 0 || s.entry.colour[1] >= 0 || s.entry.colour[2] >= 0) {
    triple_spec(s, s.entry.colour, "rgb", spec);
    return true;
  }
  if (s.functions.size() == 1) return function_spec(s, s.functions[0].name, spec, error);  // the only function
  error =
      "no entry point: define FRep(x, y, z[, t]), parametric_x/y/z(u, v, w[, t]) or parametric_r/g/b, "
      "or name a function with --entry";
  return false;
}

bool named_inputs_spec(const SemaResult& s, const std::vector<std::string>& names, KernelSpec& spec,
                       std::string& error) {
  if (s.form != ScriptForm::Expression) {
    error = "an operation is one expression of f, g (f1, f2, ...) and t, such as \"f*(1-t)+g*t\"";
    return false;
  }
  spec = {};
  for (const auto& n : names) {
    spec.input_names.push_back(n);
    spec.input_globals.push_back({s.global_slot(n)});
  }
  KernelOutput o;
  o.name = "value";
  o.global = static_cast<int>(s.globals.size());  // "$value"
  spec.outputs.push_back(o);
  return true;
}

bool point_spec(const SemaResult& s, KernelSpec& spec, bool& rgb, std::string& error) {
  spec = {};
  for (const char* n : {"x", "y", "z", "u", "v", "w", "t"}) {
    spec.input_names.push_back(n);
    spec.input_globals.push_back({s.global_slot(n)});
  }
  auto assigned = [&](const char* n) {
    return std::find(s.assigned_globals.begin(), s.assigned_globals.end(), n) != s.assigned_globals.end();
  };
  KernelOutput value;
  value.name = "value";
  value.constant = 0;
  bool colour_functions = s.entry.colour[0] >= 0 || s.entry.colour[1] >= 0 || s.entry.colour[2] >= 0;
  if (s.form == ScriptForm::Expression) {
    value.global = static_cast<int>(s.globals.size());  // "$value"
  } else if (s.entry.frep >= 0) {
    value.function = s.entry.frep;
    static const int kArgs[] = {0, 1, 2, 6};
    for (size_t k = 0; k < s.functions[s.entry.frep].params.size(); ++k) value.args.push_back(kArgs[k]);
  } else if (s.form == ScriptForm::Script && !colour_functions) {
    error = "no entry point: a colour or texture script defines FRep(x, y, z[, t]) or parametric_r/g/b(u, v, w[, t])";
    return false;
  }
  spec.outputs.push_back(value);
  rgb = colour_functions || assigned("r") || assigned("g") || assigned("b");
  for (int k = 0; k < 3; ++k) {
    KernelOutput o;
    o.name = std::string(1, "rgb"[k]);
    if (s.entry.colour[k] >= 0) {
      o.function = s.entry.colour[k];
      for (size_t a = 0; a < s.functions[o.function].params.size(); ++a) o.args.push_back(static_cast<int>(3 + a));
    } else {
      o.global = s.global_slot(o.name);
    }
    spec.outputs.push_back(o);
  }
  return true;
}

bool function_spec(const SemaResult& s, const std::string& name, KernelSpec& spec, std::string& error) {
  int fn = s.function_index(name, false);
  if (fn < 0) fn = s.function_index(name, true);
  if (fn < 0) {
    error = "no function named '" + name + "'";
    return false;
  }
  spec = {};
  if (fn == s.entry.frep) return frep_spec(s, spec, error);
  bool parametric = false;
  for (int k = 0; k < 3; ++k) parametric |= fn == s.entry.parametric[k] || fn == s.entry.colour[k];
  size_t n = s.functions[fn].params.size();
  if (parametric) {
    parametric_inputs(s, spec, false);
    spec.input_names.resize(std::max<size_t>(n, 0));
    spec.input_globals.resize(n);
  } else {
    for (size_t k = 0; k < n; ++k) {
      spec.input_names.push_back(s.symbols[s.functions[fn].params[k]].name);
      spec.input_globals.push_back({});
    }
  }
  spec.outputs.push_back(call_output(s, fn, s.functions[fn].name));
  return true;
}

}  // namespace fscript::frontend
