// Fuzz target: soundness of interval evaluation (ir/interval_eval.h). The bytes become a
// straight-line FScript program and a box; every point of the box evaluated on the VM lies in the
// interval result (NaN only where the may-be-NaN bit is set), in the batched evaluator's lanes as
// well, and the tape simplified to the box gives the full kernel's bits at every point.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>

#include "backends/vm/vm_backend.h"
#include "ir/interval_eval.h"
#include "engine/driver/driver.h"
#include "tests/fuzz/fuzz_support.h"
#include "tests/fuzz/program_gen.h"

using namespace fscript;

namespace {

const float kBounds[] = {0.0f,  -0.0f,  1.0f,  -1.0f, 0.5f,   -2.5f,      3.0f,       INFINITY,    -INFINITY, 1e-40f,
                         3e38f, -3e38f, 1e30f, 0.1f,  100.0f, 1.5707964f, 3.1415927f, -6.2831855f, 1e-7f};

float bound(FuzzedDataProvider& in) {
  if (in.ConsumeBool()) return kBounds[in.ConsumeIntegralInRange<size_t>(0, std::size(kBounds) - 1)];
  float v = in.ConsumeFloatingPointInRange<float>(-1000.0f, 1000.0f);
  return std::isnan(v) ? 0.0f : v;
}

float inside(const math::Interval& box, float f) {
  if (box.lo == box.hi) return box.lo;
  // An infinite side: the ends, or a point spread over a million around 0 held inside the box (it
  // once fell outside a box [-inf, 999.97], a finding of the harness, not of the rules).
  if (std::isinf(box.lo) || std::isinf(box.hi))
    return f < 0.1f ? box.lo : f > 0.9f ? box.hi : std::fmin(std::fmax((f - 0.5f) * 1e6f, box.lo), box.hi);
  float v = box.lo + f * (box.hi - box.lo);
  return std::isfinite(v) ? std::fmin(std::fmax(v, box.lo), box.hi) : box.lo;
}

std::string describe(const std::vector<math::Interval>& box, const std::vector<float>& p) {
  std::string s = "box";
  for (const auto& b : box) s += " [" + std::to_string(b.lo) + ", " + std::to_string(b.hi) + "]";
  s += " point";
  for (float v : p) s += " " + std::to_string(v);
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  fuzz::GenOptions go;
  go.straight_line = true;
  fuzz::GeneratedProgram prog = fuzz::generate_program(in, go);
  driver::CompileOptions o = fuzz::compile_options(true);
  frontend::DiagnosticSink diag;
  driver::Compiled c;
  if (!driver::compile(std::make_unique<frontend::SourceFile>("gen.fs", prog.text), driver::default_entry(), o, diag, c)
           .ok())
    fuzz::finding("a generated program does not compile:\n" + frontend::render_all(diag), prog.text);
  const ir::Function& fn = c.module->kernel_function();
  if (!ir::interval_evaluable(fn)) return 0;  // if-conversion left control flow: runs dense, no claim
  size_t nin = c.kernel->num_inputs();
  std::vector<math::Interval> box(nin);
  for (auto& b : box) {
    float p = bound(in), q = bound(in);
    b = {std::fmin(p, q), std::fmax(p, q), false};
  }
  ir::IntervalTape tape(fn);
  ir::IntervalEval ev;
  tape.eval(box, ev);
  std::vector<ir::IntervalLanes> lanes(nin);
  for (size_t i = 0; i < nin; ++i)
    for (size_t k = 0; k < ir::kIntervalLanes; ++k) lanes[i].set(k, box[i]);
  ir::IntervalBatchEval bev;
  tape.eval_batch(lanes, bev);
  auto simplified = vm::compile_tape(tape.simplified(ev), {});
  constexpr size_t kSamples = 40;
  std::vector<std::vector<float>> cols(nin, std::vector<float>(kSamples));
  for (size_t p = 0; p < kSamples; ++p)
    for (size_t i = 0; i < nin; ++i)
      cols[i][p] = p < 16 ? ((p >> i) & 1 ? box[i].hi : box[i].lo) : inside(box[i], in.ConsumeProbability<float>());
  std::vector<const float*> ins;
  for (auto& col : cols) ins.push_back(col.data());
  size_t nout = c.kernel->num_outputs();
  std::vector<std::vector<float>> full(nout, std::vector<float>(kSamples)), simple = full;
  std::vector<float*> fo, so;
  for (size_t k = 0; k < nout; ++k) fo.push_back(full[k].data()), so.push_back(simple[k].data());
  backends::RuntimeError err;
  if (!c.kernel->eval_batch(ins.data(), fo.data(), kSamples, err))
    fuzz::finding("straight-line code failed: " + err.message, prog.text);
  if (!simplified->eval_batch(ins.data(), so.data(), kSamples, err))
    fuzz::finding("the simplified tape failed", prog.text);
  for (size_t p = 0; p < kSamples; ++p) {
    std::vector<float> point;
    for (size_t i = 0; i < nin; ++i) point.push_back(cols[i][p]);
    for (size_t k = 0; k < nout; ++k) {
      float v = full[k][p];
      if (!ev.outputs[k].contains(v))
        fuzz::finding("output " + std::to_string(k) + " = " + std::to_string(v) + " outside [" +
                          std::to_string(ev.outputs[k].lo) + ", " + std::to_string(ev.outputs[k].hi) + "] nan " +
                          std::to_string(ev.outputs[k].nan) + ", " + describe(box, point),
                      prog.text);
      if (!bev.output(k, p % ir::kIntervalLanes).contains(v))
        fuzz::finding("the batched interval evaluator misses " + std::to_string(v) + ", " + describe(box, point),
                      prog.text);
      if (!fuzz::same(v, simple[k][p]))
        fuzz::finding("the simplified tape gives " + std::to_string(simple[k][p]) + " for " + std::to_string(v) + ", " +
                          describe(box, point),
                      prog.text);
    }
  }
  return 0;
}
