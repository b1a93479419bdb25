#pragma once
// The compile driver: the one chain from FScript text to a Kernel (load, choose the entry point,
// lower, optimise, pick the backend, compile) used by the CLI, the REPL, the scene model and tests.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "frontend/diagnostics.h"
#include "frontend/fscript/entry.h"
#include "frontend/fscript/script.h"
#include "ir/ir.h"

namespace fscript::driver {

struct BuildOptions {
  bool optimize = true;
  bool verify_each = false;  // the verifier after lowering and after every pass (tests)
  bool probe = false;        // frontend::KernelSpec::probe: the variables as extra outputs
};

// Everything one compilation depends on. The ISA (FSCRIPT_ISA) and the llvm disk cache
// (--llvm-disk-cache) are not here: they are chosen once per process, before any compile.
struct CompileOptions {
  std::string backend;  // "" = the fastest backend this binary has
  backends::Budgets budgets;
  BuildOptions build;
  bool want_kernel = true;                 // false: stop at the optimised module (emit-ir)
  std::vector<std::string> extra_globals;  // names a script may use undeclared (an operation's f, g)
};

// Chooses the kernel to build from an analysed script: fills `spec` or returns false with a message.
using EntryChoice = std::function<bool(const frontend::SemaResult&, frontend::KernelSpec&, std::string&)>;
// The script's own entry point (frontend::default_spec).
EntryChoice default_entry();
// The function `name` ("" = the default entry), as frontend::function_spec finds it.
EntryChoice named_entry(const std::string& name);

struct Compiled {
  frontend::Script script;
  frontend::KernelSpec spec;
  std::unique_ptr<ir::Module> module;
  std::unique_ptr<backends::Kernel> kernel;
};

// Where a compilation stopped. Callers word the failure for their users; `error` says why.
enum class Stage {
  Done,
  Source,     // parse or analysis errors: they are in the sink, `error` is empty
  Entry,      // no such entry point, or the script's form does not fit the role
  Internal,   // the IR verifier rejected lowering or a pass: a compiler bug
  NoBackend,  // the backend asked for is not built into this binary
  Backend,    // the backend could not compile (an environment failure)
};

struct Outcome {
  Stage stage = Stage::Done;
  std::string error;
  bool ok() const { return stage == Stage::Done; }
};

// Runs the whole chain. `out.script` holds the loaded script whatever happened after loading.
Outcome compile(std::unique_ptr<frontend::SourceFile> file, const EntryChoice& entry, const CompileOptions& opts,
                frontend::DiagnosticSink& diag, Compiled& out);

// The middle of the chain for a script already loaded: lowers (and optimises) it for `spec`.
// Lowering warnings go to `diag`. nullptr only if the verifier rejects the result (`error` says why).
std::unique_ptr<ir::Module> build_module(const frontend::Script& s, const frontend::KernelSpec& spec,
                                         frontend::DiagnosticSink& diag, const BuildOptions& opts, std::string& error);

// The end of the chain: the kernel of `m` on backend `name` ("" = backends::default_backend()).
Outcome compile_kernel(const ir::Module& m, const std::string& name, const backends::Budgets& budgets,
                       std::unique_ptr<backends::Kernel>& out);

// The kernel of f and its gradient (ir::gradient_module: outputs f, df/dx, df/dy, df/dz) for the
// FRep module `m` on backend `name`; nullptr when f has no gradient here or it did not compile
// (the polygonizers then take differences), and with `llvm` for a gradient of more than
// kMaxLlvmGradientOps operations: LLVM compiles about 50 us per operation, so prospero's gradient
// (30,000) would cost 1.5 s, far more than the differences it saves (auto and sse compile it in
// milliseconds, the VM at once).
constexpr size_t kMaxLlvmGradientOps = 2000;
std::unique_ptr<backends::Kernel> gradient_kernel(const ir::Module& m, const std::string& name,
                                                  const backends::Budgets& budgets);
// The two halves of gradient_kernel: the gradient module (ir::gradient_module; nullptr: none), and
// its kernel on backend `name` (nullptr: too big for llvm, or it did not compile).
std::unique_ptr<ir::Module> gradient_ir(const ir::Module& m);
std::unique_ptr<backends::Kernel> compile_gradient(const ir::Module& g, const std::string& name,
                                                   const backends::Budgets& budgets);

}  // namespace fscript::driver
