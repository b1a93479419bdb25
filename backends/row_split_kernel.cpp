// Grid rows (backends/row_split_kernel.h): the row-split kernel.
#include "backends/row_split_kernel.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <mutex>
#include <vector>

#include "ir/passes/row_split.h"

namespace fscript::backends {
namespace {

// Smaller jobs go through the full kernel: the prologue's own call (a chunk of its own on the
// VM, however few rows) would cost more than the split saves.
constexpr size_t kMinRowPoints = 256, kMinRowLength = 4;

struct Totals {
  std::atomic<uint64_t> kernels{0}, rows{0}, points{0}, hoisted{0}, per_point{0}, row_values{0};
};
Totals& totals() {
  static Totals t;
  return t;
}

class RowSplitKernel : public Kernel {
 public:
  RowSplitKernel(std::unique_ptr<Kernel> full, std::string backend, ir::RowSplit split, const Budgets& budgets)
      : full_(std::move(full)), backend_(std::move(backend)), split_(std::move(split)), budgets_(budgets) {}

  size_t num_inputs() const override { return full_->num_inputs(); }
  size_t num_outputs() const override { return full_->num_outputs(); }
  bool eval_batch(const float* const* inputs, float* const* outputs, size_t n, RuntimeError& err) const override {
    return full_->eval_batch(inputs, outputs, n, err);
  }
  bool eval(const float* inputs, float* outputs, RuntimeError& err) const override {
    return full_->eval(inputs, outputs, err);
  }
  // A caller with a grid ahead (the polygonizer) gets the body compiled first: it takes the rows.
  void expect_points(uint64_t points) const override {
    if (parts()) body_->expect_points(points);
    full_->expect_points(points);
    announced_ = points;  // the prologue's rows, once a call says how long a row is
  }

  bool eval_rows(const float* first, size_t count, const float* const* rest, size_t rows, float* const* outputs,
                 RuntimeError& err) const override {
    if (count * rows < kMinRowPoints || count < kMinRowLength || !parts())
      return expand_rows(*full_, first, count, rest, rows, outputs, err);
    totals().rows += rows, totals().points += rows * count;
    // Unannounced, a tiered prologue stayed on the VM for the whole job (the gyroid mesh's 617,000
    // rows: most of what --backend auto lost against sse).
    if (uint64_t a = announced_.exchange(0)) prologue_->expect_points(a / count);
    // The prologue over the rows (its first input is not read: any value), then the body in batches.
    size_t k = split_.row_values;
    std::vector<float> unused(rows, 0.0f);
    std::vector<const float*> pin(num_inputs());
    pin[0] = unused.data();
    for (size_t i = 1; i < pin.size(); ++i) pin[i] = rest[i - 1];
    std::vector<std::vector<float>> row_values(k, std::vector<float>(rows));
    std::vector<float*> pout(k);
    for (size_t i = 0; i < k; ++i) pout[i] = row_values[i].data();
    if (!prologue_->eval_batch(pin.data(), pout.data(), rows, err)) return false;
    std::vector<const float*> values(k);
    for (size_t i = 0; i < k; ++i) values[i] = row_values[i].data();
    return body_->eval_rows(first, count, values.data(), rows, outputs, err);  // row parameters: native rows
  }

 private:
  // The split's kernels, compiled once; false (rows then go through the full kernel) if that failed.
  bool parts() const {
    std::call_once(once_, [this] {
      std::string error;
      auto be = make_backend(backend_);
      if (!be) return;
      auto pro = be->compile(*split_.prologue, budgets_, error);
      auto body = pro ? be->compile(*split_.body, budgets_, error) : nullptr;
      if (!body) return;
      prologue_ = std::move(pro), body_ = std::move(body);
    });
    return body_ != nullptr;
  }

  std::unique_ptr<Kernel> full_;
  std::string backend_;
  ir::RowSplit split_;
  Budgets budgets_;
  mutable std::once_flag once_;
  mutable std::unique_ptr<Kernel> prologue_, body_;
  mutable std::atomic<uint64_t> announced_{0};
};

}  // namespace

bool row_split_enabled() {
  static const bool on = [] {
    const char* v = std::getenv("FSCRIPT_ROW_SPLIT");
    return !(v && v[0] == '0' && !v[1]);
  }();
  return on;
}

std::unique_ptr<Kernel> with_row_split(std::unique_ptr<Kernel> full, const std::string& backend, const ir::Module& m,
                                       const Budgets& budgets) {
  ir::RowSplit split;
  if (!full || !row_split_enabled() || !ir::split_rows(m, split)) return full;
  Totals& t = totals();
  ++t.kernels;
  t.hoisted = split.hoisted, t.per_point = split.per_point, t.row_values = split.row_values;
  return std::make_unique<RowSplitKernel>(std::move(full), backend, std::move(split), budgets);
}

RowStats row_stats() {
  const Totals& t = totals();
  RowStats s;
  s.kernels = t.kernels, s.rows = t.rows, s.points = t.points;
  s.hoisted = t.hoisted, s.per_point = t.per_point, s.row_values = t.row_values;
  return s;
}

}  // namespace fscript::backends
