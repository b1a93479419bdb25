// fscript run, eval, check, emit-ir, emit-asm.
#include "tools/fscript/commands.h"
#include "runtime/support/files.h"

#include <unistd.h>

#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "backends/runtime_errors.h"
#if defined(FS_HAVE_SSE)
#include "backends/sse/sse_backend.h"
#endif
#include "backends/llvm_module.h"
#include "backends/vm/vm_backend.h"
#include "frontend/check.h"
#include "frontend/fscript/formatter.h"
#include "frontend/fscript/parser.h"
#include "frontend/fscript/embedded.h"
#include "frontend/vrml/scene_scripts.h"
#include "frontend/vrml/script_scene.h"
#include "frontend/vrml/scene_file.h"
#include "frontend/vrml/vrml_parser.h"
#include "engine/scene/shape_diagnostics.h"
#include "ir/analysis.h"
#include "ir/passes/passes.h"
#include "ir/passes/gradient.h"
#include "ir/text.h"

namespace fscript::cli {

namespace {

// Arguments for the kernel's inputs: the given ones, then 0 for the rest.
bool bind_args(const Compiled& c, const std::vector<float>& given, std::vector<float>& in, std::string& error) {
  size_t n = c.spec.input_names.size();
  if (given.size() > n) {
    error = "too many arguments: " + std::to_string(given.size()) + " given, the entry takes " + std::to_string(n);
    return false;
  }
  in = given;
  in.resize(n, 0.0f);
  return true;
}

void print_outputs(const Compiled& c, const float* out, bool named) {
  size_t n = c.spec.outputs.size();
  for (size_t k = 0; k < n; ++k) {
    if (named) std::cout << c.spec.outputs[k].name << "=";
    std::cout << format_number(out[k]) << (named || k + 1 == n ? "\n" : ",");
  }
}

}  // namespace

int cmd_run(const Options& o, const std::string& file, const std::string& entry, const std::vector<std::string>& args) {
  std::vector<float> given;
  for (const auto& a : args) {
    float v;
    if (!parse_number(a, v)) {
      std::cerr << "error: '" << a << "' is not a number\n";
      return kExitUsage;
    }
    given.push_back(v);
  }
  Compiled c;
  if (int rc = compile_file(file, entry, o, c); rc != kExitOk) return rc;
  std::vector<float> in, out(c.kernel->num_outputs());
  std::string error;
  if (!bind_args(c, given, in, error)) {
    std::cerr << "error: " << error << "\n";
    return kExitUsage;
  }
  backends::RuntimeError err;
  if (!c.kernel->eval(in.data(), out.data(), err)) {
    print_runtime_error(*c.script.file, err);
    return kExitInput;
  }
  bool named = entry.empty() && c.spec.outputs.size() > 1;
  named |= entry.empty() && c.script.sema.form == frontend::ScriptForm::Assignments;
  print_outputs(c, out.data(), named);
  return kExitOk;
}

int cmd_eval(const Options& o, const std::string& file, const std::string& entry, const std::string& points) {
  Compiled c;
  if (int rc = compile_file(file, entry, o, c); rc != kExitOk) return rc;
  std::string text;
  if (!read_source(points.empty() ? "-" : points, text)) return kExitInput;
  std::string where = points.empty() || points == "-" ? "<stdin>" : points;
  size_t n_in = c.spec.input_names.size();
  std::vector<std::vector<float>> cols(n_in);
  std::istringstream ss(text);
  std::string line;
  for (size_t ln = 1; std::getline(ss, line); ++ln) {
    size_t b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos || line[b] == '#') continue;
    std::vector<float> row;
    std::stringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) {
      float v;
      if (!parse_number(cell, v)) {
        std::cerr << where << ":" << ln << ": error: '" << cell << "' is not a number\n";
        return kExitInput;
      }
      row.push_back(v);
    }
    if (row.size() > n_in) {
      std::cerr << where << ":" << ln << ": error: " << row.size() << " values, but the entry takes " << n_in << "\n";
      return kExitInput;
    }
    row.resize(n_in, 0.0f);
    for (size_t k = 0; k < n_in; ++k) cols[k].push_back(row[k]);
  }
  size_t n = n_in ? cols[0].size() : 0;
  std::vector<const float*> in(n_in);
  for (size_t k = 0; k < n_in; ++k) in[k] = cols[k].data();
  std::vector<std::vector<float>> outs(c.kernel->num_outputs(), std::vector<float>(n));
  std::vector<float*> out;
  for (auto& v : outs) out.push_back(v.data());
  backends::RuntimeError err;
  if (!c.kernel->eval_batch(in.data(), out.data(), n, err)) {
    print_runtime_error(*c.script.file, err);
    return kExitInput;
  }
  std::string buf;
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < out.size(); ++k) buf += format_number(out[k][i]) + (k + 1 == out.size() ? "\n" : ",");
  }
  std::cout << buf;
  return kExitOk;
}

