// The pass pipeline:
//
//   inline ─► promote ─► ┌ simplify ─► fold ─► gvn ─► ifconv ─► dce ┐ (until nothing changes,
//                        └──────────────────────────────────────────┘  at most 8 rounds)
//
// Inlining first makes each kernel one function, so promote turns every global into SSA values;
// the loop then folds, shares and if-converts until a fixed point.
#include <sstream>

#include "ir/passes/passes.h"
#include "ir/verifier.h"

namespace fscript::ir {
namespace {

using ModulePass = bool (*)(Module&);
using FunctionPass = bool (*)(Function&);

struct PassEntry {
  const char* name;
  ModulePass module_pass;
  FunctionPass function_pass;
};

constexpr PassEntry kPasses[] = {
    {"inline", run_inline, nullptr},     {"promote", run_promote_globals, nullptr},
    {"fold", nullptr, run_const_fold},   {"dce", nullptr, run_dce},
    {"gvn", nullptr, run_gvn},           {"simplify", nullptr, run_simplify_cfg},
    {"ifconv", nullptr, run_if_convert},
};

const PassEntry* find_pass(const std::string& name) {
  for (const auto& p : kPasses)
    if (name == p.name) return &p;
  return nullptr;
}

// Runs one pass over the module; returns "" or a verifier error.
std::string run_one(Module& m, const PassEntry& p, const PassOptions& opts, bool& changed) {
  bool c = false;
  if (p.module_pass) {
    c = p.module_pass(m);
  } else {
    for (auto& f : m.functions) c |= p.function_pass(*f);
  }
  if (c && opts.trace) opts.trace->push_back(p.name);
  changed |= c;
  if (opts.verify_each) {
    std::string e = verify(m);
    if (!e.empty()) return "after pass '" + std::string(p.name) + "': " + e;
  }
  return "";
}

}  // namespace

std::string run_passes(Module& m, const std::string& names, const PassOptions& opts) {
  std::stringstream ss(names);
  std::string n;
  while (std::getline(ss, n, ',')) {
    const PassEntry* p = find_pass(n);
    if (!p) return "unknown pass '" + n + "'";
    bool changed = false;
    if (std::string e = run_one(m, *p, opts, changed); !e.empty()) return e;
  }
  for (auto& f : m.functions) f->renumber();
  return "";
}

std::string optimize(Module& m, const PassOptions& opts) {
  bool changed = false;
  for (const char* n : {"inline", "promote"})
    if (std::string e = run_one(m, *find_pass(n), opts, changed); !e.empty()) return e;
  for (int round = 0; round < 8; ++round) {
    changed = false;
    for (const char* n : {"simplify", "fold", "gvn", "ifconv", "dce"})
      if (std::string e = run_one(m, *find_pass(n), opts, changed); !e.empty()) return e;
    if (!changed) break;
  }
  for (auto& f : m.functions) f->renumber();
  return "";
}

}  // namespace fscript::ir
