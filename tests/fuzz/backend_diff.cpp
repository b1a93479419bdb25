// Fuzz target: differential testing of the backends. The bytes become a well-formed FScript
// program (program_gen.h) that runs on the VM, the SSE backend and the LLVM backend over a batch
// that includes NaN, infinities, signed zeros, denormals and huge values. The backends must agree
// bit for bit (NaN payloads aside) and fail on the same points with the same message
// (docs/language.md, "Accuracy"; docs/reliability.md). Without transcendentals, the optimised
// and the unoptimised module must agree as well, zero signs included (constant folding and the
// identities are exact there; x + 0 -> x was not, for x = -0: found by this target). The
// one-point call is compared too, on every fifth point.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "backends/backend.h"
#include "engine/driver/driver.h"
#include "tests/fuzz/fuzz_support.h"
#include "tests/fuzz/program_gen.h"

using namespace fscript;

namespace {

const float kInf = INFINITY, kNan = NAN;
const float kValues[] = {0.0f,  -0.0f,   1.0f,   -1.0f,       0.5f,    -2.5f,       3.0f,      kInf,
                         -kInf, kNan,    1e-40f, -1e-45f,     3.4e38f, -3e38f,      1e30f,     0.1f,
                         7.25f, -100.0f, 2.0f,   0.49999997f, 1e-7f,   16777216.0f, 6.2831855f};
constexpr size_t kPoints = 67;  // no multiple of any vector width: the padded tails run too
// Ordinary inputs (finite, small): batches of these keep what a backend's fast code guesses of
// its inputs (a bound, no NaN), so that code runs on groups of differing lanes, not only on the
// one-point calls' equal lanes.
const float kOrdinary[] = {0.5f, -1.25f, 2.0f, 0.1f, -3.5f, 7.0f, 0.75f, -0.3f, 1.5f, 0.0f, -0.0f, 4.25f, -9.0f};

struct Run {
  bool ok = false;
  std::string error;
  std::vector<float> out;  // [output][point]
};

using Columns = std::vector<std::vector<float>>;

Run run_batch(const backends::Kernel& k, const Columns& cols, size_t first, size_t n) {
  std::vector<const float*> in;
  for (const auto& c : cols) in.push_back(c.data() + first);
  Run r;
  r.out.assign(k.num_outputs() * n, 0.0f);
  std::vector<float*> outs;
  for (size_t o = 0; o < k.num_outputs(); ++o) outs.push_back(r.out.data() + o * n);
  backends::RuntimeError err;
  r.ok = k.eval_batch(in.data(), outs.data(), n, err);
  r.error = err.message;
  return r;
}

std::string describe(const Columns& cols, size_t p) {
  std::string s = "point " + std::to_string(p) + " (";
  for (size_t i = 0; i < cols.size(); ++i) s += (i ? ", " : "") + std::to_string(cols[i][p]);
  return s + ")";
}

// Point by point (a batch stops at its first failing point, and which one that is depends on the
// vector width): the same status, the same message, the same bits.
void compare(const std::string& name, const backends::Kernel& want, const backends::Kernel& got, const Columns& cols,
             const std::string& text) {
  Run a = run_batch(want, cols, 0, kPoints), b = run_batch(got, cols, 0, kPoints);
  if (a.ok && b.ok) {
    for (size_t i = 0; i < a.out.size(); ++i)
      if (!fuzz::same(a.out[i], b.out[i]))
        fuzz::finding(name + " differs at " + describe(cols, i % kPoints) + ": " + std::to_string(a.out[i]) + " vs " +
                          std::to_string(b.out[i]),
                      text);
    return;
  }
  for (size_t p = 0; p < kPoints; ++p) {
    Run x = run_batch(want, cols, p, 1), y = run_batch(got, cols, p, 1);
    if (x.ok != y.ok || x.error != y.error)
      fuzz::finding(name + " fails differently at " + describe(cols, p) + ": '" + x.error + "' vs '" + y.error + "'",
                    text);
    for (size_t i = 0; x.ok && i < x.out.size(); ++i)
      if (!fuzz::same(x.out[i], y.out[i])) fuzz::finding(name + " differs at " + describe(cols, p), text);
  }
}

// The one-point call (Kernel::eval: the REPL, root finding) is code of its own on the JIT
// backends (one lane, equal lanes): every fifth point against `want`'s batch of that point alone.
void compare_points(const std::string& name, const backends::Kernel& want, const backends::Kernel& got,
                    const Columns& cols, const std::string& text) {
  for (size_t p = 0; p < kPoints; p += 5) {
    Run x = run_batch(want, cols, p, 1);
    std::vector<float> in(cols.size()), out(got.num_outputs(), 0.0f);
    for (size_t c = 0; c < cols.size(); ++c) in[c] = cols[c][p];
    backends::RuntimeError err;
    bool ok = got.eval(in.data(), out.data(), err);
    if (x.ok != ok || x.error != err.message)
      fuzz::finding(name + " one point fails differently at " + describe(cols, p) + ": '" + x.error + "' vs '" +
                        err.message + "'",
                    text);
    for (size_t i = 0; ok && x.ok && i < out.size(); ++i)
      if (!fuzz::same(x.out[i], out[i]))
        fuzz::finding(name + " one point differs at " + describe(cols, p) + ": " + std::to_string(x.out[i]) + " vs " +
                          std::to_string(out[i]),
                      text);
  }
}

std::unique_ptr<ir::Module> build(const std::string& text, bool optimize, std::unique_ptr<backends::Kernel>& vm) {
  driver::CompileOptions o = fuzz::compile_options(optimize);
  frontend::DiagnosticSink diag;
  driver::Compiled c;
  driver::Outcome r =
      driver::compile(std::make_unique<frontend::SourceFile>("gen.fs", text), driver::default_entry(), o, diag, c);
  if (!r.ok())
    fuzz::finding("a generated program does not compile: " + r.error + "\n" + frontend::render_all(diag), text);
  vm = std::move(c.kernel);
  return std::move(c.module);
}

}  // namespace