// Warnings only the optimised module shows: an array indexed by a known constant past its known
// length (fails whenever it runs). The script is compiled for its entry point; one without an
// entry (a library of functions) or that does not compile gets none.
size_t known_failures(std::unique_ptr<frontend::SourceFile> file, const std::vector<std::string>& extra_globals) {
  Options o;
  o.want_kernel = false;
  o.extra_globals = extra_globals;
  frontend::DiagnosticSink ignored;
  Compiled c;
  if (!driver::compile(std::move(file), driver::default_entry(), o, ignored, c).ok() || !c.module) return 0;
  auto found = ir::known_out_of_range(*c.module);
  for (const auto& k : found) {
    frontend::LineCol at{k.line, std::max(k.col, 1u)};
    std::cerr << frontend::render(
        frontend::located(frontend::Severity::Warning, c.script.file->path(), at, c.script.file->line_at(k.line),
                          backends::errors::array_index(k.array, k.index, k.length) + " whenever this runs"));
  }
  return found.size();
}

// known_failures of every script of a scene, each at the scene's own lines.
size_t known_failures_in_scene(const std::string& path, const std::string& text) {
  frontend::DiagnosticSink ignored;
  vrml::Scene scene;
  vrml::parse_scene(std::make_unique<frontend::SourceFile>(path, text), ignored, scene);
  std::vector<std::string> lines = frontend::split_lines(text);
  size_t n = 0;
  for (const auto& s : vrml::scene_scripts(scene)) {
    if (frontend::is_affine_field(s.script.field) || s.script.field == "operation") continue;
    auto file = std::make_unique<frontend::SourceFile>(path, s.script.text, s.script.line, s.script.col);
    file->set_outer_lines(lines);
    n += known_failures(std::move(file), {});
  }
  return n;
}

// The shape diagnostics (engine/scene/shape_diagnostics.h) of a scene's implicit shapes, or of a
// script's shape as fvrml-run draws it (one FShape, every other field at its default); the count
// of warnings. A script without an entry point (a library of functions) has no shape.
size_t shape_findings(const std::string& path, const std::string& text, bool is_wrl) {
  vrml::Scene scene;
  frontend::DiagnosticSink ignored;
  bool ok = vrml::scene_of_text(path, text, is_wrl, scene, ignored);
  scene::ModelOptions mo;
  mo.compile.backend = "vm";  // checks want answers at once, not native code
  scene::SceneModel model;
  if (!ok || !scene::build_scene_model(scene, mo, ignored, model)) return 0;
  size_t warnings = 0;
  for (const auto& f : scene::diagnose_scene(scene, model)) {
    std::cerr << frontend::render(f.diag);
    warnings += f.diag.severity == frontend::Severity::Warning;
  }
  return warnings;
}

int cmd_check(const std::vector<std::string>& files) {
  int rc = kExitOk;
  size_t scripts = 0, warnings = 0;
  for (const auto& path : files) {
    std::string text;
    bool is_wrl = is_scene_path(path);
    std::string error;
    if (is_wrl ? !vrml::read_scene_text(path, text, error) : !read_source(path, text)) {
      if (is_wrl) std::cerr << path << ":1:1: error: " << error << "\n";
      rc = kExitInput;
      continue;
    }
    frontend::DiagnosticSink diag;
    size_t n = 1;
    bool ok = is_wrl ? frontend::check_scene(path, text, diag, true, &n) : frontend::check_script(path, text, diag);
    if (!ok) rc = kExitInput;
    scripts += n, warnings += diag.all().size() - diag.error_count();
    print_diagnostics(diag);
    if (ok)
      warnings += (is_wrl ? known_failures_in_scene(path, text)
                          : known_failures(std::make_unique<frontend::SourceFile>(path, text), {})) +
          shape_findings(path, text, is_wrl);
  }
  // On a terminal, a word that all went well (a pipe or a script gets silence, as compilers give).
  if (rc == kExitOk && isatty(STDOUT_FILENO)) {
    std::cout << "ok: " << (files.size() > 1 ? std::to_string(files.size()) + " files, " : "") << scripts
              << (scripts == 1 ? " script" : " scripts") << ", no errors";
    if (warnings) std::cout << " (" << warnings << (warnings == 1 ? " warning" : " warnings") << ")";
    std::cout << "\n";
  }
  return rc;
}

