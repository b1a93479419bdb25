// The compile driver: load -> entry -> lower -> optimise -> backend -> kernel, in one place.
#include "engine/driver/driver.h"

#include "frontend/fscript/lower.h"
#include "ir/passes/gradient.h"
#include "ir/passes/passes.h"
#include "ir/verifier.h"
#include "backends/row_split_kernel.h"

namespace fscript::driver {

EntryChoice default_entry() { return frontend::default_spec; }

EntryChoice named_entry(const std::string& name) {
  if (name.empty()) return default_entry();
  return [name](const frontend::SemaResult& sema, frontend::KernelSpec& spec, std::string& error) {
    return frontend::function_spec(sema, name, spec, error);
  };
}

std::unique_ptr<ir::Module> build_module(const frontend::Script& s, const frontend::KernelSpec& spec,
                                         frontend::DiagnosticSink& diag, const BuildOptions& opts, std::string& error) {
  frontend::KernelSpec probed = spec;
  probed.probe = opts.probe;
  auto m = frontend::lower_to_ir(*s.prog, s.sema, probed, *s.file, diag);
  if (opts.verify_each) {
    error = ir::verify(*m);
    if (!error.empty()) {
      error = "after lowering: " + error;
      return nullptr;
    }
  }
  if (opts.optimize) {
    ir::PassOptions po;
    po.verify_each = opts.verify_each;
    error = ir::optimize(*m, po);
    if (!error.empty()) return nullptr;
  }
  return m;
}

Outcome compile_kernel(const ir::Module& m, const std::string& name, const backends::Budgets& budgets,
                       std::unique_ptr<backends::Kernel>& out) {
  std::string n = name.empty() ? backends::default_backend() : name;
  auto be = backends::make_backend(n);
  if (!be) return {Stage::NoBackend, backends::missing_backend_message(n)};
  Outcome o;
  out = be->compile(m, budgets, o.error);
  if (!out) o.stage = Stage::Backend;
  else out = backends::with_row_split(std::move(out), n, m, budgets);
  return o;
}

std::unique_ptr<ir::Module> gradient_ir(const ir::Module& m) { return ir::gradient_module(m); }

std::unique_ptr<backends::Kernel> compile_gradient(const ir::Module& g, const std::string& name,
                                                   const backends::Budgets& budgets) {
  std::unique_ptr<backends::Kernel> k;
  if (name == "llvm" && g.instruction_count() > kMaxLlvmGradientOps) return k;
  if (!compile_kernel(g, name, budgets, k).ok()) k.reset();
  return k;
}

std::unique_ptr<backends::Kernel> gradient_kernel(const ir::Module& m, const std::string& name,
                                                  const backends::Budgets& budgets) {
  std::unique_ptr<ir::Module> g = gradient_ir(m);
  return g ? compile_gradient(*g, name, budgets) : nullptr;
}

Outcome compile(std::unique_ptr<frontend::SourceFile> file, const EntryChoice& entry, const CompileOptions& opts,
                frontend::DiagnosticSink& diag, Compiled& out) {
  if (!frontend::load_script(std::move(file), diag, out.script, opts.extra_globals)) return {Stage::Source, ""};
  Outcome o;
  if (!entry(out.script.sema, out.spec, o.error)) return {Stage::Entry, o.error};
  out.module = build_module(out.script, out.spec, diag, opts.build, o.error);
  if (!out.module) return {Stage::Internal, o.error};
  if (!opts.want_kernel) return o;
  return compile_kernel(*out.module, opts.backend, opts.budgets, out.kernel);
}

}  // namespace fscript::driver
