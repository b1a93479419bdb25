// The default Kernel::eval_rows: a row job's points expanded into batches (backends/backend.h).
// Apart from the row split (row_split_kernel.cpp) so that code with no use for the registry (the llvm
// module) does not pull it in.
#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <memory>
#include <vector>

#include "backends/row_split_kernel.h"

namespace fscript::backends {
namespace {

constexpr size_t kRowBatch = 4096;  // points per batch a row job is cut into: in L1/L2, big for the VM
// `count` copies of v. Four at a time, the last four overlapping the ones before: the mesher's
// rows are 17 points or fewer, where a plain loop's vector body and its remainder cost more than
// the stores (a twentieth of the VM's mesh).
void fill_row(float* row, size_t count, float v) {
#if defined(__SSE2__)
  if (count >= 4) {
    __m128 b = _mm_set1_ps(v);
    for (size_t i = 0; i + 4 <= count; i += 4) _mm_storeu_ps(row + i, b);
    _mm_storeu_ps(row + count - 4, b);
    return;
  }
#endif
  for (size_t i = 0; i < count; ++i) row[i] = v;
}

// Rows [r0, r0 + n) of a row job as plain points: the first input tiled (once per call: every batch
// of a call has the same x and at most the first batch's rows), the others repeated. Buffers per
// thread, grown and never cleared: the fill writes every point it hands on.
struct Expanded {
  std::vector<std::unique_ptr<float[]>> cols;
  std::vector<size_t> size;
  std::vector<const float*> in;

  float* column(size_t k, size_t points) {
    if (cols.size() <= k) cols.resize(k + 1), size.resize(k + 1, 0);
    if (size[k] < points) cols[k].reset(new float[points]), size[k] = points;
    return cols[k].get();
  }
  void fill(const float* first, size_t count, const float* const* rest, size_t num_rest, size_t r0, size_t n,
            bool tile) {
    in.resize(1 + num_rest);
    float* x = column(0, n * count);
    in[0] = x;
    if (count == 1) {  // one point a row (a brick's last column): the rows' own arrays are the points
      if (tile) std::fill_n(x, n, first[0]);
      for (size_t k = 0; k < num_rest; ++k) in[1 + k] = rest[k] + r0;
      return;
    }
    if (tile)
      for (size_t r = 0; r < n; ++r) std::copy_n(first, count, x + r * count);
    for (size_t k = 0; k < num_rest; ++k) {
      float* c = column(1 + k, n * count);
      for (size_t r = 0; r < n; ++r) fill_row(c + r * count, count, rest[k][r0 + r]);
      in[1 + k] = c;
    }
  }
};

size_t rows_per_batch(size_t count) { return std::max<size_t>(1, kRowBatch / std::max<size_t>(count, 1)); }

}  // namespace

bool expand_rows(const Kernel& k, const float* first, size_t count, const float* const* rest, size_t rows,
                 float* const* outputs, RuntimeError& err) {
  thread_local Expanded e;
  std::vector<float*> out(k.num_outputs());
  for (size_t r0 = 0, step = rows_per_batch(count); r0 < rows; r0 += step) {
    size_t n = std::min(step, rows - r0);
    e.fill(first, count, rest, k.num_inputs() - 1, r0, n, r0 == 0);
    for (size_t o = 0; o < out.size(); ++o) out[o] = outputs[o] + r0 * count;
    if (!k.eval_batch(e.in.data(), out.data(), n * count, err)) return false;
  }
  return true;
}

bool Kernel::eval_rows(const float* first, size_t count, const float* const* rest, size_t rows, float* const* outputs,
                       RuntimeError& err) const {
  return expand_rows(*this, first, count, rest, rows, outputs, err);
}

}  // namespace fscript::backends