int cmd_emit_ir(const std::string& file, const std::string& entry, bool opt, const std::string& passes, bool llvm,
                bool gradient) {
  Compiled c;
  std::string text;
  if (refuse_scene(file) || !read_source(file, text)) return kExitInput;
  frontend::DiagnosticSink diag;
  // No entry point is fine here: the listing shows the functions with an empty kernel.
  driver::EntryChoice chosen = driver::named_entry(entry);
  std::string no_entry;
  auto any_entry = [&](const frontend::SemaResult& sema, frontend::KernelSpec& spec, std::string& error) {
    if (!chosen(sema, spec, error)) spec = {}, no_entry = error.empty() ? "no entry point" : error;
    return true;
  };
  Options o;
  o.build.optimize = (opt || llvm || gradient) && passes.empty();
  o.want_kernel = false;
  driver::Outcome r = driver::compile(std::make_unique<frontend::SourceFile>(file, text), any_entry, o, diag, c);
  print_diagnostics(diag);
  if (r.stage == driver::Stage::Source) return kExitInput;
  std::string error = r.error;
  if (c.module && !passes.empty()) error = ir::run_passes(*c.module, passes);
  if (!c.module || !error.empty()) {
    std::cerr << "error: " << error << "\n";
    return kExitInput;
  }
  if (gradient && !no_entry.empty()) {
    std::cerr << file << ": error: --gradient needs the kernel: " << no_entry << "\n";
    return kExitInput;
  }
  if (gradient) {  // what the meshers evaluate for normals
    std::unique_ptr<ir::Module> g = ir::gradient_module(*c.module);
    if (!g) {
      std::cerr << file
                << ": error: this kernel has no gradient: after optimisation it is not one block of "
                   "pure operations (a loop, a call, a global or an array is left), or it uses noise of x, y or z; "
                   "the meshers take differences of it instead\n";
      return kExitInput;
    }
    c.module = std::move(g);
  }
  if (llvm) {
    const backends::LlvmModule* lm = backends::llvm_module(&error);
    std::string text = lm ? lm->kernel_text(*c.module, {}, false, error) : "";
    if (text.empty()) {
      std::cerr << "error: " << error << "\n";
      return lm ? kExitInput : kExitUsage;
    }
    std::cout << text;
    return kExitOk;
  }
  std::cout << ir::print(*c.module);
  return kExitOk;
}

std::string backend_listing(const std::string& name, const ir::Module& m, const backends::Kernel* kernel,
                            const backends::Budgets& budgets, std::string& error) {
  if (auto* vk = dynamic_cast<const vm::VmKernel*>(kernel)) return vm::disassemble(vk->program());
  if (name == "vm" || name == "auto") {  // a kernel the row split wraps: the whole function's code
    vm::VmProgram p;
    return vm::compile_program(m, p, error) ? vm::disassemble(p) : "";
  }
#if defined(FS_HAVE_SSE)
  if (name == "sse") {
    std::string text;
    double bound = 0;
    uint32_t lanes = 4;
    if (sse::generate(m, budgets, error, &text, nullptr, &bound, false, &lanes).empty()) return "";
    text = "; " + std::to_string(lanes) + " points per iteration (" + (lanes == 8 ? "ymm" : "xmm") + " registers)\n" +
        text;
    if (bound > 0)  // the code that runs a batch whose inputs are all in range
      text = "; inputs finite with |x| <= " + std::to_string(static_cast<int>(bound)) +
          " (other batches run the general code)\n" + text;
    return text;
  }
#endif
  if (name == "llvm") {
    const backends::LlvmModule* lm = backends::llvm_module(&error);
    return lm ? lm->kernel_text(m, budgets, true, error) : "";
  }
  error = "no listing for backend '" + name + "'";
  return "";
}

int cmd_emit_asm(const Options& given, const std::string& file, const std::string& entry) {
  Options o = given;  // auto (the default) lists the VM bytecode: the code every job starts on
  if (o.backend.empty() || o.backend == "auto") o.backend = "vm";
  const std::string& name = o.backend;
  if (!backends::make_backend(name)) {  // a usage error before any compile
    std::cerr << "error: " << backends::missing_backend_message(name) << "\n";
    return kExitUsage;
  }
  Compiled c;
  if (int rc = compile_file(file, entry, o, c); rc != kExitOk) return rc;
  std::string error, text = backend_listing(name, *c.module, c.kernel.get(), o.budgets, error);
  if (text.empty()) {
    std::cerr << "error: " << error << "\n";
    return kExitInput;
  }
  std::cout << text;
  return kExitOk;
}

}  // namespace fscript::cli
