// Loading a script: parse, then analyse.
#include "frontend/fscript/script.h"

#include "frontend/fscript/parser.h"

namespace fscript::frontend {

bool load_script(std::unique_ptr<SourceFile> file, DiagnosticSink& diag, Script& out,
                 const std::vector<std::string>& extra_globals) {
  size_t errors_before = diag.error_count();
  out.file = std::move(file);
  out.prog = parse(*out.file, diag);
  out.sema = analyze(*out.prog, *out.file, diag, extra_globals);
  return diag.error_count() == errors_before;
}

}  // namespace fscript::frontend
