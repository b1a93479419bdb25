#pragma once
// Small helpers shared by the unit tests: compile a script text, evaluate an entry.
#include <memory>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "frontend/fscript/compiler.h"

namespace fscript::test {

struct Built {
  frontend::DiagnosticSink diag;
  frontend::Script script;
  std::unique_ptr<ir::Module> module;
  std::unique_ptr<backend::Kernel> kernel;
  bool ok = false;
};

// Compiles `text` for `entry` ("" = the script's entry point) on backend `be`.
inline std::unique_ptr<Built> build(const std::string& text, const std::string& entry = "", bool optimize = true,
                                    const backend::Budgets& budgets = {}, const std::string& be = "vm") {
  auto b = std::make_unique<Built>();
  if (!frontend::load_script(std::make_unique<frontend::SourceFile>("test.fs", text), b->diag, b->script)) return b;
  frontend::KernelSpec spec;
  std::string err;
  bool have = entry.empty() ? frontend::default_spec(b->script.sema, spec, err)
                            : frontend::function_spec(b->script.sema, entry, spec, err);
  if (!have) return b;
  frontend::BuildOptions bo;
  bo.optimize = optimize;
  bo.verify_each = true;
  b->module = frontend::build_module(b->script, spec, b->diag, bo, err);
  if (!b->module) return b;
  b->kernel = backend::make_backend(be)->compile(*b->module, budgets, err);
  b->ok = b->kernel != nullptr;
  return b;
}

inline float eval1(const Built& b, std::vector<float> in) {
  in.resize(b.kernel->num_inputs(), 0.0f);
  std::vector<float> out(b.kernel->num_outputs());
  backend::RuntimeError err;
  if (!b.kernel->eval(in.data(), out.data(), err)) return -12345.0f;
  return out[0];
}

inline std::string messages(const frontend::DiagnosticSink& d) { return frontend::render_all(d); }

}  // namespace fscript::test
