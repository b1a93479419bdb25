#pragma once
// The compile driver: source text -> parsed and analysed Script -> IR module for a kernel spec
// (lowered, optionally optimised). Used by the CLI, the tests and (later) the scene layer and LSP.
#include <memory>
#include <string>

#include "frontend/diagnostics.h"
#include "frontend/fscript/ast.h"
#include "frontend/fscript/entry.h"
#include "frontend/fscript/sema.h"
#include "ir/ir.h"

namespace fscript::frontend {

struct Script {
  std::unique_ptr<SourceFile> file;
  std::unique_ptr<Program> prog;
  SemaResult sema;
};

// Parses and analyses; returns false when any error was reported.
bool load_script(std::unique_ptr<SourceFile> file, DiagnosticSink& diag, Script& out,
                 const std::vector<std::string>& extra_globals = {});

struct BuildOptions {
  bool optimize = true;
  bool verify_each = false;  // verifier after every pass (tests)
};

// Lowers (and optimises) the script for `spec`. Lowering warnings go to `diag`. Returns nullptr
// only if the verifier rejects the result, which is a compiler bug (message in `error`).
std::unique_ptr<ir::Module> build_module(const Script& s, const KernelSpec& spec, DiagnosticSink& diag,
                                         const BuildOptions& opts, std::string& error);

}  // namespace fscript::frontend