// straight_diff.cpp defines it true: the same target on straight-line programs.
#ifndef FS_DIFF_STRAIGHT_LINE
#define FS_DIFF_STRAIGHT_LINE false
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  fuzz::GenOptions go;
  go.straight_line = FS_DIFF_STRAIGHT_LINE;
  fuzz::GeneratedProgram prog = fuzz::generate_program(in, go);
  if (std::getenv("FS_FUZZ_SHOW")) std::fprintf(stderr, "---- program ----\n%s\n---- end ----\n", prog.text.c_str());
  std::unique_ptr<backends::Kernel> vm;
  auto module = build(prog.text, true, vm);
  Columns cols(vm->num_inputs(), std::vector<float>(kPoints));
  for (size_t c = 0; c < cols.size(); ++c)
    for (size_t p = 0; p < kPoints; ++p) cols[c][p] = kValues[(p * (2 * c + 1) + c * 5) % std::size(kValues)];
  // Every backend this build has: one that cannot start (the llvm module not built or not
  // loadable) is a finding, or a campaign would compare the VM with the SSE code alone unseen.
  Columns ordinary(cols.size(), std::vector<float>(kPoints));
  for (size_t c = 0; c < cols.size(); ++c)
    for (size_t p = 0; p < kPoints; ++p) ordinary[c][p] = kOrdinary[(p * (2 * c + 3) + c) % std::size(kOrdinary)];
  compare_points("vm batch against vm", *vm, *vm, cols, prog.text);
  for (const std::string& name : backends::available_backends()) {
    if (name == "vm") continue;
    auto backend = backends::make_backend(name);
    if (!backend) fuzz::finding(backends::missing_backend_message(name), prog.text);
    std::string error;
    auto k = backend->compile(*module, fuzz::small_budgets(), error);
    if (!k) fuzz::finding(name + " cannot compile: " + error, prog.text);
    compare("vm against " + name, *vm, *k, cols, prog.text);
    compare("vm against " + name + " (ordinary inputs)", *vm, *k, ordinary, prog.text);
    compare_points("vm batch against " + name, *vm, *k, cols, prog.text);
  }
  if (!prog.transcendental) {
    std::unique_ptr<backends::Kernel> plain;
    build(prog.text, false, plain);
    compare("optimised against unoptimised", *vm, *plain, cols, prog.text);
  }
  return 0;
}
