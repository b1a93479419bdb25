// Fuzz target: bytes as an FScript file through the lexer, parser, sema, lowering, the verifier
// after every pass, the gradient pass, and one evaluation on the VM. Diagnostics are fine; crashes,
// hangs, leaks, a verifier failure, a refusal without an error, or a gradient kernel whose f is not
// the kernel's are findings.
#include <cstddef>
#include <cstdint>
#include <memory>

#include "ir/passes/gradient.h"
#include "ir/text.h"
#include "ir/verifier.h"
#include "engine/driver/driver.h"
#include "runtime/support/big_stack.h"
#include "tests/fuzz/fuzz_support.h"

using namespace fscript;

namespace {

void one_input(const std::string& text) {
  driver::CompileOptions o = fuzz::compile_options(true);
  frontend::DiagnosticSink diag;
  driver::Compiled c;
  driver::Outcome r =
      driver::compile(std::make_unique<frontend::SourceFile>("fuzz.fs", text), driver::default_entry(), o, diag, c);
  if (r.stage == driver::Stage::Internal) fuzz::finding("the verifier rejected the compiler's IR: " + r.error, text);
  if (r.stage == driver::Stage::Source && !diag.has_errors()) fuzz::finding("refused without an error", text);
  frontend::render_all(diag);  // every diagnostic renders (source line, caret)
  if (!c.module) return;
  std::string v = ir::verify(*c.module);
  if (!v.empty()) fuzz::finding("verifier: " + v, text);
  // The text form round-trips: print(read(print(m))) == print(m).
  std::string printed = ir::print(*c.module), error;
  auto back = ir::read(printed, error);
  if (!back) fuzz::finding("the IR printer wrote what the reader refuses: " + error + "\n" + printed, text);
  if (ir::print(*back) != printed) fuzz::finding("the IR text does not round-trip", text);
  if (!c.kernel) return;
  std::vector<float> in(c.kernel->num_inputs(), 0.25f), out(c.kernel->num_outputs());
  backends::RuntimeError err;
  bool ran = c.kernel->eval(in.data(), out.data(), err);
  if (!ran && err.message.empty()) fuzz::finding("a runtime error without a message", text);
  // Small kernels only: optimising a module four times the size tripled the cost of an execution,
  // and what the rules can get wrong shows in a few operations.
  if (c.module->instruction_count() > 400) return;
  auto g = ir::gradient_module(*c.module);
  if (!g) return;
  if (std::string gv = ir::verify(*g); !gv.empty()) fuzz::finding("verifier, gradient module: " + gv, text);
  std::unique_ptr<backends::Kernel> gk;
  if (!driver::compile_kernel(*g, "vm", o.budgets, gk).ok())
    fuzz::finding("the gradient module does not compile", text);
  float d[4];
  if (!ran || !gk->eval(in.data(), d, err)) return;  // a straight-line kernel has no runtime error
  if (!(d[0] == out[0] || (d[0] != d[0] && out[0] != out[0])))
    fuzz::finding("the gradient kernel's f is not the kernel's", text);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  // As the tools do: deeply nested (accepted) input needs more than the default stack.
  fuzz::run_deep([&] { one_input(text); });
  return 0;
}
