#pragma once
// Lowering: annotated AST -> SSA IR (Braun et al., "Simple and Efficient Construction of SSA
// Form": locals become SSA values with phis; globals and arrays stay explicit memory until the
// promote_globals pass). Also synthesizes the kernel function that a backend compiles.
#include <memory>
#include <vector>

#include "frontend/diagnostics.h"
#include "frontend/fscript/ast.h"
#include "frontend/fscript/sema.h"
#include "ir/ir.h"

namespace fscript::frontend {

// One output of a kernel: a call of a user function with kernel inputs as arguments, the final
// value of a global, or a constant (a parametric coordinate the script does not define).
struct KernelOutput {
  std::string name;        // for printing (`name=value`)
  int function = -1;       // user function index, or -1
  std::vector<int> args;   // kernel input indices passed to the function
  int global = -1;         // global slot, or -1
  float constant = 0;      // when function and global are both -1
};

// How a kernel maps its inputs to the program: each input sets some globals (x and u for an FRep
// point), then the top-level statements run, then the outputs are computed in order.
struct KernelSpec {
  std::vector<std::string> input_names;
  std::vector<std::vector<int>> input_globals;  // per input: global slots it sets
  std::vector<KernelOutput> outputs;
  // The probe (fscript probe, the REPL's :probe): every write of a variable, every function's
  // arguments, each if's and ?:'s condition and each min's and max's operands also go to a probe
  // slot, a module global named kProbePrefix + "kind|function|name|line|col" (kind: var, arg,
  // if, ?:, min, max; a min's or max's name is 1 or 2, its operand), and the kernel returns the
  // probe slots' last values after its outputs, in slot order (NaN: never reached).
  bool probe = false;
};

constexpr const char* kProbePrefix = "\x01probe|";

constexpr const char* kKernelName = "kernel";

// Lowers every user function and the kernel (last in the module). Warnings (maybe-unassigned,
// missing return) go to `diag`.
std::unique_ptr<ir::Module> lower_to_ir(const Program& prog, const SemaResult& sema, const KernelSpec& spec,
                                        const SourceFile& file, DiagnosticSink& diag);

}  // namespace fscript::frontend
