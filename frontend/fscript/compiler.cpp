// Compile driver: parse, analyse, lower, optimise.
#include "frontend/fscript/compiler.h"

#include "frontend/fscript/lower.h"
#include "frontend/fscript/parser.h"
#include "ir/passes/passes.h"
#include "ir/verifier.h"

namespace fscript::frontend {

bool load_script(std::unique_ptr<SourceFile> file, DiagnosticSink& diag, Script& out,
                 const std::vector<std::string>& extra_globals) {
  size_t errors_before = diag.error_count();
  out.file = std::move(file);
  out.prog = parse(*out.file, diag);
  out.sema = analyze(*out.prog, *out.file, diag, extra_globals);
  return diag.error_count() == errors_before;
}

std::unique_ptr<ir::Module> build_module(const Script& s, const KernelSpec& spec, DiagnosticSink& diag,
                                         const BuildOptions& opts, std::string& error) {
  auto m = lower_to_ir(*s.prog, s.sema, spec, *s.file, diag);
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

}  // namespace fscript::frontend
