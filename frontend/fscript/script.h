#pragma once
// A loaded script: its source, syntax tree and analysis. Lowering it to a kernel (and optimising
// and compiling that) is the compile driver's job, in engine/driver.
#include <memory>
#include <string>
#include <vector>

#include "frontend/diagnostics.h"
#include "frontend/fscript/ast.h"
#include "frontend/fscript/sema.h"

namespace fscript::frontend {

struct Script {
  std::unique_ptr<SourceFile> file;
  std::unique_ptr<Program> prog;
  SemaResult sema;
};

// Parses and analyses; returns false when any error was reported.
bool load_script(std::unique_ptr<SourceFile> file, DiagnosticSink& diag, Script& out,
                 const std::vector<std::string>& extra_globals = {});

}  // namespace fscript::frontend
