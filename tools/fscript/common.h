#pragma once
// Shared pieces of the fscript commands: loading and compiling a script to a Kernel with
// diagnostics printed, number formatting and parsing per the CLI contract.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "frontend/diagnostics.h"
#include "engine/driver/driver.h"

namespace fscript::cli {

constexpr int kExitOk = 0;
constexpr int kExitInput = 1;
constexpr int kExitUsage = 2;

// The command line's choices are the compile driver's options (backend "" = backends::default_backend()).
using Options = driver::CompileOptions;
using Compiled = driver::Compiled;

// Reads FILE ("-" is standard input). On failure prints "error: cannot read ..." and returns false.
bool read_source(const std::string& path, std::string& text);

// Prints every diagnostic of the sink to standard error.
void print_diagnostics(const frontend::DiagnosticSink& sink);

// The generated code of backend `name` as text: VM bytecode, or the JIT's assembly; "" with a
// message when there is none (emit-asm, the REPL's :asm).
std::string backend_listing(const std::string& name, const ir::Module& m, const backends::Kernel* kernel,
                            const backends::Budgets& budgets, std::string& error);

// Reads `path` and runs the compile driver for `entry` ("" = the script's entry point; "FRep"
// style names match without case), printing what went wrong. Returns an exit status (0 = ready).
int compile_file(const std::string& path, const std::string& entry, const Options& opts, Compiled& out,
                 bool want_kernel = true);

// Numbers: %.9g, nan (never -nan), inf, -inf.
std::string format_number(float v);
// A .wrl scene (also .wrl.gz, .wrz) rather than a .fs script.
bool is_scene_path(const std::string& p);
// For commands that take a script: true (with the message printed) when `path` is a scene instead.
bool refuse_scene(const std::string& path);
// Accepts decimal, hex float, nan, inf, -inf, -0. Returns false on anything else.
bool parse_number(const std::string& text, float& out);

// --size: W or WxH, each 1 to 32,768.
bool parse_size(const std::string& s, uint32_t& w, uint32_t& h);
// Exactly n finite numbers separated by commas (--bounds, --view).
bool parse_numbers(const std::string& s, size_t n, float* out);

// Prints a runtime error as a compiler would: "FILE:LINE:COL: error: message", the line, a caret.
void print_runtime_error(const frontend::SourceFile& file, const backends::RuntimeError& err);

}  // namespace fscript::cli
